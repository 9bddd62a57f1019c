//! The registry of scene kinds: one [`KindInfo`] per kind in [`KINDS`], the one place that
//! maps a kind to its name, the tables it reads, the typed spec built from them, its scene
//! folder, its example scenario, its outputs and its reference page. Validation, the run
//! record, the engine choice, sweeps and the docs tests all read it; the scenes dispatch on
//! the [`SceneSpec`] it builds (`crate::scenes::run_scene`).
//!
//! Adding a kind: `CONTRIBUTING.md`, "Add a scene kind"; `src/scenario/tests/registry.rs` fails
//! when a registered kind lacks one of its pieces.

use super::check::Check;
use super::schema::{
    free_settling, funnel_pour, restitution_drop, sedimentation, tilt_friction, Engine,
    EngineChoice, Entry, FreeSettlingSpec, FunnelPourSpec, Kind, RestitutionSpec, Scenario,
    SedimentationSpec, TiltFrictionSpec,
};
use crate::error::BadInput;

/// One spec per kind of scene: the tables the kind needs, present and checked.
// One value per scenario file: the size of the largest variant does not matter.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, PartialEq)]
pub enum SceneSpec {
    /// Kinds `free_settling` and `drop` ([`FreeSettlingSpec::entry`] tells them apart): spheres
    /// released submerged, or dropped through air into the fluid.
    FreeSettling(FreeSettlingSpec),
    /// Kind `restitution_drop`.
    RestitutionDrop(RestitutionSpec),
    /// Kind `tilt_friction`.
    TiltFriction(TiltFrictionSpec),
    /// Kind `funnel_pour`.
    FunnelPour(FunnelPourSpec),
    /// Kind `sedimentation`.
    Sedimentation(SedimentationSpec),
}

/// What the code knows about one kind of scene.
#[derive(Clone, Copy, Debug)]
// `folder`, `example` and `outputs` are read by the registry's test (scenario::tests::registry),
// which checks that every kind has them.
#[cfg_attr(not(test), allow(dead_code))]
pub struct KindInfo {
    /// The kind.
    pub kind: Kind,
    /// Its name in scenario files (`kind = "…"`, as serde reads it), and the stem of its
    /// reference page `docs/scenarios/<name>.md`.
    pub name: &'static str,
    /// Its scene's folder under `src/scenes/`: the kind's name, except for `drop`, a mode of
    /// `free_settling` ([`super::Entry::Drop`]).
    pub folder: &'static str,
    /// The optional top-level tables it reads (a table not listed for a kind is refused; the
    /// tables every kind reads, `[fluid]`, `[drag]`, `[time]`, are not listed), in the order
    /// the error message lists them.
    pub tables: &'static [&'static str],
    /// Needs spheres: at least one `[[spheres]]` table or a `[spheres_csv]` file.
    pub needs_spheres: bool,
    /// Its bodies touch: `engine = "auto"` resolves to Rapier.
    pub rapier: bool,
    /// `settle sweep` can run it (`crate::sweep::targets`).
    pub sweepable: bool,
    /// Its example scenario, a file of `scenarios/`.
    pub example: &'static str,
    /// Files every run of the kind writes (besides `run.toml` and `report.html`), each named on
    /// its reference page.
    pub outputs: &'static [&'static str],
    /// Its main chart, a chart file every run writes (the Python package's `Result.plot()`
    /// draws it by default).
    pub main_chart: &'static str,
    /// Builds the kind's spec from a scenario whose common tables were checked.
    pub(crate) spec: fn(&Check, &Scenario) -> Result<SceneSpec, BadInput>,
}

