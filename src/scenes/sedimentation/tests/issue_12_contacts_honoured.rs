//! Issue 12, data loss and hangs, item 7 (moved from `tests/regression/`): `[contacts]` on a sedimentation scenario was accepted,
//! listed in `run.toml`, and ignored: the cylinder's grain contacts were frictionless with
//! restitution 0 whatever it said, so a run with `friction = 1, restitution = 1` gave the same
//! results, bit for bit, as one without the table. The cylinder's contact solve now takes
//! `friction` and `restitution` from `[contacts]` (defaults as before: 0 and 0).

use super::prepare;
use crate::contact::RestitutionLaw;
use crate::scenes::sedimentation::{setup, simulate, ContactStats, GrainContacts, State};
use std::path::Path;

fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().expect("temp dir")
}

/// A short run of sample 1 (5 000 grains, 120 s: hundreds of close pairs), with an optional
/// `[contacts]` table written beside the scenario.
fn run(contacts: Option<&str>) -> (State, GrainContacts) {
    let dir = tmp();
    let src = std::fs::read_to_string("scenarios/sedimentation_sample1.toml").unwrap();
    let data = std::fs::canonicalize("data/sedimentation_samples.csv").unwrap();
    let mut text = src.replace(
        "csv = \"../data/sedimentation_samples.csv\"",
        &format!("csv = {:?}", data.display().to_string()),
    );
    if let Some(c) = contacts {
        text.push_str(&format!("\n[contacts]\n{c}\n"));
    }
    let path = dir.path().join("s.toml");
    std::fs::write(&path, text).unwrap();
    let ov = vec![
        "sample.particles=5000".to_string(),
        "time.end_s=120.0".to_string(),
        "sample.record_times_s=[120.0]".to_string(),
        "sample.snapshot_times_s=[]".to_string(),
        "sample.contacts=true".to_string(),
    ];
    let p = prepare(Path::new(&path), None, &ov).unwrap();
    let su = setup(&p).unwrap();
    let st = simulate(&su, State::initial(&su), &[], &mut ());
    assert!(st.fault.is_none() && !st.interrupted);
    (st, su.contacts)
}

#[test]
fn contacts_table_sets_the_friction_and_restitution_of_the_cylinders_grains() {
    let (plain, c0) = run(None);
    assert_eq!(c0, GrainContacts::default());
    assert_eq!(c0.friction, 0.0);
    assert_eq!(c0.restitution, RestitutionLaw::constant(0.0));
    // A table with the defaults changes nothing, bit for bit (the wall time aside).
    let (same, _) = run(Some("friction = 0.0\nrestitution = 0.0"));
    let no_wall = |c: ContactStats| ContactStats { wall_s: 0.0, ..c };
    assert_eq!(no_wall(same.contacts), no_wall(plain.contacts));
    assert!(!plain.x_m.is_empty(), "the contacts moved no grain across");
    assert!(same.x_m == plain.x_m && same.y_m == plain.y_m);
    // Rough, elastic grains: the scenario's values reach the contact solve, and the run differs.
    let (rough, c1) = run(Some("friction = 1.0\nrestitution = 1.0"));
    assert_eq!(c1.friction, 1.0);
    assert_eq!(c1.restitution, RestitutionLaw::constant(1.0));
    assert!(plain.contacts.pairs > 100, "{:?}", plain.contacts);
    let moved = (0..plain.len())
        .filter(|&i| rough.x_m[i] != plain.x_m[i] || rough.y_m[i] != plain.y_m[i])
        .count();
    println!(
        "{moved} grains end elsewhere; contacts {:?} against {:?}",
        rough.contacts, plain.contacts
    );
    assert!(
        moved > 0,
        "[contacts] friction = 1, restitution = 1 changed nothing"
    );
}
