//! The typed scenario: what each kind needs, built once at the end of validation ("parse,
//! don't validate"). A scene receives its own spec, with every table its kind needs present
//! and checked, and the fluid's rheology with its parameters; it never re-asserts what
//! validation already established.

use super::schema::{
    Contacts, Container, FunnelSpec, InstrumentsSpec, Measure, Release, Repeats,
    RestitutionDropSpec, SampleSpec, SphereSpec, TiltSpec,
};

/// One spec per kind of scene: the tables the kind needs, present and checked.
// One value per scenario file: the size of the largest variant does not matter.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, PartialEq)]
pub enum SceneSpec {
    /// Kind `free_settling`: spheres released submerged.
    FreeSettling(FreeSettlingSpec),
    /// Kind `drop`: spheres dropped through air into the fluid (`release.fall_heights_m` holds
    /// at least one height).
    Drop(FreeSettlingSpec),
    /// Kind `restitution_drop`.
    RestitutionDrop(RestitutionSpec),
    /// Kind `tilt_friction`.
    TiltFriction(TiltFrictionSpec),
    /// Kind `funnel_pour`.
    FunnelPour(FunnelPourSpec),
    /// Kind `sedimentation`.
    Sedimentation(SedimentationSpec),
}

/// Free settling and drops: each sphere alone in the fluid, no contacts.
#[derive(Clone, Debug, PartialEq)]
pub struct FreeSettlingSpec {
    /// The container (its bottom stops a sphere), or `None` for an unbounded fluid.
    pub container: Option<Container>,
    /// Release depth, speed and (drops) fall heights.
    pub release: Release,
    /// Probe times, detector section and steadiness window, if any.
    pub measure: Option<Measure>,
}

/// A ball dropped on a plate in air (kind `restitution_drop`).
#[derive(Clone, Debug, PartialEq)]
pub struct RestitutionSpec {
    /// The `[restitution_drop]` table: heights, measurements, tolerance.
    pub drop: RestitutionDropSpec,
    /// The ball: the scenario's one `[[spheres]]` entry.
    pub ball: SphereSpec,
    /// The contact properties (`[contacts]`).
    pub contacts: Contacts,
}

/// A block on a tilted plate (kind `tilt_friction`).
#[derive(Clone, Debug, PartialEq)]
pub struct TiltFrictionSpec {
    /// The `[tilt]` table: block, angles, duration, slide distance, bisection tolerance.
    pub tilt: TiltSpec,
    /// The block's edge lengths [x, y, z], m (`tilt.block_size_m`).
    pub block_size_m: [f64; 3],
    /// The contact properties (`[contacts]`).
    pub contacts: Contacts,
}

/// Balls poured from a funnel into the fluid-filled cylinder (kind `funnel_pour`).
#[derive(Clone, Debug, PartialEq)]
pub struct FunnelPourSpec {
    /// The `[funnel]` table: ball count and funnel geometry.
    pub funnel: FunnelSpec,
    /// Radius of the cylinder, m (half of `container.diameter_m`).
    pub cylinder_radius_m: f64,
    /// Height of the fluid column, m (`container.height_m`).
    pub height_m: f64,
    /// The contact properties (`[contacts]`).
    pub contacts: Contacts,
    /// Repeats and their first seed (`[repeats]`; absent: one run, seed 0).
    pub repeats: Repeats,
}

/// The 2D projection of the sedimentation cylinder (kind `sedimentation`).
#[derive(Clone, Debug, PartialEq)]
pub struct SedimentationSpec {
    /// The soil sample (`[sample]`).
    pub sample: SampleSpec,
    /// Width B of the projected cylinder, m (`container.width_m`).
    pub width_m: f64,
    /// Height H of the fluid column, m (`container.height_m`).
    pub height_m: f64,
    /// The hydrometer, buoyancy sphere and pipette (`[instruments]`; absent: every default).
    pub instruments: InstrumentsSpec,
    /// The grain contacts (`[contacts]`; absent: the scene's defaults).
    pub contacts: Option<Contacts>,
}

impl SceneSpec {
    /// The kind's name as written in scenario files.
    pub fn kind_name(&self) -> &'static str {
        match self {
            SceneSpec::FreeSettling(_) => "free_settling",
            SceneSpec::Drop(_) => "drop",
            SceneSpec::RestitutionDrop(_) => "restitution_drop",
            SceneSpec::TiltFriction(_) => "tilt_friction",
            SceneSpec::FunnelPour(_) => "funnel_pour",
            SceneSpec::Sedimentation(_) => "sedimentation",
        }
    }

    /// The spec of a `funnel_pour` scenario (None for another kind).
    pub fn funnel_pour(&self) -> Option<&FunnelPourSpec> {
        match self {
            SceneSpec::FunnelPour(f) => Some(f),
            _ => None,
        }
    }

    /// The spec of a `restitution_drop` scenario (None for another kind).
    pub fn restitution_drop(&self) -> Option<&RestitutionSpec> {
        match self {
            SceneSpec::RestitutionDrop(r) => Some(r),
            _ => None,
        }
    }

    /// The spec of a `tilt_friction` scenario (None for another kind).
    pub fn tilt_friction(&self) -> Option<&TiltFrictionSpec> {
        match self {
            SceneSpec::TiltFriction(t) => Some(t),
            _ => None,
        }
    }

    /// The spec of a `sedimentation` scenario (None for another kind).
    pub fn sedimentation(&self) -> Option<&SedimentationSpec> {
        match self {
            SceneSpec::Sedimentation(s) => Some(s),
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
        assert!(matches!(p.scene, SceneSpec::Drop(_)), "{:?}", p.scene);
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
