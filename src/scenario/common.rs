//! The typed common part of a scenario: what every kind reads beside its own spec
//! ([`super::SceneSpec`]), built once as the scenario is parsed. The fluid is its
//! [`RheologyModel`] and density, the drag its [`DragLaw`] (after the `physics` switch), the
//! engine the one `engine = "auto"` resolves to.

use super::schema::{
    Dim, Engine, Kind, Physics, Record, ReferenceSpec, RheologyModel, Scenario, Submergence,
    SweepSpec, Time, Transient,
};
use crate::fluid::{DragLaw, SphereDrag};

/// The parts of a scenario every kind reads, typed.
#[derive(Clone, Debug, PartialEq)]
pub struct Common {
    /// Name of the run (`OUT/<name>/`).
    pub name: String,
    /// The kind of scene.
    pub kind: Kind,
    /// 2 or 3.
    pub dimension: Dim,
    /// `full` or `ideal-stokes`.
    pub physics: Physics,
    /// The engine the bodies run on (`engine = "auto"` resolved, [`Scenario::engine`]).
    pub engine: Engine,
    /// Magnitude of gravity, m/s².
    pub gravity_m_s2: f64,
    /// The fluid's rheology with its parameters.
    pub rheology: RheologyModel,
    /// Fluid density ρ_f, kg/m³.
    pub fluid_density_kg_m3: f64,
    /// How a body crossing the free surface is immersed (`fluid.submergence`).
    pub submergence: Submergence,
    /// The drag law of every body (`Drag::law`: the `[drag]` table in this fluid,
    /// after the `physics` switch).
    pub drag: DragLaw,
    /// Time step, duration and integrator.
    pub time: Time,
    /// What to record.
    pub record: Record,
    /// Transient forces (absent: all off).
    pub transient: Option<Transient>,
    /// Measured curves drawn beside the simulated ones (kind `free_settling`).
    pub reference: Option<ReferenceSpec>,
    /// Default settings of `settle sweep`.
    pub sweep: Option<SweepSpec>,
}

impl Common {
    /// The common part of scenario `s`, whose fluid has rheology `rheology` (both checked by
    /// validation; total: nothing here can fail).
    pub fn of(s: &Scenario, rheology: RheologyModel) -> Self {
        Self {
            name: s.name.clone(),
            kind: s.kind,
            dimension: s.dimension,
            physics: s.physics,
            engine: s.engine(),
            gravity_m_s2: s.gravity_m_s2,
            rheology,
            fluid_density_kg_m3: s.fluid.density_kg_m3,
            submergence: s.fluid.submergence,
            drag: s.drag.law(rheology, s.physics),
            time: s.time.clone(),
            record: s.record.clone(),
            transient: s.transient.clone(),
            reference: s.reference.clone(),
            sweep: s.sweep.clone(),
        }
    }

    /// The drag of one sphere of diameter `d_m` in this fluid.
    pub fn sphere_drag(&self, d_m: f64) -> SphereDrag {
        SphereDrag::new(self.drag, d_m, self.fluid_density_kg_m3)
    }

    /// The added-mass coefficient C_m of the Rapier scenes (`transient.added_mass`,
    /// `transient.added_mass_coefficient`; 0 when off or without `[transient]`), for
    /// [`crate::engine::dim3::World::set_added_mass_coefficient`].
    pub fn added_mass_coefficient(&self) -> f64 {
        self.transient
            .as_ref()
            .map_or(0.0, |t| t.added_mass_coefficient_on())
    }
}
