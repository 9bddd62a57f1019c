//! The per-grain stages of a step: its size, the free update of every suspended grain, the
//! deposition on the bed, the clock, and the fault scan.

use super::setup::Setup;
use super::state::State;
use super::voidage::VoidageGrid;
use crate::dynamics::{advance, DtBasis, Integrator, Unstable};
use crate::fluid::newtonian::{stokes_response_time_s, stokes_terminal_velocity_m_s};
use crate::fluid::{sphere_mass_kg, sphere_volume_m3};
use crate::scenario::{Physics, SampleSpec, Scenario};
use nalgebra::SVector;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

/// Grains updated (or searched, in the contact stage) between two checks for an interrupt
/// request: a few milliseconds of work, so that Ctrl-C/SIGTERM stops even a step of millions of
/// grains within about a second.
pub const INTERRUPT_CHECK_GRAINS: usize = 4096;

/// The heights and vertical speeds of every grain at the start of a step: what the contact
/// stage re-does its clusters from, and what an interrupted step goes back to (the free update
/// and the contact stage change nothing else before deposition).
#[derive(Clone, Debug, Default)]
pub struct StepStart {
    /// Height of each grain's centre, m.
    pub y_m: Vec<f64>,
    /// Vertical velocity of each grain, m/s.
    pub v_m_s: Vec<f64>,
}

impl StepStart {
    /// Keeps the heights and speeds of `st`.
    pub fn capture(&mut self, st: &State) {
        self.y_m.clear();
        self.y_m.extend(st.grains.iter().map(|g| g.y_m));
        self.v_m_s.clear();
        self.v_m_s.extend_from_slice(&st.velocity_m_s);
    }

