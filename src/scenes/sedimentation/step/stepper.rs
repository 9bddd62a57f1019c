//! The constants of a run's steps ([`Stepper`]) and what follows from them alone: the step
//! size, the Stokes speeds of the grains. The free update, deposition and the fault scan that
//! use them are in [`super`] and its kernel.

use super::super::setup::Setup;
use super::super::state::State;
use super::super::voidage::VoidageGrid;
use crate::dynamics::Integrator;
use crate::fluid::newtonian::stokes_terminal_velocity_m_s;
use crate::sample::Grains;
use crate::scenario::Physics;
use rayon::prelude::*;

/// Grains updated (or searched, in the contact stage) between two checks for an interrupt
/// request: a few milliseconds of work, so that Ctrl-C/SIGTERM stops even a step of millions of
/// grains within about a second.
pub const INTERRUPT_CHECK_GRAINS: usize = 4096;

/// The constants of a run's steps. SI units.
#[derive(Clone, Copy, Debug)]
pub struct Stepper {
    /// `ideal-stokes`: Stokes drag, no voidage, no bed growth, no contacts.
    pub ideal: bool,
    /// Integrator of the free update.
    pub integrator: Integrator,
    /// Gravity g, m/s².
    pub gravity_m_s2: f64,
    /// Grain density ρ_p, kg/m³.
    pub grain_density_kg_m3: f64,
    /// Fluid density ρ_f, kg/m³.
    pub fluid_density_kg_m3: f64,
    /// Viscosity μ, Pa s.
    pub viscosity_pa_s: f64,
    /// Largest step, s.
    pub max_step_s: f64,
    /// Voidage cell size, m (the fastest suspended grain moves at most half of it per step).
    pub cell_m: f64,
    /// Bed area times its packing fraction, m² (the bed grows by the deposited volume over it).
    pub bed_area_m2: f64,
    /// Speed above which a grain of the free update is a fault: twice the largest grain's
    /// Stokes terminal speed, m/s.
    pub speed_bound_m_s: f64,
}

impl Stepper {
    /// The step constants of the run of `setup` (its physics, integrator, gravity, fluid,
    /// `[sample]` and grains).
    pub fn new(setup: &Setup) -> Self {
        let (c, sm) = (&setup.common, &setup.spec.sample);
        let mut me = Self {
            ideal: c.physics == Physics::IdealStokes,
            integrator: c.time.integrator,
            gravity_m_s2: c.gravity_m_s2,
            grain_density_kg_m3: sm.density_kg_m3,
            fluid_density_kg_m3: c.fluid_density_kg_m3,
            viscosity_pa_s: setup.viscosity_pa_s,
            max_step_s: sm.max_step_s,
            cell_m: sm.voidage_cell_m,
            bed_area_m2: setup.width_m * setup.thickness_m * sm.bed_packing,
            speed_bound_m_s: 0.0,
        };
        me.speed_bound_m_s = 2.0
            * setup
                .grains
                .kinds_present()
                .iter()
                .map(|k| me.stokes_speed_m_s(k.diameter_m))
                .fold(0.0, f64::max);
        me
    }

    /// Stokes terminal speed of a grain of diameter `d_m`, m/s.
    pub fn stokes_speed_m_s(&self, d_m: f64) -> f64 {
        stokes_terminal_velocity_m_s(
            d_m,
            self.grain_density_kg_m3,
            self.fluid_density_kg_m3,
            self.viscosity_pa_s,
            self.gravity_m_s2,
        )
    }

    /// The Stokes terminal speed of every grain of `grains` ([`Stepper::stokes_speed_m_s`]),
    /// m/s: computed once per run for [`Stepper::step_with_vmax_s`].
    pub fn stokes_speeds_m_s(&self, grains: &Grains) -> Vec<f64> {
        let speeds: Vec<f64> = grains
            .kinds
            .iter()
            .map(|k| self.stokes_speed_m_s(k.diameter_m))
            .collect();
        grains.kind.iter().map(|&k| speeds[k as usize]).collect()
    }

    /// The step from time `t_s` to `next_event_s` before any bound from the grains: up to the
    /// event, at most `max_step_s`, at least 1e-12 s.
    pub fn clock_step_s(&self, t_s: f64, next_event_s: f64) -> f64 {
        (next_event_s - t_s).min(self.max_step_s).max(1e-12)
    }

    /// The largest speed of the suspended grains of `st`, each the larger of its speed and its
    /// Stokes terminal speed (`stokes_speeds_m_s`, [`Stepper::stokes_speeds_m_s`]), m/s, for
    /// [`Stepper::step_with_vmax_s`] (0 in ideal Stokes, whose steps it does not bound). Searched
    /// in parallel (a maximum does not depend on the order).
    pub fn vmax_m_s(&self, st: &State, stokes_speeds_m_s: &[f64]) -> f64 {
        if self.ideal {
            return 0.0;
        }
        st.velocity_m_s
            .par_iter()
            .zip(st.settled.par_iter())
            .zip(stokes_speeds_m_s.par_iter())
            .with_min_len(INTERRUPT_CHECK_GRAINS)
            .filter(|((_, s), _)| !**s)
            .map(|((v, _), &vs)| v.abs().max(vs))
            .reduce(|| 0.0, f64::max)
    }

    /// The step from time `t_s` to `next_event_s`: up to the event, at most `max_step_s`; full
    /// physics also keeps the fastest suspended grain within half a voidage cell per step, given
    /// the largest speed `vmax_m_s` of the suspended grains (each the larger of its speed and its
    /// Stokes terminal speed, for grains still accelerating), m/s, as
    /// [`Stepper::deposit_vmax`] or [`Stepper::vmax_m_s`] give it. At least 1e-12 s.
    pub fn step_with_vmax_s(&self, t_s: f64, next_event_s: f64, vmax_m_s: f64) -> f64 {
        let mut dt = (next_event_s - t_s).min(self.max_step_s);
        if !self.ideal && vmax_m_s > 0.0 {
            dt = dt.min(0.5 * self.cell_m / vmax_m_s);
        }
        dt.max(1e-12)
    }

    /// Whether [`CellDrag`](super::kernel::CellDrag) takes the exponential step of Dallavalle's drag with the Di Felice
    /// factor (the tabulated terminal state, else the Newton step) rather than
    /// [`crate::dynamics::advance`] with the cell's drag: the exponential integrator on a Di
    /// Felice grid.
    pub fn fast_path(&self, grid: &VoidageGrid) -> bool {
        self.integrator == Integrator::Exponential && grid.is_di_felice()
    }
}
