//! Every file a run writes is named on its kind's reference page (`docs/scenarios/<kind>.md`), so
//! a new output cannot appear undocumented (issue 13, item 7: the reference lists what each kind
//! writes). Hidden files (`.settle-run`) are settle's bookkeeping and are described in `docs/outputs.md`.

use crate::common::{settle, tmp};
use std::path::Path;

/// Whether `doc` names the output `name`: in full (`summary.csv`), or as a stem followed by
/// another extension and this one (`` `transient.csv`/`.svg` ``, `` `z_distribution.csv` and
/// `.svg` ``), or, for a folder, as `name/`.
fn documented(doc: &str, name: &str, is_dir: bool) -> bool {
    if is_dir {
        return doc.contains(&format!("`{name}/"));
    }
    if doc.contains(&format!("`{name}`")) || doc.contains(&format!("`OUT/<name>/{name}`")) {
        return true;
    }
    match name.rsplit_once('.') {
        Some((stem, ext)) => {
            let (start, other) = (format!("`{stem}."), format!("`.{ext}`"));
            doc.match_indices(&start).any(|(i, _)| {
                let after = &doc[i + start.len()..];
                let Some(close) = after.find('`') else {
                    return false;
                };
                let rest = &after[close + 1..];
                ["/", " and ", " or ", ", "]
                    .iter()
                    .any(|sep| rest.starts_with(&format!("{sep}{other}")))
            })
        }
        None => false,
    }
}

/// Runs `file` with `sets` and checks every entry of its output folder against the page of
/// `kind`.
fn check(file: &str, sets: &[&str], kind: &str) {
    let dir = tmp();
    let mut c = settle();
    c.args(["run", file, "--quiet", "--out"]).arg(dir.path());
    for s in sets {
        c.arg("--set").arg(s);
    }
    let o = c.output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let page = Path::new("docs/scenarios").join(format!("{kind}.md"));
    let doc = std::fs::read_to_string(&page).unwrap();
    let run_dir = std::fs::read_dir(dir.path())
        .unwrap()
        .flatten()
        .find(|e| e.path().is_dir())
        .expect("a run folder")
        .path();
    let mut missing = Vec::new();
    let mut n = 0;
    for e in std::fs::read_dir(&run_dir).unwrap().flatten() {
        let name = e.file_name().to_string_lossy().into_owned();
        if name.starts_with('.') {
            continue;
        }
        n += 1;
        if !documented(&doc, &name, e.path().is_dir()) {
            missing.push(name);
        }
    }
    assert!(n >= 3, "{file}: only {n} outputs");
    assert!(
        missing.is_empty(),
        "{}: {file} writes {missing:?}, which the page does not name",
        page.display()
    );
}

#[test]
fn the_reader_recognises_the_pages_phrasings() {
    let doc = "- `summary.csv`: …\n- `transient.csv`/`.svg` and `snapshots/`: …";
    assert!(documented(doc, "summary.csv", false));
    assert!(documented(doc, "transient.svg", false));
    assert!(documented(doc, "snapshots", true));
    assert!(!documented(doc, "summary.svg", false));
    assert!(!documented(doc, "profiles.csv", false));
}

#[test]
fn free_settling_outputs_are_documented() {
    check("scenarios/stokes_single.toml", &[], "free_settling");
    check("scenarios/valentik_susp1.toml", &[], "free_settling");
    check(
        "scenarios/ten_cate_e1.toml",
        &["time.end_s=0.5"],
        "free_settling",
    );
}

#[test]
fn drop_outputs_are_documented() {
    check("scenarios/paste_single_ball.toml", &[], "drop");
}

#[test]
fn contact_scene_outputs_are_documented() {
    check("scenarios/restitution_drop.toml", &[], "restitution_drop");
    check("scenarios/tilt_friction.toml", &[], "tilt_friction");
}

#[test]
fn funnel_outputs_are_documented() {
    check(
        "scenarios/paste_68_balls.toml",
        &[
            "repeats.count=1",
            "time.dt_s=1e-4",
            "time.end_s=0.05",
            "funnel.count_time_s=0.04",
        ],
        "funnel_pour",
    );
}

#[test]
fn sedimentation_outputs_are_documented() {
    check(
        "scenarios/sedimentation_sample1.toml",
        &["sample.particles=2000", "time.end_s=900"],
        "sedimentation",
    );
}

/// Every kind of [`settle::Kind`]; the match is exhaustive, so a new kind does not compile here
/// until it is listed.
fn every_kind() -> [settle::Kind; 6] {
    use settle::Kind::*;
    let all = [
        FreeSettling,
        Drop,
        RestitutionDrop,
        TiltFriction,
        FunnelPour,
        Sedimentation,
    ];
    for k in all {
        match k {
            FreeSettling | Drop | RestitutionDrop | TiltFriction | FunnelPour | Sedimentation => {}
        }
    }
    all
}

/// Every registered kind has its outputs checked above (a `check(…, "<kind>")` call), so that a
/// new kind cannot write undocumented files unnoticed.
#[test]
fn every_registered_kind_is_checked_here() {
    let this = include_str!("outputs_docs.rs");
    for k in every_kind() {
        assert!(
            this.contains(&format!("\"{}\",\n    );", k.name()))
                || this.contains(&format!("], \"{}\");", k.name())),
            "add a check(\"scenarios/…\", &[…], \"{}\") to tests/scenario/outputs_docs.rs",
            k.name()
        );
    }
}
