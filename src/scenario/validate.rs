//! Validation of a parsed scenario: which tables its kind uses, then each table's checks (which
//! sit next to their structs in [`super::schema`]), then the rules between tables. Each failure
//! names the file, the key and the allowed range.

use super::check::Check;
use super::schema::*;
use super::spec::*;
use crate::error::BadInput;
use std::path::Path;

pub use super::check::MAX_STEPS;

/// The kinds that use each optional top-level table. A table given to any other kind is refused
/// (it would be ignored). The tables every kind uses (`fluid`, `drag`, `time`) and the plain
/// top-level keys are not listed.
const TABLE_KINDS: &[(&str, &[Kind])] = {
    use Kind::*;
    &[
        (
            "container",
            &[FreeSettling, Drop, FunnelPour, Sedimentation],
        ),
        ("release", &[FreeSettling, Drop]),
        (
            "spheres",
            &[FreeSettling, Drop, RestitutionDrop, FunnelPour],
        ),
        (
            "spheres_csv",
            &[FreeSettling, Drop, RestitutionDrop, FunnelPour],
        ),
        ("measure", &[FreeSettling, Drop]),
        ("record", &[FreeSettling, Drop, FunnelPour]),
        ("sweep", &[FreeSettling, Drop, FunnelPour]),
        (
            "contacts",
            &[RestitutionDrop, TiltFriction, FunnelPour, Sedimentation],
        ),
        ("restitution_drop", &[RestitutionDrop]),
        ("tilt", &[TiltFriction]),
        ("funnel", &[FunnelPour]),
        ("repeats", &[FunnelPour]),
        ("sample", &[Sedimentation]),
        ("instruments", &[Sedimentation]),
        (
            "transient",
            &[FreeSettling, Drop, RestitutionDrop, FunnelPour],
        ),
        ("reference", &[FreeSettling]),
    ]
};

/// Whether the top-level key `key` may appear in a scenario of `kind`: the plain keys and the
/// tables every kind uses always, the tables of [`TABLE_KINDS`] for the kinds listed there.
pub fn table_used_by(key: &str, kind: Kind) -> bool {
    TABLE_KINDS
        .iter()
        .find(|(t, _)| *t == key)
        .is_none_or(|(_, kinds)| kinds.contains(&kind))
}

