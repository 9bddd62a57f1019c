//! The whole scenario file ([`Scenario`]) with its top-level keys and the `[record]` and
//! `[sweep]` tables. The checks that read the whole scenario sit in [`super::rules`].

use super::base::{Dim, EngineChoice, Kind, Physics};
use super::bodies::{Container, ReferenceSpec, Release, SphereSpec, SpheresCsv};
use super::contacts::Contacts;
use super::fluid::{Drag, Fluid};
use super::measure::Measure;
use super::tables::funnel_pour::{FunnelSpec, Repeats};
use super::tables::restitution_drop::RestitutionDropSpec;
use super::tables::sedimentation::{InstrumentsSpec, SampleSpec};
use super::tables::tilt_friction::TiltSpec;
use super::time::Time;
use super::transient::Transient;
use crate::dynamics::Integrator;
use crate::error::BadInput;
use crate::scenario::check::{oc, Check};
use serde::{Deserialize, Serialize};

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

impl Scenario {
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