    /// Puts every grain of `st` back at the captured heights and speeds.
    pub fn rewind(&self, st: &mut State) {
        for ((g, v), (&y0, &v0)) in st
            .grains
            .iter_mut()
            .zip(st.velocity_m_s.iter_mut())
            .zip(self.y_m.iter().zip(&self.v_m_s))
        {
            g.y_m = y0;
            *v = v0;
        }
    }
}

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
    /// The step constants of scenario `s` (sample `sm`) for the grains of `st`.
    pub fn new(s: &Scenario, sm: &SampleSpec, setup: &Setup, st: &State) -> Self {
        let mut me = Self {
            ideal: s.physics == Physics::IdealStokes,
            integrator: s.time.integrator,
            gravity_m_s2: s.gravity_m_s2,
            grain_density_kg_m3: sm.density_kg_m3,
            fluid_density_kg_m3: s.fluid.density_kg_m3,
            viscosity_pa_s: setup.viscosity_pa_s,
            max_step_s: sm.max_step_s,
            cell_m: sm.voidage_cell_m,
            bed_area_m2: setup.width_m * setup.thickness_m * sm.bed_packing,
            speed_bound_m_s: 0.0,
        };
        me.speed_bound_m_s = 2.0
            * st.grains
                .iter()
                .map(|gr| me.stokes_speed_m_s(gr.diameter_m))
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

    /// The step from `st`: up to `next_event_s`, at most `max_step_s`; full physics also keeps
    /// the fastest suspended grain (its speed, or its Stokes terminal speed if larger, for grains
    /// still accelerating) within half a voidage cell per step. At least 1e-12 s.
    pub fn step_size_s(&self, st: &State, next_event_s: f64) -> f64 {
        let mut dt = (next_event_s - st.time_s).min(self.max_step_s);
        if !self.ideal {
            let vmax = st
                .velocity_m_s
                .iter()
                .zip(&st.settled)
                .zip(&st.grains)
                .filter(|((_, s), _)| !**s)
                .map(|((v, _), gr)| v.abs().max(self.stokes_speed_m_s(gr.diameter_m)))
                .fold(0.0, f64::max);
            if vmax > 0.0 {
                dt = dt.min(0.5 * self.cell_m / vmax);
            }
        }
        dt.max(1e-12)
    }

    /// Advances every suspended grain of `st` by `dt_s` with the exact (exponential) or chosen
    /// integrator of [`crate::dynamics`], vertically, under gravity, buoyancy and the drag of
    /// its voidage cell; a grain reaching the bed surface stops on it (flagged by
    /// [`Stepper::deposit`]). In parallel, by chunks of [`INTERRUPT_CHECK_GRAINS`] grains: every
    /// grain's update is independent. Returns false if an interrupt was requested
    /// ([`crate::interrupt::requested`], checked before each chunk): the update is then
    /// incomplete and the caller must rewind the step ([`StepStart::rewind`]).
    pub fn free_update(&self, st: &mut State, grid: &VoidageGrid, dt_s: f64) -> bool {
        let floor = st.bed_height_m;
        let (g, rho_p, rho_f) = (
            self.gravity_m_s2,
            self.grain_density_kg_m3,
            self.fluid_density_kg_m3,
        );
        let integrator = self.integrator;
        let n = INTERRUPT_CHECK_GRAINS;
        let stopped = AtomicBool::new(false);
        st.grains
            .par_chunks_mut(n)
            .zip(st.velocity_m_s.par_chunks_mut(n))
            .zip(st.settled.par_chunks(n))
            .for_each(|((grains, speeds), settled)| {
                if stopped.load(Ordering::Relaxed) || crate::interrupt::requested() {
                    stopped.store(true, Ordering::Relaxed);
                    return;
                }
                for ((gr, v), _) in grains
                    .iter_mut()
                    .zip(speeds.iter_mut())
                    .zip(settled)
                    .filter(|(_, s)| !**s)
                {
                    let d = gr.diameter_m;
                    let drag = grid.drag_at(d, gr.x_m, gr.y_m);
                    let m = sphere_mass_kg(d, rho_p);
                    let w = SVector::<f64, 1>::new(-(m - sphere_mass_kg(d, rho_f)) * g);
                    let step = advance(integrator, &drag, m, &w, &SVector::<f64, 1>::new(*v), dt_s);
                    *v = step.velocity_m_s[0];
                    gr.y_m += step.displacement_m[0];
                    if gr.y_m - 0.5 * d <= floor {
                        gr.y_m = floor + 0.5 * d;
                    }
                }
            });
        !stopped.into_inner()
    }

    /// Deposition (serial: the bed grows as grains join it): every suspended grain touching the
    /// bed surface joins the bed, at rest on it; with full physics the bed rises by the grain's
    /// real volume over `bed_area_m2`.
    pub fn deposit(&self, st: &mut State) {
        for ((gr, v), settled) in st
            .grains
            .iter_mut()
            .zip(st.velocity_m_s.iter_mut())
            .zip(st.settled.iter_mut())
        {
            if !*settled && gr.y_m - 0.5 * gr.diameter_m <= st.bed_height_m + 1e-15 {
                *settled = true;
                *v = 0.0;
                gr.y_m = st.bed_height_m + 0.5 * gr.diameter_m;
                if !self.ideal {
                    st.bed_height_m +=
                        gr.weight * sphere_volume_m3(gr.diameter_m) / self.bed_area_m2;
                }
            }
        }
    }

    /// The first grain in a numerical fault after a step of `dt_s` from `st` (state updated in
    /// place, time not yet advanced), as an [`Unstable`] report: a non-finite position or
    /// velocity, a centre outside the cylinder (beside the walls, or a diameter above the top),
    /// or, with `speed_bound_m_s`, a speed above it. The suggested dt is the explicit drag limit
    /// 2τ of that grain (Stokes τ = ρ_p d²/(18 μ)) with the explicit integrator, else half the
    /// step.
    pub fn grain_fault(
        &self,
        st: &State,
        setup: &Setup,
        dt_s: f64,
        speed_bound_m_s: Option<f64>,
    ) -> Option<Unstable> {
        let (width, height) = (setup.width_m, setup.height_m);
        let bound = speed_bound_m_s.unwrap_or(f64::INFINITY);
        let i = st
            .grains
            .par_iter()
            .zip(st.velocity_m_s.par_iter())
            .position_first(|(gr, v)| {
                !(gr.y_m.is_finite() && v.is_finite() && gr.x_m.is_finite())
                    || v.abs() > bound
                    || gr.y_m > height + gr.diameter_m
                    || gr.x_m < -1e-12
                    || gr.x_m > width + 1e-12
            })?;
        let (gr, v) = (st.grains[i], st.velocity_m_s[i]);
        let d = gr.diameter_m;
        let (stable, basis) = if self.integrator == Integrator::Explicit {
            (
                2.0 * stokes_response_time_s(d, self.grain_density_kg_m3, self.viscosity_pa_s),
                DtBasis::ExplicitDrag,
            )
        } else {
            (0.5 * dt_s, DtBasis::Halved)
        };
        let (quantity, value) = if !(gr.y_m.is_finite() && gr.x_m.is_finite()) {
            ("position", gr.y_m)
        } else if !v.is_finite() {
            ("velocity", v)
        } else if v.abs() > bound {
            (
                "speed (bound: twice the largest grain's Stokes terminal speed), m/s",
                v.abs(),
            )
        } else {
            ("height above the bottom (outside the cylinder), m", gr.y_m)
        };
        Some(Unstable {
            body: format!("grain {i} (d = {d:.3e} m)"),
            time_s: st.time_s + dt_s,
            step: st.steps + 1,
            what: format!("{quantity} = {value:.3e}"),
            dt_s,
            stable_dt_s: stable,
            dt_basis: basis,
        })
    }
}

/// Advances the clock of `st` by `dt_s` (landing exactly on `next_event_s` when within a relative
/// 1e-9 of it) and counts the step.
pub fn advance_clock(st: &mut State, dt_s: f64, next_event_s: f64) {
    st.time_s += dt_s;
    st.steps += 1;
    st.dt_range_s = (st.dt_range_s.0.min(dt_s), st.dt_range_s.1.max(dt_s));
    if (next_event_s - st.time_s).abs() <= 1e-9 * next_event_s.max(1.0) {
        st.time_s = next_event_s;
    }
}
