//! Ideal Stokes with the exponential integrator: every step of an interval between two events
//! at once, grain by grain ([`Stepper::ideal_interval`]), each step the free update of
//! [`kernel`](super::kernel) with [`StokesDrag`].

use super::super::setup::Setup;
use super::super::state::State;
use super::kernel::{free_step, horizontal_fault, on_bed, Limits, StokesDrag, StokesGrain};
use super::stepper::{Stepper, INTERRUPT_CHECK_GRAINS};
use crate::dynamics::phi12;
use crate::fluid::{sphere_mass_kg, DragLaw, SphereDrag};
use crate::sample::Grains;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

/// Grains stepped together (independent chains the processor overlaps).
const L: usize = 8;

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
    /// The factors of every grain of `grains` at the largest step of `stepper` (Stokes drag).
    pub fn new(stepper: &Stepper, grains: &Grains) -> Self {
        let dt = stepper.max_step_s;
        let factors = grains
            .kind
            .par_iter()
            .map(|&k| {
                let g = stepper.stokes_grain(grains.kinds[k as usize].diameter_m);
                factors(g.mass_kg, g.slope_n_s_m, dt)
            })
            .collect();
        Self { dt_s: dt, factors }
    }
}

/// (dt φ₁(−k dt/m), dt² φ₂(−k dt/m)) of a grain of mass `m_kg` and Stokes slope `k_n_s_m` over a
/// step `dt_s`, s and s².
fn factors(m_kg: f64, k_n_s_m: f64, dt_s: f64) -> (f64, f64) {
    let (phi1, phi2) = phi12(-k_n_s_m / m_kg * dt_s);
    (dt_s * phi1, dt_s * dt_s * phi2)
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

impl Stepper {
    /// What [`StokesDrag`] reads of a grain of diameter `d_m` (m), its factors not yet set.
    pub fn stokes_grain(&self, d_m: f64) -> StokesGrain {
        let (rho_p, rho_f) = (self.grain_density_kg_m3, self.fluid_density_kg_m3);
        let stokes = DragLaw::Stokes {
            viscosity_pa_s: self.viscosity_pa_s,
        };
        let m = sphere_mass_kg(d_m, rho_p);
        StokesGrain {
            mass_kg: m,
            body_force_n: -(m - sphere_mass_kg(d_m, rho_f)) * self.gravity_m_s2,
            slope_n_s_m: SphereDrag::new(stokes, d_m, rho_f).slope_n_s_m(0.0),
            dt_phi1_s: 0.0,
            dt2_phi2_s2: 0.0,
        }
    }

    /// ideal-Stokes with the exponential integrator: advances every suspended grain of `st`
    /// through all the steps of an interval between two events at once, `runs` giving the steps
    /// in order as (dt, count) pairs, s. Each step of each grain is the free update of
    /// [`super::kernel::free_step`] with [`StokesDrag`] (the same operations as
    /// [`crate::dynamics::advance`] for Stokes drag, exact for linear drag), then deposition as
    /// [`Stepper::deposit_vmax`] does it; in ideal Stokes the grains do not interact and the bed
    /// does not rise, so every grain's path is its own, and is made grain after grain, its
    /// φ-factors computed once per distinct dt ([`IdealCache`] for the largest) and its state
    /// kept in registers. Grains are taken 8 at a time, in parallel by chunks of
    /// [`INTERRUPT_CHECK_GRAINS`]. The clock is not advanced (see [`super::advance_clock`]).
    /// Returns what stopped the interval and the grain-steps made; on anything but
    /// [`Interval::Done`] the caller must rewind ([`super::StepStart::rewind_all`]): on a fault
    /// (a grain the fault scan would report) the step loop redoes the interval step by step to
    /// report it.
    pub fn ideal_interval(
        &self,
        st: &mut State,
        setup: &Setup,
        runs: &[(f64, u64)],
        cache: &IdealCache,
    ) -> (Interval, u64) {
        let job = Job {
            stepper: self,
            setup,
            xs: if st.x_m.is_empty() {
                &setup.grains.x_m
            } else {
                &st.x_m
            },
            runs,
            cache,
            lim: Limits {
                floor_m: st.bed_height_m,
                speed_bound_m_s: self.speed_bound_m_s,
            },
        };
        let n = INTERRUPT_CHECK_GRAINS;
        let stopped = AtomicBool::new(false);
        let fault = AtomicBool::new(false);
        let moved = st
            .y_m
            .par_chunks_mut(n)
            .zip(st.velocity_m_s.par_chunks_mut(n))
            .zip(st.settled.par_chunks_mut(n))
            .enumerate()
            .map(|(ci, ((ys, speeds), settled))| {
                if stopped.load(Ordering::Relaxed)
                    || fault.load(Ordering::Relaxed)
                    || crate::interrupt::requested()
                {
                    stopped.store(true, Ordering::Relaxed);
                    return 0;
                }
                let (moved, bad) = job.chunk(ci * n, ys, speeds, settled);
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
}

/// One interval of [`Stepper::ideal_interval`].
struct Job<'a> {
    stepper: &'a Stepper,
    setup: &'a Setup,
    /// The horizontal position of every grain, m.
    xs: &'a [f64],
    runs: &'a [(f64, u64)],
    cache: &'a IdealCache,
    lim: Limits,
}

/// [`L`] grains stepped together: each lane's grain, height (m), speed (m/s), half its diameter
/// (m), the height above which its centre is a fault (m), and whether it is still suspended.
#[derive(Clone, Copy)]
struct Lanes {
    grain: [StokesGrain; L],
    y_m: [f64; L],
    v_m_s: [f64; L],
    half_d_m: [f64; L],
    top_m: [f64; L],
    live: [bool; L],
}

impl Job<'_> {
    /// The interval of the chunk of grains starting at grain `base` (heights `ys`, speeds
    /// `speeds`, settled flags `settled`): its grain-steps and whether a grain failed the fault
    /// test.
    fn chunk(
        &self,
        base: usize,
        ys: &mut [f64],
        speeds: &mut [f64],
        settled: &mut [bool],
    ) -> (u64, bool) {
        let width = self.setup.width_m;
        let xs = &self.xs[base..base + ys.len()];
        let mut bad = false;
        // The grains of the chunk still suspended, `L` at a time (the horizontal position, which
        // does not change, tested here).
        let mut live_in_chunk: Vec<usize> = Vec::with_capacity(ys.len());
        for (k, (&x, &st)) in xs.iter().zip(settled.iter()).enumerate() {
            bad |= horizontal_fault(x, width);
            if !st {
                live_in_chunk.push(k);
            }
        }
        let mut moved = 0u64;
        for group in live_in_chunk.chunks(L) {
            let lanes = self.lanes(base, group, ys, speeds);
            let factors = |i: usize| &self.cache.factors[base + group[i]];
            let (lanes, m, b) = self.step_lanes(lanes, group.len(), factors);
            (moved, bad) = (moved + m, bad | b);
            for (i, &g) in group.iter().enumerate() {
                ys[g] = lanes.y_m[i];
                speeds[g] = lanes.v_m_s[i];
                settled[g] = !lanes.live[i];
            }
            if bad {
                break;
            }
        }
        (moved, bad)
    }

    /// The lanes of the grains `group` (indices into `ys` and `speeds`, of the chunk starting at
    /// grain `base`); the lanes past the group are empty.
    fn lanes(&self, base: usize, group: &[usize], ys: &[f64], speeds: &[f64]) -> Lanes {
        let empty = StokesGrain {
            mass_kg: 1.0,
            body_force_n: 0.0,
            slope_n_s_m: 0.0,
            dt_phi1_s: 0.0,
            dt2_phi2_s2: 0.0,
        };
        let mut lanes = Lanes {
            grain: [empty; L],
            y_m: [0.0; L],
            v_m_s: [0.0; L],
            half_d_m: [0.5; L],
            top_m: [0.0; L],
            live: [false; L],
        };
        for (i, &g) in group.iter().enumerate() {
            let d = self.setup.grains.diameter_m(base + g);
            lanes.grain[i] = self.stepper.stokes_grain(d);
            lanes.live[i] = true;
            (lanes.y_m[i], lanes.v_m_s[i]) = (ys[g], speeds[g]);
            lanes.half_d_m[i] = 0.5 * d;
            lanes.top_m[i] = self.setup.height_m + d;
        }
        lanes
    }

    /// Every step of the interval for `lanes`, the first `l` of them holding grains whose
    /// factors at the cached step are `cached(i)`; every lane computes, only the live ones keep
    /// the result. Returns the lanes after them, the grain-steps made and whether a grain failed
    /// the fault test (the lanes then stop).
    #[inline(always)]
    fn step_lanes<'c>(
        &self,
        lanes: Lanes,
        l: usize,
        cached: impl Fn(usize) -> &'c (f64, f64),
    ) -> (Lanes, u64, bool) {
        // In locals, so that the lanes stay in registers.
        let Lanes {
            mut grain,
            mut y_m,
            mut v_m_s,
            half_d_m,
            top_m,
            mut live,
        } = lanes;
        let (lim, floor) = (self.lim, self.lim.floor_m);
        let (mut moved, mut bad) = (0u64, false);
        'runs: for &(dt, count) in self.runs {
            if !live.iter().any(|&x| x) {
                break;
            }
            for (i, g) in grain.iter_mut().enumerate().take(l) {
                (g.dt_phi1_s, g.dt2_phi2_s2) = if dt == self.cache.dt_s {
                    *cached(i)
                } else {
                    factors(g.mass_kg, g.slope_n_s_m, dt)
                };
            }
            let drag = StokesDrag { dt_s: dt };
            for _ in 0..count {
                for i in 0..L {
                    let (y0, v0, half) = (y_m[i], v_m_s[i], half_d_m[i]);
                    let (y1, v1, fault) = free_step(&drag, &grain[i], y0, v0, half, top_m[i], lim);
                    bad |= live[i] && fault;
                    // Deposition (the bed does not rise in ideal Stokes).
                    let lands = on_bed(y1, half, floor);
                    let (y2, v2) = if lands { (floor + half, 0.0) } else { (y1, v1) };
                    y_m[i] = if live[i] { y2 } else { y0 };
                    v_m_s[i] = if live[i] { v2 } else { v0 };
                    moved += live[i] as u64;
                    live[i] &= !lands;
                }
                if bad {
                    break 'runs;
                }
            }
        }
        let lanes = Lanes {
            grain,
            y_m,
            v_m_s,
            half_d_m,
            top_m,
            live,
        };
        (lanes, moved, bad)
    }
}
