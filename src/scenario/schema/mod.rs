//! The scenario schema (serde): the common tables here and in the files beside this one, one
//! file per kind-specific table under `kinds/`. Defaults are documented on each field. Each
//! table's range checks sit next to its struct (`fn check`); [`super::validate`] runs them.

mod bodies;
mod contacts;
mod fluid;
/// The tables of one kind each, with their checks and the typed spec of the kind built from
/// them: one file per kind under `kinds/`, named as the kind.
mod kinds {
    pub mod free_settling;
    pub mod funnel_pour;
    pub mod restitution_drop;
    pub mod sedimentation;
    pub mod tilt_friction;
}
mod measure;
mod time;
mod transient;

pub use bodies::{Container, ReferenceSpec, Release, SphereSpec, SpheresCsv};
pub use contacts::Contacts;
pub use fluid::{Drag, Fluid, Rheology, RheologyModel, Submergence};
pub(crate) use kinds::free_settling;
pub use kinds::free_settling::{Entry, FreeSettlingSpec};
pub(crate) use kinds::funnel_pour;
pub use kinds::funnel_pour::{FunnelPourSpec, FunnelSpec, Repeats};
pub(crate) use kinds::restitution_drop;
pub use kinds::restitution_drop::{RestitutionDropSpec, RestitutionSpec};
pub(crate) use kinds::sedimentation;
pub(crate) use kinds::sedimentation::trim_default_times;
pub use kinds::sedimentation::{InstrumentsSpec, SampleSpec, SedimentationSpec};
pub(crate) use kinds::tilt_friction;
pub use kinds::tilt_friction::{TiltFrictionSpec, TiltSpec};
pub use measure::Measure;
pub use time::Time;
pub use transient::{Confinement, History, HistoryReynolds, Transient, Wall};

use super::check::{oc, Check, Range};
use crate::dynamics::Integrator;
use crate::error::BadInput;
use serde::{Deserialize, Serialize};
// Re-exported for the unit tests only.

/// Standard gravity used when a scenario does not set `gravity_m_s2`, m/s².
pub const DEFAULT_GRAVITY_M_S2: f64 = 9.81;

/// A whole scenario file.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Scenario {
    /// Name of the run; results go to `OUT/<name>/`. Letters, digits, `_`, `-`, `.` only.
    pub name: String,
    /// What kind of scene this is.
    pub kind: Kind,
    /// 2 or 3 (`dimension = 2` in TOML, written back as the number). Default 3.
    #[serde(default = "default_dimension")]
    pub dimension: Dim,
    /// Free text shown in `run.toml`.
    #[serde(default)]
    pub description: String,
    /// `full` (default) or `ideal-stokes`: Stokes drag with the fluid's (plastic) viscosity, no
    /// yield stress, no voidage, no contacts — the reference case for checking the pipeline.
    #[serde(default)]
    pub physics: Physics,
    /// Which engine advances the bodies. Default `auto`.
    #[serde(default)]
    pub engine: EngineChoice,
    /// Magnitude of gravity, m/s², acting along −z in 3D and −y in 2D. Default 9.81.
    #[serde(default = "default_gravity")]
    pub gravity_m_s2: f64,
    /// The fluid.
    pub fluid: Fluid,
    /// The drag law.
    pub drag: Drag,
    /// Time step, duration and integrator.
    pub time: Time,
    /// The container (tank, cylinder); none for an unbounded fluid.
    #[serde(default)]
    pub container: Option<Container>,
    /// How bodies are released.
    #[serde(default)]
    pub release: Release,
    /// Spheres listed inline.
    #[serde(default)]
    pub spheres: Vec<SphereSpec>,
    /// Spheres read from a CSV file (in addition to `spheres`).
    #[serde(default)]
    pub spheres_csv: Option<SpheresCsv>,
    /// How terminal velocity and other quantities are measured.
    #[serde(default)]
    pub measure: Option<Measure>,
    /// What to record.
    #[serde(default)]
    pub record: Record,
    /// Default settings for `settle sweep`.
    #[serde(default)]
    pub sweep: Option<SweepSpec>,
    /// Contact properties (scenes with contacts).
    #[serde(default)]
    pub contacts: Option<Contacts>,
    /// Restitution drop settings (kind `restitution_drop`).
    #[serde(default)]
    pub restitution_drop: Option<RestitutionDropSpec>,
    /// Tilt test settings (kind `tilt_friction`).
    #[serde(default)]
    pub tilt: Option<TiltSpec>,
    /// Funnel geometry and release (kind `funnel_pour`).
    #[serde(default)]
    pub funnel: Option<FunnelSpec>,
    /// Repeated runs with different seeds (kind `funnel_pour`).
    #[serde(default)]
    pub repeats: Option<Repeats>,
    /// The soil sample (kind `sedimentation`).
    #[serde(default)]
    pub sample: Option<SampleSpec>,
    /// The hydrometer, buoyancy sphere and pipette read during a sedimentation run (kind
    /// `sedimentation`; absent: every default of [`InstrumentsSpec`]).
    #[serde(default)]
    pub instruments: Option<InstrumentsSpec>,
    /// Transient forces: added mass, history force, wall correction (kinds `free_settling`,
    /// `drop`; the added mass alone in `restitution_drop` and `funnel_pour`; absent: all off,
    /// the quasi-steady forces).
    #[serde(default)]
    pub transient: Option<Transient>,
    /// Measured curves drawn beside the simulated v(t) and gap (kind `free_settling`; absent:
    /// none).
    #[serde(default)]
    pub reference: Option<ReferenceSpec>,
}