/// Every kind, in the order of [`Kind`].
pub const KINDS: &[KindInfo] = &[
    KindInfo {
        kind: Kind::FreeSettling,
        name: "free_settling",
        folder: "free_settling",
        tables: &[
            "container",
            "release",
            "spheres",
            "spheres_csv",
            "measure",
            "record",
            "sweep",
            "transient",
            "reference",
        ],
        needs_spheres: true,
        rapier: false,
        sweepable: true,
        example: "stokes_single.toml",
        outputs: &["summary.csv", "timeseries.csv", "velocity.svg"],
        main_chart: "velocity.svg",
        spec: |c, s| Ok(SceneSpec::FreeSettling(free_settling::free_settling(c, s)?)),
    },
    KindInfo {
        kind: Kind::Drop,
        name: "drop",
        folder: "free_settling",
        tables: &[
            "container",
            "release",
            "spheres",
            "spheres_csv",
            "measure",
            "record",
            "sweep",
            "transient",
        ],
        needs_spheres: true,
        rapier: false,
        sweepable: true,
        example: "paste_single_ball.toml",
        outputs: &["summary.csv", "timeseries.csv", "settling_distance.svg"],
        main_chart: "settling_distance.svg",
        spec: |c, s| Ok(SceneSpec::FreeSettling(free_settling::drop(c, s)?)),
    },
    KindInfo {
        kind: Kind::RestitutionDrop,
        name: "restitution_drop",
        folder: "restitution_drop",
        tables: &[
            "spheres",
            "spheres_csv",
            "contacts",
            "restitution_drop",
            "transient",
        ],
        needs_spheres: true,
        rapier: true,
        sweepable: false,
        example: "restitution_drop.toml",
        outputs: &["summary.csv", "fit.csv", "rebound_height.svg"],
        main_chart: "rebound_height.svg",
        spec: |c, s| Ok(SceneSpec::RestitutionDrop(restitution_drop::spec(c, s)?)),
    },
    KindInfo {
        kind: Kind::TiltFriction,
        name: "tilt_friction",
        folder: "tilt_friction",
        tables: &["contacts", "tilt"],
        needs_spheres: false,
        rapier: true,
        sweepable: false,
        example: "tilt_friction.toml",
        outputs: &["summary.csv", "threshold.csv", "tilt_displacement.svg"],
        main_chart: "tilt_displacement.svg",
        spec: |c, s| Ok(SceneSpec::TiltFriction(tilt_friction::spec(c, s)?)),
    },
    KindInfo {
        kind: Kind::FunnelPour,
        name: "funnel_pour",
        folder: "funnel_pour",
        tables: &[
            "container",
            "spheres",
            "spheres_csv",
            "record",
            "sweep",
            "contacts",
            "funnel",
            "repeats",
            "transient",
        ],
        needs_spheres: true,
        rapier: true,
        sweepable: true,
        example: "paste_68_balls.toml",
        outputs: &[
            "balls.csv",
            "counts.csv",
            "presence.csv",
            "z_distribution.csv",
        ],
        main_chart: "z_distribution.svg",
        spec: |c, s| Ok(SceneSpec::FunnelPour(funnel_pour::spec(c, s)?)),
    },
    KindInfo {
        kind: Kind::Sedimentation,
        name: "sedimentation",
        folder: "sedimentation",
        tables: &["container", "contacts", "sample", "instruments"],
        needs_spheres: false,
        rapier: false,
        sweepable: false,
        example: "sedimentation_sample1.toml",
        outputs: &[
            "summary.csv",
            "readings.csv",
            "granulometry.csv",
            "cylinder.csv",
            "instruments.csv",
        ],
        main_chart: "granulometry.svg",
        spec: |c, s| Ok(SceneSpec::Sedimentation(sedimentation::spec(c, s)?)),
    },
];

/// The registry entry of `kind`.
pub fn info(kind: Kind) -> &'static KindInfo {
    // Every variant of `Kind` has an entry (src/scenario/tests/registry.rs); the first entry stands
    // in for none, which cannot happen.
    KINDS.iter().find(|k| k.kind == kind).unwrap_or(&KINDS[0])
}

/// The names of the kinds `settle sweep` can run.
pub fn sweepable_names() -> Vec<&'static str> {
    KINDS
        .iter()
        .filter(|k| k.sweepable)
        .map(|k| k.name)
        .collect()
}

// The kind's name and the engine it runs on are read from the registry, so they are defined
// here, beside it (the schema below does not read the registry).
impl Scenario {
    /// Which engine the scenario runs on: `engine = "rapier"` always gives Rapier; `auto` (and
    /// `free`) give the free integrator for the kinds without contacts (free settling, drop,
    /// sedimentation, whose grain contacts run in their own solve) and Rapier for the contact
    /// kinds (restitution drop, tilt, funnel pour).
    pub fn engine(&self) -> Engine {
        if self.engine == EngineChoice::Rapier || info(self.kind).rapier {
            Engine::Rapier
        } else {
            Engine::Free
        }
    }
}