/// Refuses a top-level table (of `present`, the keys of the file after `--set`) that `kind`
/// does not use, naming the table and the kind and listing the tables it uses.
pub fn check_tables(kind: Kind, present: &[&str], file: &Path) -> Result<(), BadInput> {
    for key in present {
        if let Some((_, kinds)) = TABLE_KINDS.iter().find(|(t, _)| t == key) {
            if !kinds.contains(&kind) {
                let used: Vec<String> = TABLE_KINDS
                    .iter()
                    .filter(|(_, k)| k.contains(&kind))
                    .map(|(t, _)| format!("[{t}]"))
                    .collect();
                return Err(BadInput::new(
                    file,
                    Some(key),
                    format!(
                        "the [{key}] table is not used by kind = \"{}\" (allowed: [fluid], [drag], [time]{}{})",
                        kind.name(),
                        if used.is_empty() { "" } else { ", " },
                        used.join(", ")
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// Validates ranges and cross-table rules, and builds the typed parts of the scenario: the
/// spec of its kind and the rheology of its fluid.
pub fn validate(s: &Scenario, file: &Path) -> Result<(SceneSpec, RheologyModel), BadInput> {
    let c = Check { file };
    s.check_common(&c)?;
    let rheology = s.fluid.check(&c)?;
    s.drag.check(&c, &s.fluid, s.physics)?;
    s.time.check(&c)?;
    if let Some(ct) = &s.container {
        ct.check(&c, s.dimension)?;
    }
    s.release.check(&c, s)?;
    if s.kind == Kind::Drop && s.engine == EngineChoice::Rapier {
        return Err(c.err("engine", "`rapier` is not available for kind = \"drop\" yet (no contacts there): allowed `auto`, `free`"));
    }
    let scene = check_kind(&c, s)?;
    if let Some(ct) = &s.contacts {
        ct.check(&c)?;
    }
    if let Some(r) = &s.repeats {
        r.check(&c)?;
    }
    if !matches!(s.kind, Kind::TiltFriction | Kind::Sedimentation)
        && s.spheres.is_empty()
        && s.spheres_csv.is_none()
    {
        return Err(c.err(
            "spheres",
            "missing: give at least one [[spheres]] table or a [spheres_csv] file",
        ));
    }
    for (i, sp) in s.spheres.iter().enumerate() {
        sp.check(&c, &format!("spheres[{i}]"), s)?;
    }
    if let Some(m) = &s.measure {
        let h = s
            .container
            .as_ref()
            .map(|c| c.height_m)
            .unwrap_or(f64::INFINITY);
        m.check(&c, h, s.time.end_s)?;
    }
    s.record.check(&c, s.time.end_s)?;
    if let Some(t) = &s.transient {
        t.check(&c, s)?;
    }
    if let Some(sw) = &s.sweep {
        sw.check(&c, s.time.end_s)?;
    }
    Ok((scene, rheology))
}

/// The kind's own tables: present, and checked; the kind's spec built from them.
fn check_kind(c: &Check, s: &Scenario) -> Result<SceneSpec, BadInput> {
    let missing = |key: &str, what: &str| {
        c.err(
            key,
            format!("missing: kind = \"{}\" needs {what}", s.kind.name()),
        )
    };
    match s.kind {
        Kind::RestitutionDrop => {
            let rd = s.restitution_drop.as_ref().ok_or_else(|| {
                missing(
                    "restitution_drop",
                    "a [restitution_drop] table with drop_heights_m",
                )
            })?;
            let contacts = contact_scene_3d(c, s)?;
            let ball = match (s.spheres.as_slice(), &s.spheres_csv) {
                ([ball], None) => ball,
                _ => return Err(c.err(
                    "spheres",
                    "kind = \"restitution_drop\" drops one ball: give exactly one [[spheres]] table (no [spheres_csv])",
                )),
            };
            rd.check(c)?;
            Ok(SceneSpec::RestitutionDrop(RestitutionSpec {
                drop: rd.clone(),
                ball: ball.clone(),
                contacts,
            }))
        }
        Kind::TiltFriction => {
            let t = s.tilt.as_ref().ok_or_else(|| {
                missing(
                    "tilt",
                    "a [tilt] table (block_size_m, block_density_kg_m3, angles_deg, duration_s)",
                )
            })?;
            let contacts = contact_scene_3d(c, s)?;
            t.check(c, s)?;
            let block_size_m: [f64; 3] =
                t.block_size_m.as_slice().try_into().map_err(|_| {
                    c.err("tilt.block_size_m", "give the three edge lengths [x, y, z]")
                })?;
            Ok(SceneSpec::TiltFriction(TiltFrictionSpec {
                tilt: t.clone(),
                block_size_m,
                contacts,
            }))
        }
        Kind::FunnelPour => {
            let f = s
                .funnel
                .as_ref()
                .ok_or_else(|| missing("funnel", "a [funnel] table (count, geometry)"))?;
            let (height_m, diameter_m) = match &s.container {
                Some(Container {
                    height_m,
                    diameter_m: Some(d),
                    ..
                }) => (*height_m, *d),
                _ => {
                    return Err(missing(
                        "container.diameter_m",
                        "a cylindrical [container] with diameter_m",
                    ))
                }
            };
            let contacts = contact_scene_3d(c, s)?;
            f.check(c, s)?;
            Ok(SceneSpec::FunnelPour(FunnelPourSpec {
                funnel: f.clone(),
                cylinder_radius_m: 0.5 * diameter_m,
                height_m,
                contacts,
                repeats: s.repeats.clone().unwrap_or(Repeats { count: 1, seed: 0 }),
            }))
        }
        Kind::Sedimentation => sedimentation(c, s),
        Kind::FreeSettling | Kind::Drop => {
            let spec = FreeSettlingSpec {
                container: s.container.clone(),
                release: s.release.clone(),
                measure: s.measure.clone(),
            };
            Ok(if s.kind == Kind::Drop {
                SceneSpec::Drop(spec)
            } else {
                SceneSpec::FreeSettling(spec)
            })
        }
    }
}

/// The tables of kind `sedimentation`: `[sample]`, a `[container]` with its width, dimension 2,
/// `[instruments]` if given.
fn sedimentation(c: &Check, s: &Scenario) -> Result<SceneSpec, BadInput> {
    let missing = |key: &str, what: &str| {
        c.err(
            key,
            format!("missing: kind = \"sedimentation\" needs {what}"),
        )
    };
    let sm = s.sample.as_ref().ok_or_else(|| {
        missing(
            "sample",
            "a [sample] table (csv, sample, mass_kg, density_kg_m3)",
        )
    })?;
    let (h, b) = match &s.container {
        Some(Container {
            height_m,
            width_m: Some(b),
            ..
        }) => (*height_m, *b),
        _ => {
            return Err(missing(
                "container.width_m",
                "a [container] with width_m (B) and height_m (H)",
            ))
        }
    };
    if s.dimension != Dim::Two {
        return Err(c.err("dimension", "kind = \"sedimentation\" is the 2D projection of the cylinder (seed 000 §4.4): allowed 2"));
    }
    sm.check(c, s)?;
    let instruments = s.instruments.clone().unwrap_or_default();
    if s.instruments.is_some() {
        instruments.check(c, s, sm, h, b)?;
    }
    Ok(SceneSpec::Sedimentation(SedimentationSpec {
        sample: sm.clone(),
        width_m: b,
        height_m: h,
        instruments,
        contacts: s.contacts.clone(),
    }))
}

/// Checks one sphere (also used for spheres read from CSV, with `key` naming the row).
pub(crate) fn check_sphere(
    file: &Path,
    key: &str,
    sp: &SphereSpec,
    s: &Scenario,
) -> Result<(), BadInput> {
    sp.check(&Check { file }, key, s)
}

/// Kinds with contacts run in a Rapier 3D world: a [contacts] table (returned), dimension 3,
/// engine `auto` or `rapier`.
fn contact_scene_3d(c: &Check, s: &Scenario) -> Result<Contacts, BadInput> {
    let kind = s.kind.name();
    let Some(contacts) = &s.contacts else {
        return Err(c.err(
            "contacts",
            format!("missing: kind = \"{kind}\" needs a [contacts] table (restitution, friction, rolling_resistance)"),
        ));
    };
    if s.dimension != Dim::Three {
        return Err(c.err(
            "dimension",
            format!("kind = \"{kind}\" is 3D-only (Rapier 3D contacts): allowed 3"),
        ));
    }
    if s.engine == EngineChoice::Free {
        return Err(c.err(
            "engine",
            format!("kind = \"{kind}\" needs contacts: allowed `auto`, `rapier`"),
        ));
    }
    Ok(contacts.clone())
}

/// The name of a kind as written in scenario files (see [`Kind::name`]).
pub fn kind_name(k: Kind) -> &'static str {
    k.name()
}
