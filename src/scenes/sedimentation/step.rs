//! The per-grain stages of a step: its size, the free update of every suspended grain, the
//! deposition on the bed, the clock, and the fault scan.

mod interval;
pub mod kernel;
mod stepper;

pub use interval::{IdealCache, Interval};
pub use stepper::{Stepper, INTERRUPT_CHECK_GRAINS};

use super::setup::Setup;
use super::state::State;
use super::voidage::VoidageGrid;
use crate::dynamics::{DtBasis, Integrator, Unstable};
use crate::fluid::newtonian::stokes_response_time_s;
use crate::sample::Grains;
use kernel::{
    bed_rise_m, free_step, horizontal_fault, on_bed, vertical_fault, CellDrag, CellGrain, Limits,
};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

/// The heights and vertical speeds of the grains a step can change, at its start: what the
/// contact stage re-does its clusters from, and what an interrupted step goes back to (the free
/// update and the contact stage change nothing else before deposition).
#[derive(Clone, Debug, Default)]
pub struct StepStart {
    /// Height of each grain's centre, m (entry i: grain i, as the contact stage reads them).
    pub y_m: Vec<f64>,
    /// Vertical velocity of each grain, m/s.
    pub v_m_s: Vec<f64>,
    /// Settled flag of each grain (kept only by [`StepStart::capture_all`]).
    pub settled: Vec<bool>,
}

impl StepStart {
    /// Keeps the heights and speeds of every grain of `st` (in parallel, by chunks of
    /// [`INTERRUPT_CHECK_GRAINS`] grains: copies only).
    pub fn capture(&mut self, st: &State) {
        let (n, len) = (INTERRUPT_CHECK_GRAINS, st.len());
        self.y_m.resize(len, 0.0);
        self.v_m_s.resize(len, 0.0);
        self.y_m
            .par_chunks_mut(n)
            .zip(self.v_m_s.par_chunks_mut(n))
            .zip(st.y_m.par_chunks(n).zip(st.velocity_m_s.par_chunks(n)))
            .for_each(|((ys, vs), (y0, v0))| {
                ys.copy_from_slice(y0);
                vs.copy_from_slice(v0);
            });
    }

    /// Keeps the heights, speeds and settled flags of every grain of `st` (before an
    /// ideal-Stokes interval, which deposits grains as it goes).
    pub fn capture_all(&mut self, st: &State) {
        self.capture(st);
        self.settled.clear();
        self.settled.extend_from_slice(&st.settled);
    }

    /// Puts every grain of `st` back at the heights, speeds and settled flags kept by
    /// [`StepStart::capture_all`].
    pub fn rewind_all(&self, st: &mut State) {
        self.rewind(st);
        st.settled.copy_from_slice(&self.settled);
    }

    /// Puts every grain of `st` back at its captured height and speed.
    pub fn rewind(&self, st: &mut State) {
        let n = INTERRUPT_CHECK_GRAINS;
        st.y_m
            .par_chunks_mut(n)
            .zip(st.velocity_m_s.par_chunks_mut(n))
            .zip(self.y_m.par_chunks(n).zip(self.v_m_s.par_chunks(n)))
            .for_each(|((ys, vs), (y0, v0))| {
                ys.copy_from_slice(y0);
                vs.copy_from_slice(v0);
            });
    }
}

impl Stepper {
    /// Advances every suspended grain of `active` (ascending grain indices of `st`) by `dt_s`
    /// with the exact (exponential) or chosen integrator of [`crate::dynamics`], vertically,
    /// under gravity, buoyancy and the drag of its voidage cell; a grain reaching the bed surface
    /// stops on it (flagged by [`Stepper::deposit_vmax`]). In parallel, by chunks of
    /// [`INTERRUPT_CHECK_GRAINS`] grains: every grain's update is independent. Returns None if
    /// an interrupt was requested ([`crate::interrupt::requested`], checked before each chunk):
    /// the update is then incomplete and the caller must rewind the step ([`StepStart::rewind`]).
    /// Otherwise returns the number of grains advanced, and whether any grain of `active`
    /// (suspended or not) now fails the test of [`Stepper::grain_fault`] with the bound
    /// `speed_bound_m_s` in the cylinder of `setup` (checked here as the grains are updated;
    /// `grain_fault` then names the first). `active` lists every suspended grain (settled ones are
    /// tested only); other grains are left alone.
    pub fn free_update(
        &self,
        st: &mut State,
        setup: &Setup,
        grid: &VoidageGrid,
        dt_s: f64,
        active: &[usize],
    ) -> Option<(u64, bool)> {
        let (width, height) = (setup.width_m, setup.height_m);
        let lim = Limits {
            floor_m: st.bed_height_m,
            speed_bound_m_s: self.speed_bound_m_s,
        };
        let drag = CellDrag::new(self, grid, dt_s);
        let suspect = AtomicBool::new(false);
        let n = INTERRUPT_CHECK_GRAINS;
        let stopped = AtomicBool::new(false);
        let (grains, xs) = (&setup.grains, &st.x_m);
        let x_of = |i: usize| xs.get(i).copied().unwrap_or_else(|| grains.x_m[i]);
        let moved = st
            .y_m
            .par_chunks_mut(n)
            .zip(st.velocity_m_s.par_chunks_mut(n))
            .zip(st.settled.par_chunks(n))
            .enumerate()
            .map(|(ci, ((ys, speeds), settled))| {
                let base = ci * n;
                let lo = active.partition_point(|&i| i < base);
                let hi = active.partition_point(|&i| i < base + ys.len());
                if lo == hi {
                    return 0;
                }
                if stopped.load(Ordering::Relaxed) || crate::interrupt::requested() {
                    stopped.store(true, Ordering::Relaxed);
                    return 0;
                }
                let mut moved = 0u64;
                let mut bad = false;
                for &i in &active[lo..hi] {
                    let k = i - base;
                    let (y, v) = (&mut ys[k], &mut speeds[k]);
                    let (kind, x) = (grains.kind_of(i), x_of(i));
                    let d = kind.diameter_m;
                    if settled[k] {
                        bad |= Self::faulty(x, *y, d, *v, width, height, lim.speed_bound_m_s);
                        continue;
                    }
                    let g = CellGrain {
                        diameter_m: d,
                        class: kind.class,
                        cell: grid.cell_of(x, *y),
                    };
                    let fault;
                    (*y, *v, fault) = free_step(&drag, &g, *y, *v, 0.5 * d, height + d, lim);
                    moved += 1;
                    bad |= fault || horizontal_fault(x, width);
                }
                if bad {
                    suspect.store(true, Ordering::Relaxed);
                }
                moved
            })
            .sum::<u64>();
        (!stopped.into_inner()).then_some((moved, suspect.into_inner()))
    }