impl Kind {
    /// The name of the kind as written in scenario files (`free_settling`, …).
    pub fn name(self) -> &'static str {
        info(self).name
    }
}

impl SceneSpec {
    /// The kind's name as written in scenario files.
    pub fn kind_name(&self) -> &'static str {
        self.kind().name()
    }

    /// The kind of the scenario this spec was built from.
    pub fn kind(&self) -> Kind {
        match self {
            SceneSpec::FreeSettling(f) => match f.entry {
                Entry::Submerged => Kind::FreeSettling,
                Entry::Drop => Kind::Drop,
            },
            SceneSpec::RestitutionDrop(_) => Kind::RestitutionDrop,
            SceneSpec::TiltFriction(_) => Kind::TiltFriction,
            SceneSpec::FunnelPour(_) => Kind::FunnelPour,
            SceneSpec::Sedimentation(_) => Kind::Sedimentation,
        }
    }

    #[cfg_attr(not(test), allow(dead_code))] // read by the unit tests
    /// The spec of a `funnel_pour` scenario (None for another kind).
    pub fn funnel_pour(&self) -> Option<&FunnelPourSpec> {
        match self {
            SceneSpec::FunnelPour(f) => Some(f),
            _ => None,
        }
    }

    #[cfg_attr(not(test), allow(dead_code))] // read by the unit tests
    /// The spec of a `restitution_drop` scenario (None for another kind).
    pub fn restitution_drop(&self) -> Option<&RestitutionSpec> {
        match self {
            SceneSpec::RestitutionDrop(r) => Some(r),
            _ => None,
        }
    }

    #[cfg_attr(not(test), allow(dead_code))] // read by the unit tests
    /// The spec of a `tilt_friction` scenario (None for another kind).
    pub fn tilt_friction(&self) -> Option<&TiltFrictionSpec> {
        match self {
            SceneSpec::TiltFriction(t) => Some(t),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::BadInput;
    use crate::scenario::{Dim, Kind, Parsed, RheologyModel};
    use std::path::Path;
    use std::path::PathBuf;

    fn root() -> PathBuf {
        PathBuf::from(env!("CARGO_MANIFEST_DIR"))
    }

    fn parse(file: &str, set: &[&str]) -> Result<Parsed, BadInput> {
        let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
        crate::scenario::parse(&root().join("scenarios").join(file), &set)
    }

    #[test]
    fn every_scenario_parses_into_the_spec_of_its_kind() {
        let dir = root().join("scenarios");
        let mut n = 0;
        for e in std::fs::read_dir(&dir).unwrap() {
            let path = e.unwrap().path();
            if path.extension().is_none_or(|x| x != "toml") {
                continue;
            }
            let p = crate::scenario::parse(&path, &[]).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(p.scene.kind_name(), p.scenario.kind.name(), "{path:?}");
            assert_eq!(Some(p.rheology), p.scenario.fluid.model(), "{path:?}");
            n += 1;
        }
        assert!(n >= 5, "{n} scenarios");
    }

    #[test]
    fn sedimentation_spec_holds_its_tables() {
        let p = parse("sedimentation_sample1.toml", &[]).unwrap();
        let s = &p.scenario;
        let SceneSpec::Sedimentation(sed) = &p.scene else {
            panic!("{:?}", p.scene)
        };
        assert_eq!(Some(&sed.sample), s.sample.as_ref());
        let ct = s.container.as_ref().unwrap();
        assert_eq!((Some(sed.width_m), sed.height_m), (ct.width_m, ct.height_m));
        assert_eq!(sed.instruments, s.instruments.clone().unwrap_or_default());
        assert_eq!(sed.contacts, s.contacts);
        assert_eq!(s.dimension, Dim::Two);
    }

    #[test]
    fn funnel_spec_holds_radius_contacts_and_repeats() {
        let p = parse("paste_68_balls.toml", &["repeats.count=2"]).unwrap();
        let s = &p.scenario;
        let SceneSpec::FunnelPour(f) = &p.scene else {
            panic!("{:?}", p.scene)
        };
        let ct = s.container.as_ref().unwrap();
        assert_eq!(f.cylinder_radius_m, 0.5 * ct.diameter_m.unwrap());
        assert_eq!(f.height_m, ct.height_m);
        assert_eq!(Some(&f.contacts), s.contacts.as_ref());
        assert_eq!(f.repeats.count, 2);
        assert_eq!(Some(&f.funnel), s.funnel.as_ref());
        // Without [repeats]: one run, seed 0.
        let mut s = s.clone();
        s.repeats = None;
        let p = Parsed::new(s, Path::new("t.toml")).unwrap();
        let SceneSpec::FunnelPour(f) = &p.scene else {
            panic!("{:?}", p.scene)
        };
        assert_eq!((f.repeats.count, f.repeats.seed), (1, 0));
    }

    #[test]
    fn free_settling_and_drop_share_their_spec() {
        let p = parse("stokes_single.toml", &[]).unwrap();
        let SceneSpec::FreeSettling(f) = &p.scene else {
            panic!("{:?}", p.scene)
        };
        assert_eq!(f.release, p.scenario.release);
        assert_eq!(f.container, p.scenario.container);
        assert_eq!(f.measure, p.scenario.measure);
        let p = parse(
            "stokes_single.toml",
            &["kind=drop", "release.fall_heights_m=[0.0]"],
        )
        .unwrap();
        assert!(
            matches!(&p.scene, SceneSpec::FreeSettling(f) if f.entry == crate::scenario::Entry::Drop),
            "{:?}",
            p.scene
        );
    }

    #[test]
    fn a_missing_table_names_the_table_and_the_kind() {
        let p = parse("paste_68_balls.toml", &[]).unwrap();
        let mut s = p.scenario.clone();
        s.funnel = None;
        let e = Parsed::new(s, Path::new("t.toml")).unwrap_err();
        assert_eq!(e.key.as_deref(), Some("funnel"));
        assert!(e.message.contains("funnel_pour"), "{e}");
        let mut s = p.scenario.clone();
        s.contacts = None;
        let e = Parsed::new(s, Path::new("t.toml")).unwrap_err();
        assert_eq!(e.key.as_deref(), Some("contacts"));
        assert!(e.message.contains("funnel_pour"), "{e}");
        let p = parse("sedimentation_sample1.toml", &[]).unwrap();
        let mut s = p.scenario.clone();
        s.sample = None;
        let e = Parsed::new(s, &root().join("scenarios/s.toml")).unwrap_err();
        assert_eq!(e.key.as_deref(), Some("sample"));
        assert!(e.message.contains("sedimentation"), "{e}");
        let mut s = p.scenario;
        s.container.as_mut().unwrap().width_m = None;
        let e = Parsed::new(s, &root().join("scenarios/s.toml")).unwrap_err();
        assert_eq!(e.key.as_deref(), Some("container.width_m"));
        assert_eq!(Kind::Sedimentation.name(), "sedimentation");
    }

    #[test]
    fn the_rheology_carries_its_parameters() {
        let p = parse("stokes_single.toml", &[]).unwrap();
        assert_eq!(p.rheology.drag_viscosity_pa_s(), 1e-3);
        assert_eq!(p.rheology.yield_stress_pa(), 0.0);
        let p = parse("paste_68_balls.toml", &[]).unwrap();
        let f = &p.scenario.fluid;
        assert_eq!(
            p.rheology,
            RheologyModel::Bingham {
                plastic_viscosity_pa_s: f.plastic_viscosity_pa_s.unwrap(),
                yield_stress_pa: f.yield_stress_pa.unwrap(),
            }
        );
        assert_eq!(
            p.rheology.drag_viscosity_pa_s(),
            f.plastic_viscosity_pa_s.unwrap()
        );
    }

    #[test]
    fn dimension_is_written_back_as_a_number() {
        let p = parse("stokes_single.toml", &[]).unwrap();
        let text = toml::to_string(&p.scenario).unwrap();
        assert!(text.contains("\ndimension = 3\n"), "{text}");
        let p = parse("sedimentation_sample1.toml", &[]).unwrap();
        let text = toml::to_string(&p.scenario).unwrap();
        assert!(text.contains("\ndimension = 2\n"), "{text}");
        let e = parse("stokes_single.toml", &["dimension=300"]).unwrap_err();
        assert_eq!(e.key.as_deref(), Some("dimension"));
        assert!(e.message.contains("2 or 3"), "{e}");
    }
}
