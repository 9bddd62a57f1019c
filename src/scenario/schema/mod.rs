//! The scenario schema (serde): the whole file in `scenario.rs`, the common tables in the files
//! beside it, the tables of one kind each under `tables/`, and the spec of each kind under
//! `kinds/`. Defaults are documented on each field. A table's own range checks sit next to its
//! struct (`fn check`); the checks that read the whole scenario sit in `rules.rs` (common
//! tables) and `kinds/` (kind tables); [`super::validate`] runs them. This file only declares
//! the modules and re-exports their names; the files form no import circle (issue 24).

mod base;
mod bodies;
mod contacts;
mod fluid;
mod kinds;
mod measure;
mod rules;
mod scenario;
mod tables;
mod time;
mod transient;

pub(crate) use base::within_run;
pub use base::{Dim, Engine, EngineChoice, Kind, Physics};
pub use bodies::{Container, ReferenceSpec, Release, SphereSpec};
pub use contacts::Contacts;
#[cfg(test)]
pub(crate) use fluid::Rheology; // for the unit tests only
pub use fluid::{RheologyModel, Submergence};
pub(crate) use kinds::free_settling;
pub use kinds::free_settling::{Entry, FreeSettlingSpec};
pub(crate) use kinds::funnel_pour;
pub use kinds::funnel_pour::FunnelPourSpec;
pub(crate) use kinds::restitution_drop;
pub use kinds::restitution_drop::RestitutionSpec;
pub(crate) use kinds::sedimentation;
pub(crate) use kinds::sedimentation::trim_default_times;
pub use kinds::sedimentation::SedimentationSpec;
pub(crate) use kinds::tilt_friction;
pub use kinds::tilt_friction::TiltFrictionSpec;
pub use measure::Measure;
pub(crate) use rules::check_sphere;
pub use scenario::{Record, Scenario, SweepSpec};
pub use tables::funnel_pour::{FunnelSpec, Repeats};
pub use tables::restitution_drop::RestitutionDropSpec;
pub use tables::sedimentation::{InstrumentsSpec, SampleSpec};
pub use tables::tilt_friction::TiltSpec;
pub use time::Time;
pub use transient::{Confinement, History, HistoryReynolds, Transient, Wall};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::BadInput;
    use serde::Deserialize;
    use std::path::Path;

    const STOKES: &str = include_str!("../../../scenarios/stokes_single.toml");

    fn load(text: &str, set: &[&str]) -> Result<Scenario, BadInput> {
        let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
        crate::scenario::load_str(text, Path::new("t.toml"), &set)
    }

    #[test]
    fn dim_reads_two_or_three_only() {
        #[derive(Deserialize)]
        struct D {
            dimension: Dim,
        }
        let d: D = toml::from_str("dimension = 2").unwrap();
        assert_eq!(d.dimension, Dim::Two);
        let d: D = toml::from_str("dimension = 3").unwrap();
        assert_eq!(d.dimension, Dim::Three);
        assert!(toml::from_str::<D>("dimension = 4").is_err());
        assert_eq!(u8::from(Dim::Two), 2);
        let s = load(STOKES, &[]).unwrap();
        assert_eq!(s.dim(), Dim::Three);
        let e = load(STOKES, &["dimension=4"]).unwrap_err();
        assert_eq!(e.key.as_deref(), Some("dimension"));
        assert!(e.message.contains("2 or 3"), "{e}");
    }

    #[test]
    fn engine_resolves_auto_per_kind() {
        let s = load(STOKES, &[]).unwrap();
        assert_eq!(s.engine(), Engine::Free);
        let s = load(STOKES, &["engine=rapier"]).unwrap();
        assert_eq!(s.engine(), Engine::Rapier);
        assert_eq!(s.engine().name(), "rapier");
        let mut s = s;
        s.kind = Kind::FunnelPour;
        s.engine = EngineChoice::Auto;
        assert_eq!(s.engine(), Engine::Rapier);
    }

    #[test]
    fn one_viscosity_for_every_rheology() {
        let s = load(STOKES, &[]).unwrap();
        let model = s.fluid.model().unwrap();
        assert_eq!(model.drag_viscosity_pa_s(), 1e-3);
        let mut f = s.fluid.clone();
        f.rheology = Rheology::Bingham;
        f.viscosity_pa_s = None;
        f.plastic_viscosity_pa_s = Some(0.7);
        f.yield_stress_pa = Some(136.0);
        let model = f.model().unwrap();
        assert_eq!(model.drag_viscosity_pa_s(), 0.7);
        assert_eq!(model.yield_stress_pa(), 136.0);
        assert_eq!(
            model,
            fluid::RheologyModel::Bingham {
                plastic_viscosity_pa_s: 0.7,
                yield_stress_pa: 136.0
            }
        );
        f.plastic_viscosity_pa_s = None;
        assert_eq!(f.model(), None);
    }

    #[test]
    fn a_table_the_kind_does_not_use_is_refused() {
        let e = load(STOKES, &["contacts.friction=0.3"]).unwrap_err();
        assert_eq!(e.key.as_deref(), Some("contacts"));
        assert!(e.message.contains("free_settling"), "{e}");
        assert!(
            e.message.contains("[measure]"),
            "lists the used tables: {e}"
        );
        let e = load(STOKES, &["repeats.count=2"]).unwrap_err();
        assert_eq!(e.key.as_deref(), Some("repeats"));
        // [contacts] is used by the sedimentation grain contacts.
        let sed = include_str!("../../../scenarios/sedimentation_sample1.toml");
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/s.toml");
        let set = [
            "contacts.friction=0.3".to_string(),
            "contacts.restitution=0.5".to_string(),
        ];
        crate::scenario::load_str(sed, &path, &set).expect("[contacts] on sedimentation");
    }
}
