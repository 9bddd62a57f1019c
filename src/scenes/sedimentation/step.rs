//! The per-grain stages of a step: its size, the free update of every suspended grain, the
//! deposition on the bed, the clock, and the fault scan.

use super::setup::Setup;
use super::state::State;
use super::voidage::VoidageGrid;
use crate::dynamics::terminal::exponential_near_terminal;
use crate::dynamics::{
    advance, exponential_dallavalle_1d, phi12, DallavalleGrain, DtBasis, Integrator, Unstable,
};
use crate::fluid::newtonian::{stokes_response_time_s, stokes_terminal_velocity_m_s};
use crate::fluid::{sphere_mass_kg, sphere_volume_m3, DragLaw, SphereDrag};
use crate::scenario::{Physics, SampleSpec, Scenario};
use nalgebra::SVector;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

/// Grains updated (or searched, in the contact stage) between two checks for an interrupt
/// request: a few milliseconds of work, so that Ctrl-C/SIGTERM stops even a step of millions of
/// grains within about a second.
pub const INTERRUPT_CHECK_GRAINS: usize = 4096;

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
    /// Keeps the heights and speeds of every grain of `st`.
    pub fn capture(&mut self, st: &State) {
        self.y_m.clear();
        self.y_m.extend(st.grains.iter().map(|g| g.y_m));
        self.v_m_s.clear();
        self.v_m_s.extend_from_slice(&st.velocity_m_s);
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

    /// The Stokes terminal speed of every grain of `st` ([`Stepper::stokes_speed_m_s`]), m/s:
    /// computed once per run for [`Stepper::step_size_s`].
    pub fn stokes_speeds_m_s(&self, st: &State) -> Vec<f64> {
        st.grains
            .iter()
            .map(|gr| self.stokes_speed_m_s(gr.diameter_m))
            .collect()
    }

    /// The step from time `t_s` to `next_event_s` before any bound from the grains: up to the
    /// event, at most `max_step_s`, at least 1e-12 s.
    pub fn clock_step_s(&self, t_s: f64, next_event_s: f64) -> f64 {
        (next_event_s - t_s).min(self.max_step_s).max(1e-12)
    }

    /// The step from `st`: up to `next_event_s`, at most `max_step_s`; full physics also keeps
    /// the fastest suspended grain (its speed, or its Stokes terminal speed if larger, for grains
    /// still accelerating) within half a voidage cell per step. At least 1e-12 s.
    /// `stokes_speeds_m_s` holds each grain's Stokes terminal speed
    /// ([`Stepper::stokes_speeds_m_s`]). The largest speed is searched in parallel (a maximum
    /// does not depend on the order).
    pub fn step_size_s(&self, st: &State, next_event_s: f64, stokes_speeds_m_s: &[f64]) -> f64 {
        let vmax = if self.ideal {
            0.0
        } else {
            st.velocity_m_s
                .par_iter()
                .zip(st.settled.par_iter())
                .zip(stokes_speeds_m_s.par_iter())
                .with_min_len(INTERRUPT_CHECK_GRAINS)
                .filter(|((_, s), _)| !**s)
                .map(|((v, _), &vs)| v.abs().max(vs))
                .reduce(|| 0.0, f64::max)
        };
        self.step_with_vmax_s(st.time_s, next_event_s, vmax)
    }

    /// The step of [`Stepper::step_size_s`] from time `t_s` given the largest speed `vmax_m_s`
    /// of the suspended grains (each the larger of its speed and its Stokes terminal speed),
    /// m/s, as [`Stepper::deposit_vmax`] returns it.
    pub fn step_with_vmax_s(&self, t_s: f64, next_event_s: f64, vmax_m_s: f64) -> f64 {
        let mut dt = (next_event_s - t_s).min(self.max_step_s);
        if !self.ideal && vmax_m_s > 0.0 {
            dt = dt.min(0.5 * self.cell_m / vmax_m_s);
        }
        dt.max(1e-12)
    }

    /// Advances every suspended grain of `active` (ascending grain indices of `st`) by `dt_s`
    /// with the exact (exponential) or chosen integrator of [`crate::dynamics`], vertically,
    /// under gravity, buoyancy and the drag of its voidage cell; a grain reaching the bed surface
    /// stops on it (flagged by [`Stepper::deposit`]). In parallel, by chunks of
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
        let bound = self.speed_bound_m_s;
        let suspect = AtomicBool::new(false);
        let floor = st.bed_height_m;
        let fast = self.fast_path(grid);
        let n = INTERRUPT_CHECK_GRAINS;
        let stopped = AtomicBool::new(false);
        let moved = st
            .grains
            .par_chunks_mut(n)
            .zip(st.velocity_m_s.par_chunks_mut(n))
            .zip(st.settled.par_chunks(n))
            .enumerate()
            .map(|(ci, ((grains, speeds), settled))| {
                let base = ci * n;
                let lo = active.partition_point(|&i| i < base);
                let hi = active.partition_point(|&i| i < base + grains.len());
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
                    let (gr, v) = (&mut grains[k], &mut speeds[k]);
                    if settled[k] {
                        bad |= Self::faulty(gr, *v, width, height, bound);
                        continue;
                    }
                    let cell = grid.cell_of(gr.x_m, gr.y_m);
                    let (v1, dx) =
                        self.grain_step(grid, fast, gr.diameter_m, gr.class, cell, *v, dt_s);
                    *v = v1;
                    gr.y_m += dx;
                    if gr.y_m - 0.5 * gr.diameter_m <= floor {
                        gr.y_m = floor + 0.5 * gr.diameter_m;
                    }
                    moved += 1;
                    bad |= Self::faulty(gr, *v, width, height, bound);
                }
                if bad {
                    suspect.store(true, Ordering::Relaxed);
                }
                moved
            })
            .sum::<u64>();
        (!stopped.into_inner()).then_some((moved, suspect.into_inner()))
    }

    /// Whether [`Stepper::grain_step`] takes the exponential step of Dallavalle's drag with the
    /// Di Felice factor ([`exponential_near_terminal`], else [`exponential_dallavalle_1d`])
    /// rather than [`advance`] with the cell's drag: the exponential integrator on a Di Felice
    /// grid.
    pub fn fast_path(&self, grid: &VoidageGrid) -> bool {
        self.integrator == Integrator::Exponential && grid.is_di_felice()
    }

    /// The free update of one suspended grain over `dt_s`: diameter `d_m`, size class `class`,
    /// in voidage cell `cell` of `grid`, vertical velocity `v_m_s` (m/s), under gravity,
    /// buoyancy and its cell's drag, with `fast` = [`Stepper::fast_path`]. Returns its new
    /// velocity (m/s) and its displacement (m), before any stop on the bed.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn grain_step(
        &self,
        grid: &VoidageGrid,
        fast: bool,
        d_m: f64,
        class: usize,
        cell: usize,
        v_m_s: f64,
        dt_s: f64,
    ) -> (f64, f64) {
        let d = d_m;
        let (g, rho_f) = (self.gravity_m_s2, self.fluid_density_kg_m3);
        let m = sphere_mass_kg(d, self.grain_density_kg_m3);
        let w = -(m - sphere_mass_kg(d, rho_f)) * g;
        let quick = fast.then(|| {
            let voidage = grid.voidage(cell);
            let mut grain = DallavalleGrain {
                diameter_m: d,
                fluid_density_kg_m3: rho_f,
                viscosity_pa_s: self.viscosity_pa_s,
                voidage,
                // Read only by the solve below, which computes it.
                ln_voidage: 0.0,
                mass_kg: m,
                body_force_n: w,
            };
            grid.terminal_table(class, d)
                .and_then(|t| exponential_near_terminal(t, &grain, v_m_s, dt_s))
                .or_else(|| {
                    grain.ln_voidage = voidage.ln();
                    exponential_dallavalle_1d(&grain, v_m_s, dt_s)
                })
        });
        match quick.flatten() {
            Some(step) => step,
            None => {
                let drag = grid.drag(d, cell);
                let w = SVector::<f64, 1>::new(w);
                let v0 = SVector::<f64, 1>::new(v_m_s);
                let step = advance(self.integrator, &drag, m, &w, &v0, dt_s);
                (step.velocity_m_s[0], step.displacement_m[0])
            }
        }
    }

    /// The test of [`Stepper::grain_fault`] (with the speed bound) on grain `gr` of speed `v_m_s`
    /// (m/s) in the cylinder of `setup`.
    pub fn is_faulty(&self, gr: &crate::sample::Grain, v_m_s: f64, setup: &Setup) -> bool {
        Self::faulty(
            gr,
            v_m_s,
            setup.width_m,
            setup.height_m,
            self.speed_bound_m_s,
        )
    }

    /// The test of [`Stepper::grain_fault`] on one grain of speed `v` (m/s) in a cylinder of
    /// `width` × `height` (m) with speed bound `bound` (m/s).
    fn faulty(gr: &crate::sample::Grain, v: f64, width: f64, height: f64, bound: f64) -> bool {
        !(gr.y_m.is_finite() && v.is_finite() && gr.x_m.is_finite())
            || v.abs() > bound
            || gr.y_m > height + gr.diameter_m
            || gr.x_m < -1e-12
            || gr.x_m > width + 1e-12
    }

    /// ideal-Stokes with the exponential integrator: advances every suspended grain of `st`
    /// through all the steps of an interval between two events at once, `runs` giving the steps
    /// in order as (dt, count) pairs, s. The result is bit for bit that of the step loop
    /// ([`Stepper::free_update`], [`Stepper::grain_fault`], [`Stepper::deposit`] after each
    /// step): Stokes drag is linear, so the exponential update (`crate::dynamics`, exact for
    /// linear drag) is done here with the same operations, but for one grain after another, its
    /// φ-functions computed once per distinct dt and its state kept in registers; in ideal-Stokes
    /// the grains do not interact and the bed does not rise, so every grain's path is its own.
    /// Grains are taken eight at a time (independent chains the processor overlaps), in parallel
    /// by chunks of [`INTERRUPT_CHECK_GRAINS`]. Grains deposit on the bed as they reach it.
    /// The clock is not advanced (see [`advance_clock`]). Returns what stopped the interval and
    /// the grain-steps made; on anything but [`Interval::Done`] the caller must rewind
    /// ([`StepStart::rewind_all`]): on a fault (a grain the fault scan would report) the step
    /// loop redoes the interval step by step to report it.
    pub fn ideal_interval(
        &self,
        st: &mut State,
        setup: &Setup,
        runs: &[(f64, u64)],
        cache: &IdealCache,
    ) -> (Interval, u64) {
        const L: usize = 8;
        let floor = st.bed_height_m;
        let (g_acc, rho_p, rho_f) = (
            self.gravity_m_s2,
            self.grain_density_kg_m3,
            self.fluid_density_kg_m3,
        );
        let (width, height) = (setup.width_m, setup.height_m);
        let bound = self.speed_bound_m_s;
        let stokes = DragLaw::Stokes {
            viscosity_pa_s: self.viscosity_pa_s,
        };
        let n = INTERRUPT_CHECK_GRAINS;
        let stopped = AtomicBool::new(false);
        let fault = AtomicBool::new(false);
        let moved = st
            .grains
            .par_chunks_mut(n)
            .zip(st.velocity_m_s.par_chunks_mut(n))
            .zip(st.settled.par_chunks_mut(n))
            .enumerate()
            .map(|(ci, ((grains, speeds), settled))| {
                if stopped.load(Ordering::Relaxed)
                    || fault.load(Ordering::Relaxed)
                    || crate::interrupt::requested()
                {
                    stopped.store(true, Ordering::Relaxed);
                    return 0;
                }
                let mut moved = 0u64;
                let mut bad = false;
                let base = ci * n;
                // The grains of the chunk still suspended, `L` at a time.
                let mut live_in_chunk: Vec<usize> = Vec::with_capacity(grains.len());
                for (k, (gr, &st)) in grains.iter().zip(settled.iter()).enumerate() {
                    let x = gr.x_m;
                    bad |= !x.is_finite() || x < -1e-12 || x > width + 1e-12;
                    if !st {
                        live_in_chunk.push(k);
                    }
                }
                for lanes in live_in_chunk.chunks(L) {
                    let l = lanes.len();
                    let mut live = [false; L];
                    let (mut y, mut v, mut d) = ([0.0; L], [0.0; L], [1.0; L]);
                    let (mut m, mut w, mut k) = ([1.0; L], [0.0; L], [0.0; L]);
                    for (i, &g) in lanes.iter().enumerate() {
                        let gr = &grains[g];
                        live[i] = true;
                        (y[i], v[i], d[i]) = (gr.y_m, speeds[g], gr.diameter_m);
                        m[i] = sphere_mass_kg(d[i], rho_p);
                        w[i] = -(m[i] - sphere_mass_kg(d[i], rho_f)) * g_acc;
                        k[i] = SphereDrag::new(stokes, d[i], rho_f).slope_n_s_m(0.0);
                    }
                    let half = d.map(|x| 0.5 * x);
                    for &(dt, count) in runs {
                        if !live.iter().any(|&x| x) {
                            break;
                        }
                        let (mut c1, mut c2) = ([0.0; L], [0.0; L]);
                        for i in 0..l {
                            (c1[i], c2[i]) = if dt == cache.dt_s {
                                cache.factors[base + lanes[i]]
                            } else {
                                let (phi1, phi2) = phi12(-k[i] / m[i] * dt);
                                (dt * phi1, dt * dt * phi2)
                            };
                        }
                        for _ in 0..count {
                            // Every lane computes; only the live ones keep the result.
                            for i in 0..L {
                                // As `crate::dynamics::exponential` for Stokes drag.
                                let a0 = (w[i] - v[i] * k[i]) / m[i];
                                let v1 = v[i] + a0 * c1[i];
                                let dx = v[i] * dt + a0 * c2[i];
                                let mut y1 = y[i] + dx;
                                if y1 - half[i] <= floor {
                                    y1 = floor + half[i];
                                }
                                // As `grain_fault` (the horizontal position is checked above).
                                bad |= live[i]
                                    && (!(y1.is_finite() && v1.is_finite())
                                        || v1.abs() > bound
                                        || y1 > height + d[i]);
                                // As `deposit` (the bed does not rise in ideal-Stokes).
                                let lands = y1 - half[i] <= floor + 1e-15;
                                let (y2, v2) = if lands {
                                    (floor + half[i], 0.0)
                                } else {
                                    (y1, v1)
                                };
                                y[i] = if live[i] { y2 } else { y[i] };
                                v[i] = if live[i] { v2 } else { v[i] };
                                moved += live[i] as u64;
                                live[i] &= !lands;
                            }
                            if bad {
                                break;
                            }
                        }
                        if bad {
                            break;
                        }
                    }
                    for (i, &g) in lanes.iter().enumerate() {
                        grains[g].y_m = y[i];
                        speeds[g] = v[i];
                        settled[g] = !live[i];
                    }
                    if bad {
                        break;
                    }
                }
                if bad {
                    fault.store(true, Ordering::Relaxed);
                }
                moved
            })
            .sum::<u64>();
        let end = if fault.into_inner() {
            Interval::Fault
        } else if stopped.into_inner() {
            Interval::Interrupted
        } else {
            Interval::Done
        };
        (end, moved)
    }

    /// Deposition (serial, in ascending grain order: the bed grows as grains join it): every
    /// suspended grain of `active` (ascending grain indices, every suspended grain among them)
    /// touching the bed surface joins the bed, at rest on it; with full physics the bed rises by
    /// the grain's real volume over `bed_area_m2`.
    pub fn deposit(&self, st: &mut State, active: &[usize]) {
        for &i in active {
            let (gr, v, settled) = (
                &mut st.grains[i],
                &mut st.velocity_m_s[i],
                &mut st.settled[i],
            );
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

    /// [`Stepper::deposit`], returning the largest speed of the grains still suspended after it
    /// (each the larger of its speed and its Stokes terminal speed, `stokes_speeds_m_s`), m/s,
    /// 0 if none: the bound of the next step ([`Stepper::step_with_vmax_s`]), found in the same
    /// pass. `active` as for [`Stepper::deposit`].
    pub fn deposit_vmax(&self, st: &mut State, stokes_speeds_m_s: &[f64], active: &[usize]) -> f64 {
        let mut vmax = 0.0f64;
        for &i in active {
            let (gr, v, settled, vs) = (
                &mut st.grains[i],
                &mut st.velocity_m_s[i],
                &mut st.settled[i],
                stokes_speeds_m_s[i],
            );
            if *settled {
                continue;
            }
            if gr.y_m - 0.5 * gr.diameter_m <= st.bed_height_m + 1e-15 {
                *settled = true;
                *v = 0.0;
                gr.y_m = st.bed_height_m + 0.5 * gr.diameter_m;
                if !self.ideal {
                    st.bed_height_m +=
                        gr.weight * sphere_volume_m3(gr.diameter_m) / self.bed_area_m2;
                }
            } else {
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
        let i = st
            .grains
            .par_iter()
            .zip(st.velocity_m_s.par_iter())
            .position_first(|(gr, v)| Self::faulty(gr, *v, width, height, bound))?;
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

/// The factors dt φ₁ and dt² φ₂ of the exponential update of every grain at one step size
/// (ideal-Stokes: the largest step, which most steps take), computed once per run for
/// [`Stepper::ideal_interval`].
#[derive(Clone, Debug, Default)]
pub struct IdealCache {
    /// The step they are for, s (0: none; every step is longer).
    pub dt_s: f64,
    /// (dt φ₁, dt² φ₂) of each grain, s and s².
    pub factors: Vec<(f64, f64)>,
}

impl IdealCache {
    /// The factors of every grain of `st` at the largest step of `stepper` (Stokes drag).
    pub fn new(stepper: &Stepper, st: &State) -> Self {
        let stokes = DragLaw::Stokes {
            viscosity_pa_s: stepper.viscosity_pa_s,
        };
        let dt = stepper.max_step_s;
        let factors = st
            .grains
            .par_iter()
            .map(|gr| {
                let d = gr.diameter_m;
                let m = sphere_mass_kg(d, stepper.grain_density_kg_m3);
                let k = SphereDrag::new(stokes, d, stepper.fluid_density_kg_m3).slope_n_s_m(0.0);
                let (phi1, phi2) = phi12(-k / m * dt);
                (dt * phi1, dt * dt * phi2)
            })
            .collect();
        Self { dt_s: dt, factors }
    }
}

/// What ended an interval of [`Stepper::ideal_interval`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interval {
    /// Every step made.
    Done,
    /// An interrupt was requested: the interval is incomplete.
    Interrupted,
    /// A grain would be reported by the fault scan: the interval is incomplete.
    Fault,
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