fn default_dimension() -> Dim {
    Dim::Three
}
fn default_gravity() -> f64 {
    DEFAULT_GRAVITY_M_S2
}

/// Kinds of scene.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    /// Independent spheres settling from rest in a still fluid, no contacts between them
    /// (f-EDEM §3 single sphere, §4.1 Valentik–Whitmore tanks). Each sphere runs alone.
    FreeSettling,
    /// Spheres dropped from `release.fall_heights_m` above the free surface through air into the
    /// fluid, each alone, until they stop (f-EDEM §4.2 steel balls in paste backfill).
    Drop,
    /// A ball dropped on a plate in air; rebound heights against measurements (f-EDEM App. II).
    RestitutionDrop,
    /// A block on a plate tilted to a series of angles: sticks or slides (f-EDEM App. III).
    TiltFriction,
    /// Many balls released from a funnel into the fluid-filled cylinder, with contacts (f-EDEM
    /// §4.2, 68 steel balls into paste backfill), repeated with different seeds.
    FunnelPour,
    /// A 2D projection of the ASTM D422 sedimentation cylinder: a soil sample of representative
    /// grains settling from a homogeneous suspension (seed 000 §4–5).
    Sedimentation,
}

/// Physics switch.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Physics {
    /// Everything the scenario asks for.
    #[default]
    Full,
    /// Stokes drag only, no yield stress, no voidage, no contacts.
    IdealStokes,
}

/// Engine choice.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "kebab-case")]
pub enum EngineChoice {
    /// `free` where the scene has no contacts, `rapier` otherwise.
    #[default]
    Auto,
    /// Our own integrator only (no contact pipeline): exact free flight, fastest.
    Free,
    /// Every body in a Rapier world, fluid forces through the force hook.
    Rapier,
}

/// Recording settings.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Record {
    /// Write `timeseries.csv`. Default true.
    #[serde(default = "yes")]
    pub timeseries: bool,
    /// Interval between time-series rows, s. Default: every step up to 2000 rows per body.
    #[serde(default)]
    pub every_s: Option<f64>,
}

impl Default for Record {
    fn default() -> Self {
        Self {
            timeseries: true,
            every_s: None,
        }
    }
}

fn yes() -> bool {
    true
}

/// Default settings of `settle sweep` for this scenario.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SweepSpec {
    /// Time steps to run, s.
    #[serde(default)]
    pub dt_s: Vec<f64>,
    /// Integrators to compare. Default: all three.
    #[serde(default)]
    pub integrators: Vec<Integrator>,
    /// Relative tolerance for the recommended dt. Default 0.01.
    #[serde(default)]
    pub tol: Option<f64>,
}