    /// The test of [`Stepper::grain_fault`] (with the speed bound) on grain `gr` of speed `v_m_s`
    /// (m/s) in the cylinder of `setup`.
    pub fn is_faulty(&self, gr: &crate::sample::Grain, v_m_s: f64, setup: &Setup) -> bool {
        Self::faulty(
            gr.x_m,
            gr.y_m,
            gr.diameter_m,
            v_m_s,
            setup.width_m,
            setup.height_m,
            self.speed_bound_m_s,
        )
    }

    /// The test of [`Stepper::grain_fault`] on one grain at (`x`, `y`) of diameter `d` (m) and
    /// speed `v` (m/s) in a cylinder of `width` × `height` (m) with speed bound `bound` (m/s).
    #[allow(clippy::too_many_arguments)]
    fn faulty(x: f64, y: f64, d: f64, v: f64, width: f64, height: f64, bound: f64) -> bool {
        vertical_fault(y, v, height + d, bound) || horizontal_fault(x, width)
    }

    /// Deposition (serial, in ascending grain order: the bed grows as grains join it): every
    /// suspended grain of `active` (ascending grain indices, every suspended grain among them)
    /// touching the bed surface ([`kernel::on_bed`]) joins the bed, at rest on it; with full
    /// physics the bed rises by the grain's real volume over `bed_area_m2`
    /// ([`kernel::bed_rise_m`]). Returns the largest speed of the grains still suspended after
    /// it (each the larger of its speed and its Stokes terminal speed, `stokes_speeds_m_s`; only
    /// its speed where that list is empty), m/s, 0 if none: the bound of the next step
    /// ([`Stepper::step_with_vmax_s`]), found in the same pass.
    pub fn deposit_vmax(
        &self,
        st: &mut State,
        grains: &Grains,
        stokes_speeds_m_s: &[f64],
        active: &[usize],
    ) -> f64 {
        let mut vmax = 0.0f64;
        for &i in active {
            let (y, v) = (&mut st.y_m[i], &mut st.velocity_m_s[i]);
            if st.settled[i] {
                continue;
            }
            let kind = grains.kind_of(i);
            let half_d = 0.5 * kind.diameter_m;
            if on_bed(*y, half_d, st.bed_height_m) {
                st.settled[i] = true;
                *v = 0.0;
                *y = st.bed_height_m + half_d;
                if !self.ideal {
                    st.bed_height_m += bed_rise_m(kind.weight, kind.diameter_m, self.bed_area_m2);
                }
            } else {
                let vs = stokes_speeds_m_s.get(i).copied().unwrap_or(0.0);
                vmax = vmax.max(v.abs().max(vs));
            }
        }
        vmax
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
        let grains = &setup.grains;
        let i = st
            .y_m
            .par_iter()
            .zip(st.velocity_m_s.par_iter())
            .enumerate()
            .position_first(|(i, (&y, &v))| {
                let (x, d) = (st.x_m(grains, i), grains.diameter_m(i));
                Self::faulty(x, y, d, v, width, height, bound)
            })?;
        let (gr, v) = (st.grain(grains, i), st.velocity_m_s[i]);
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

/// The time after a step of `dt_s` from `t_s`, s: landing exactly on `next_event_s` when within a
/// relative 1e-9 of it.
pub fn clock_after(t_s: f64, dt_s: f64, next_event_s: f64) -> f64 {
    let t = t_s + dt_s;
    if (next_event_s - t).abs() <= 1e-9 * next_event_s.max(1.0) {
        next_event_s
    } else {
        t
    }
}

/// Advances the clock of `st` by `dt_s` ([`clock_after`]) and counts the step.
pub fn advance_clock(st: &mut State, dt_s: f64, next_event_s: f64) {
    st.time_s = clock_after(st.time_s, dt_s, next_event_s);
    st.steps += 1;
    st.dt_range_s = (st.dt_range_s.0.min(dt_s), st.dt_range_s.1.max(dt_s));
}