/// The engine a scenario runs on, after `engine = "auto"` is resolved ([`Scenario::engine`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Engine {
    /// Our own integrator only: exact free flight, no contacts.
    Free,
    /// Every body in a Rapier world, fluid forces through the force hook.
    Rapier,
}

impl Engine {
    /// The name written in `run.toml` and shown to the user: `free` or `rapier`.
    pub fn name(self) -> &'static str {
        match self {
            Engine::Free => "free",
            Engine::Rapier => "rapier",
        }
    }
}

impl std::fmt::Display for Engine {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The dimension of a scene. In TOML it is the number `2` or `3` (`dimension = 2`); any other
/// number is refused when parsed as a `Dim`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(try_from = "i64", into = "u8")]
pub enum Dim {
    /// A 2D scene: gravity along −y.
    Two,
    /// A 3D scene: gravity along −z.
    Three,
}

/// A dimension other than 2 or 3 (the number read).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BadDim(pub i64);

impl std::fmt::Display for BadDim {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} is not allowed: 2 or 3", self.0)
    }
}

impl TryFrom<i64> for Dim {
    type Error = BadDim;
    fn try_from(n: i64) -> Result<Self, BadDim> {
        match n {
            2 => Ok(Dim::Two),
            3 => Ok(Dim::Three),
            _ => Err(BadDim(n)),
        }
    }
}

impl From<Dim> for u8 {
    fn from(d: Dim) -> u8 {
        match d {
            Dim::Two => 2,
            Dim::Three => 3,
        }
    }
}

impl Scenario {
    /// Which engine the scenario runs on: `engine = "rapier"` always gives Rapier; `auto` (and
    /// `free`) give the free integrator for the kinds without contacts (free settling, drop,
    /// sedimentation, whose grain contacts run in their own solve) and Rapier for the contact
    /// kinds (restitution drop, tilt, funnel pour).
    pub fn engine(&self) -> Engine {
        if self.engine == EngineChoice::Rapier || crate::scenario::info(self.kind).rapier {
            Engine::Rapier
        } else {
            Engine::Free
        }
    }

    #[cfg_attr(not(test), allow(dead_code))] // read by the unit tests
    /// The dimension (the field `dimension`).
    pub fn dim(&self) -> Dim {
        self.dimension
    }

    /// Checks the top-level keys `name` and `gravity_m_s2` (`dimension` is checked as it is
    /// parsed: 2 or 3 only).
    pub(crate) fn check_common(&self, c: &Check) -> Result<(), BadInput> {
        let name_ok = !self.name.is_empty()
            && !self.name.starts_with('.')
            && self
                .name
                .chars()
                .all(|ch| ch.is_ascii_alphanumeric() || "_-.".contains(ch));
        if !name_ok {
            return Err(c.err(
                "name",
                format!("`{}` is not allowed: use letters, digits, `_`, `-` and `.`, not starting with `.` (it names the output folder)", self.name),
            ));
        }
        c.range("gravity_m_s2", self.gravity_m_s2, oc(0.0, 1000.0, "m/s²"))
    }
}

impl Kind {
    /// The name of the kind as written in scenario files (`free_settling`, …).
    pub fn name(self) -> &'static str {
        crate::scenario::info(self).name
    }
}

impl Record {
    /// `every_s` within (0, end_s].
    pub(crate) fn check(&self, c: &Check, end_s: f64) -> Result<(), BadInput> {
        match self.every_s {
            Some(e) => c.range("record.every_s", e, oc(0.0, end_s, "s")),
            None => Ok(()),
        }
    }
}

impl SweepSpec {
    /// Every `dt_s` within (0, end_s], `tol` within (0, 1].
    pub(crate) fn check(&self, c: &Check, end_s: f64) -> Result<(), BadInput> {
        c.each("sweep.dt_s", &self.dt_s, oc(0.0, end_s, "s"))?;
        match self.tol {
            Some(t) => c.range("sweep.tol", t, oc(0.0, 1.0, "")),
            None => Ok(()),
        }
    }
}

/// `(0, end_s]` with the note used for times within a run.
pub(crate) fn within_run(end_s: f64) -> Range<'static> {
    oc(0.0, end_s, "s (within time.end_s)")
}

#[cfg(test)]
mod tests {
    use super::*;
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
