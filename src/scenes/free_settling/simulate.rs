//! The step loop of one sphere as named stages — take a step (the free engine or a Rapier world),
//! check stability, locate events within the step (surface entry, detectors, probes), record,
//! decide whether to stop — and the runners over all spheres (rayon, results in input order),
//! with one dispatch on the dimension and the engine.

use super::scene::Scene;
use super::setup::{uses_rapier, RunOptions, SphereSetup};
use super::submerged::{added_mass_kg, analytic_at, submerged_step};
use crate::contact::rayleigh_time_s;
use crate::dynamics::{advance, explicit_stable_dt_s, Monitor, Motion, Step, Unstable};
use crate::engine::{dim2, dim3, EngineSettings, SphereWorld};
use crate::fluid::bingham::reynolds_bingham;
use crate::fluid::immersion;
use crate::fluid::{sphere_mass_kg, DragLaw, DragRegime};
use crate::scenario::inputs::SphereCase;
use crate::scenario::{Dim, Submergence};
use nalgebra::SVector;
use std::collections::VecDeque;

/// Steps of one sphere between two looks at [`crate::interrupt::requested`]: ~0.1 ms of the
/// free engine, ~50 ms of a Rapier world, so an interruption is honoured well within a second.
pub const INTERRUPT_CHECK_STEPS: u64 = 1024;

/// One recorded time-series row.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Time, s.
    pub time_s: f64,
    /// Depth of the centre below the free surface, m.
    pub depth_m: f64,
    /// Downward velocity, m/s.
    pub velocity_m_s: f64,
    /// Analytic velocity (Stokes drag only), m/s.
    pub velocity_analytic_m_s: Option<f64>,
    /// Analytic depth (Stokes drag only), m.
    pub depth_analytic_m: Option<f64>,
}

/// Why a sphere's run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StopReason {
    /// Reached `time.end_s`.
    EndTime,
    /// Reached the container bottom.
    Bottom,
    /// Held at rest by the yield stress (nothing can change afterwards).
    Static,
    /// The terminal-velocity window criterion was met.
    Steady,
}

impl StopReason {
    /// CSV label.
    pub fn label(self) -> &'static str {
        match self {
            Self::EndTime => "end_time",
            Self::Bottom => "bottom",
            Self::Static => "static",
            Self::Steady => "steady",
        }
    }
}

/// Result of one sphere.
#[derive(Clone, Debug)]
pub struct SphereResult {
    /// The sphere.
    pub case: SphereCase,
    /// Terminal velocity of the simulation: the rolling-window reading when configured, else the
    /// section reading, else the final velocity, m/s.
    pub v_simulated_m_s: f64,
    /// Whether the rolling-window criterion was met (None without a window).
    pub terminal_steady: Option<bool>,
    /// Section reading (fixed detectors), m/s.
    pub v_section_m_s: Option<f64>,
    /// Steadiness over the fixed section (None without a section reading).
    pub steady_in_section: Option<bool>,
    /// Force-balance terminal velocity, m/s.
    pub v_force_balance_m_s: f64,
    #[cfg_attr(not(test), allow(dead_code))] // read by the unit tests
    /// The force balance sits on a jump of the drag law.
    pub force_balance_at_jump: bool,
    /// Stokes terminal velocity (eq. 21) when the law is Stokes, m/s.
    pub v_analytic_m_s: Option<f64>,
    /// Regime label at the end (`static`, `jump`, a branch of eq. 19, or `smooth`).
    pub regime: DragRegime,
    /// Bingham Reynolds number at the simulated terminal velocity (eq. 18), if Bingham.
    pub re_bingham: Option<f64>,
    /// Particle Reynolds number ρ_f |v| d / η at the simulated terminal velocity (f-EDEM eq. 6),
    /// if the drag law is Newtonian (Stokes, Dallavalle or a C_d correlation).
    pub reynolds: Option<f64>,
    /// Max over the run of |v − v_analytic| / v_t (Stokes only).
    pub max_velocity_error_rel: Option<f64>,
    /// Particle response time m/(dF/dv) at the start, s (Stokes: ρ d²/18μ).
    pub response_time_s: f64,
    /// Rayleigh time (f-EDEM eq. 22) if E and ν are given, s.
    pub rayleigh_time_s: Option<f64>,
    /// Velocities at the probe times `[measure].velocity_at_s`: (time, simulated, analytic).
    pub probes: Vec<(f64, f64, Option<f64>)>,
    /// Recorded time series.
    pub samples: Vec<Sample>,
    /// Steps taken.
    pub steps: u64,
    /// Time at the end, s.
    pub end_time_s: f64,
    /// Why the run ended.
    pub stop: StopReason,
    /// Speed when the lowest point reached the free surface, m/s (drops).
    pub entry_velocity_m_s: Option<f64>,
    /// Final depth of the sphere's lowest point below the free surface, m.
    pub final_bottom_depth_m: f64,
    /// Time at which the sphere came to rest, s (None if it never stopped).
    pub stop_time_s: Option<f64>,
}

/// Why the spheres of a run did not all finish.
#[derive(Debug)]
pub enum Halt {
    /// A sphere went unstable.
    Unstable(Unstable),
    /// Ctrl-C/SIGTERM ([`crate::interrupt::requested`]).
    Interrupted,
}

impl From<Unstable> for Halt {
    fn from(u: Unstable) -> Self {
        Self::Unstable(u)
    }
}

/// Runs every sphere of a free-settling scenario on the free engine, in parallel (rayon);
/// results in input order. Not interruptible (see [`run_scene_cases`]).
pub fn run(
    sc: Scene,
    cases: &[SphereCase],
    opts: RunOptions,
) -> Result<Vec<SphereResult>, Unstable> {
    run_cases(sc, cases, opts, false, false).map_err(uninterruptible)
}

/// Runs every sphere through its own Rapier world with the force hook (`engine = "rapier"`):
/// the same scene as the free engine, through the contact pipeline. It must give the same answer
/// (src/scenes/free_settling/tests/rapier.rs); it costs ~300× more per step.
#[cfg(test)]
pub fn run_rapier(
    sc: Scene,
    cases: &[SphereCase],
    opts: RunOptions,
) -> Result<Vec<SphereResult>, Unstable> {
    run_cases(sc, cases, opts, true, false).map_err(uninterruptible)
}

/// Runs every sphere of the scene `sc` on the engine its scenario asks for, stopping within
/// [`INTERRUPT_CHECK_STEPS`] steps of every running sphere once an interruption is requested.
pub fn run_scene_cases(
    sc: Scene,
    cases: &[SphereCase],
    opts: RunOptions,
) -> Result<Vec<SphereResult>, Halt> {
    run_cases(sc, cases, opts, uses_rapier(sc.common), true)
}

fn uninterruptible(h: Halt) -> Unstable {
    match h {
        Halt::Unstable(u) => u,
        Halt::Interrupted => unreachable!("an uninterruptible run was interrupted"),
    }
}

/// The one dispatch on dimension and engine: every case in parallel, results in input order,
/// the first halt wins.
fn run_cases(
    sc: Scene,
    cases: &[SphereCase],
    opts: RunOptions,
    rapier: bool,
    interruptible: bool,
) -> Result<Vec<SphereResult>, Halt> {
    use rayon::prelude::*;
    let on = interruptible;
    let one = |c: &SphereCase| match (sc.common.dimension, rapier) {
        (Dim::Two, false) => run_sphere_with::<2>(sc, c, opts, None, on),
        (Dim::Three, false) => run_sphere_with::<3>(sc, c, opts, None, on),
        (Dim::Two, true) => rapier_sphere::<2, dim2::World>(sc, c, opts, on),
        (Dim::Three, true) => rapier_sphere::<3, dim3::World>(sc, c, opts, on),
    };
    cases.par_iter().map(one).collect()
}

/// Runs one sphere in `D` dimensions (vertical = last axis) on the free engine.
#[cfg(test)]
pub fn run_sphere<const D: usize>(
    sc: Scene,
    case: &SphereCase,
    opts: RunOptions,
) -> Result<SphereResult, Unstable> {
    run_sphere_with::<D>(sc, case, opts, None, false).map_err(uninterruptible)
}

/// A step taken by an engine instead of [`advance`]: given dt, advance the sphere and report its
/// new velocity and displacement.
pub type ExternalStep<'a, const D: usize> = &'a mut dyn FnMut(f64) -> Result<Step<D>, Unstable>;

/// The state of one sphere's run.
struct State<const D: usize> {
    v: SVector<f64, D>,
    depth: f64,
    t: f64,
    step: u64,
    monitor: Monitor,
    motion: Motion,
    entry: Option<f64>,
    samples: Vec<Sample>,
    probes: Vec<(f64, f64, Option<f64>)>,
    /// Rolling window of (time, depth, speed), oldest first; the front stays at or above the
    /// depth one window length up.
    trail: VecDeque<(f64, f64, f64)>,
    terminal: Option<(f64, bool)>,
    cross_top: Option<(f64, f64)>, // (time, velocity)
    cross_bottom: Option<(f64, f64)>,
    max_err: f64,
    /// The history-force state ([`super::transient`]).
    body: Option<crate::dynamics::transient::TransientBody>,
    /// Downward speeds at the probe times inside the current step, taken from the history
    /// state before the step: (time, speed).
    peeked: Vec<(f64, f64)>,
}

/// The loop of one sphere, with the steps taken by `external` (a Rapier world) when given.
fn run_sphere_with<const D: usize>(
    sc: Scene,
    case: &SphereCase,
    opts: RunOptions,
    mut external: Option<ExternalStep<'_, D>>,
    interruptible: bool,
) -> Result<SphereResult, Halt> {
    let su = SphereSetup::<D>::new(sc, case, opts);
    let d = su.d_m;
    let mut st = State {
        v: su.down * su.v0_m_s,
        depth: su.depth0_m,
        t: 0.0,
        step: 0,
        monitor: Monitor::default(),
        motion: Motion::Moving,
        entry: (su.crossing && su.depth0_m + 0.5 * d >= 0.0).then_some(su.v0_m_s),
        samples: Vec::new(),
        probes: Vec::with_capacity(su.probe_times_s.len()),
        trail: VecDeque::from([(0.0, su.depth0_m, su.v0_m_s)]),
        terminal: None,
        cross_top: None,
        cross_bottom: None,
        max_err: 0.0,
        body: su.transient.as_ref().and_then(|t| t.body(su.v0_m_s)),
        peeked: Vec::new(),
    };
    if opts.timeseries {
        st.samples.push(sample(&su, 0.0, st.depth, su.v0_m_s));
    }
    let mut stop = StopReason::EndTime;
    while st.step < su.n_steps {
        if interruptible
            && st.step.is_multiple_of(INTERRUPT_CHECK_STEPS)
            && crate::interrupt::requested()
        {
            return Err(Halt::Interrupted);
        }
        let s = match external.as_mut() {
            Some(ext) => ext(su.dt_s)?,
            None => free_step(&su, &mut st, opts),
        };
        check_stable(&su, &mut st, &s, case)?;
        let depth_new = st.depth - s.displacement_m[D - 1];
        st.step += 1;
        let t_new = st.step as f64 * su.dt_s;
        locate_events(&su, &mut st, opts, -s.velocity_m_s[D - 1], depth_new, t_new);
        st.v = s.velocity_m_s;
        st.depth = depth_new;
        st.t = t_new;
        st.motion = s.motion;
        let speed = -st.v[D - 1];
        if opts.timeseries && (st.step.is_multiple_of(su.record_every) || st.step == su.n_steps) {
            st.samples.push(sample(&su, st.t, st.depth, speed));
        }
        if let Some(reason) = stop_reason(&su, &mut st, speed) {
            stop = reason;
            break;
        }
    }
    if opts.timeseries && st.samples.last().map(|s| s.time_s) != Some(st.t) {
        st.samples.push(sample(&su, st.t, st.depth, -st.v[D - 1]));
    }
    Ok(finish(&su, st, case, stop))
}

/// A time-series row, with the Stokes solution beside it when the law is Stokes.
fn sample<const D: usize>(su: &SphereSetup<D>, t: f64, depth: f64, vel: f64) -> Sample {
    let an = analytic_at(su, t);
    Sample {
        time_s: t,
        depth_m: depth,
        velocity_m_s: vel,
        velocity_analytic_m_s: an.map(|a| a.0),
        depth_analytic_m: an.map(|a| su.depth0_m + a.1),
    }
}

/// Stage 1, free engine: one step of [`advance`]. A drop crossing the surface with full
/// submergence falls exactly to the surface, then takes the rest of the step with the full
/// fluid forces (event location, so entry is not late by a step); partial submergence scales
/// drag and buoyancy by [`immersion`] at the start of the step.
fn free_step<const D: usize>(su: &SphereSetup<D>, st: &mut State<D>, opts: RunOptions) -> Step<D> {
    let (d, g, dt, m) = (su.d_m, su.g_m_s2, su.dt_s, su.m_kg);
    if !su.crossing {
        let (v, depth, t) = (st.v, st.depth, st.t);
        if let Some(body) = st.body.as_mut() {
            st.peeked.clear();
            for &tp in su
                .probe_times_s
                .iter()
                .filter(|&&tp| tp > t && tp <= t + dt * (1.0 + 1e-12))
            {
                let part =
                    submerged_step(su, Some(body), opts.integrator, &v, depth, tp - t, false);
                st.peeked.push((tp, -part.velocity_m_s[D - 1]));
            }
        }
        return submerged_step(su, st.body.as_mut(), opts.integrator, &v, depth, dt, true);
    }
    let am = added_mass_kg(su); // C_m m_f of the immersed volume: m + fv·am
    let m_in = m + am;
    let gap = -(st.depth + 0.5 * d); // lowest point above the surface, m
    let s_down = -st.v[D - 1];
    let free_fall = s_down * dt + 0.5 * g * dt * dt;
    if su.submergence == Submergence::Full && gap > 0.0 && free_fall > gap {
        let t_c = 2.0 * gap / (s_down + (s_down * s_down + 2.0 * g * gap).sqrt());
        let v_c = st.v + su.down * (g * t_c);
        st.entry = Some(s_down + g * t_c);
        let rest = advance(opts.integrator, &su.drag, m_in, &su.w_n, &v_c, dt - t_c);
        Step {
            displacement_m: su.down * gap + rest.displacement_m,
            ..rest
        }
    } else {
        let (fv, fa) = immersion(st.depth, d, su.submergence);
        let w_now = su.down * (m * g - fv * su.m_fluid_kg * g);
        let m_now = m + fv * am;
        advance(
            opts.integrator,
            &su.drag.scaled(fa),
            m_now,
            &w_now,
            &st.v,
            dt,
        )
    }
}

/// Stage 2: the new velocity must stay below the physical speed bound and must not grow away
/// from the force balance ([`Monitor`]).
fn check_stable<const D: usize>(
    su: &SphereSetup<D>,
    st: &mut State<D>,
    s: &Step<D>,
    case: &SphereCase,
) -> Result<(), Unstable> {
    let (v, v_new) = (st.v, s.velocity_m_s);
    let overshoot = v_new.norm() > su.speed_bound_m_s;
    let growing = st.monitor.check(
        (v - su.v_eq_m_s).as_slice(),
        (v_new - su.v_eq_m_s).as_slice(),
    );
    if !overshoot && growing.is_none() {
        return Ok(());
    }
    let what = growing.unwrap_or_else(|| {
        format!(
            "speed {:.3e} m/s is above the physical bound 2·max(v₀, v_terminal) = {:.3e} m/s",
            v_new.norm(),
            su.speed_bound_m_s
        )
    });
    // A velocity that reverses under a yield-stress drag is the explicit scheme failing to
    // hold the body at rest (the drag is set-valued there): no dt cures that.
    let yield_chatter = su.drag.static_resistance_n() > 0.0 && v.dot(&v_new) < 0.0;
    let dt = su.dt_s;
    Err(Unstable {
        body: case.id.clone(),
        time_s: (st.step + 1) as f64 * dt,
        step: st.step + 1,
        what: if yield_chatter {
            format!("{what}: the velocity reverses at the yield-stress stop (explicit drag chatters about rest)")
        } else {
            what
        },
        dt_s: dt,
        stable_dt_s: if yield_chatter {
            0.0
        } else {
            explicit_stable_dt_s(su.m_kg, s.drag_slope_n_s_m)
        },
        dt_basis: crate::dynamics::DtBasis::ExplicitDrag,
    })
}

/// Stage 3: events inside the step from `st` (time `st.t`) to `depth_new` at `t_new`, speed
/// `speed1`: surface entry and detector crossings (interpolated), probe velocities (dense
/// output: the same scheme over the part of the step) and the error against Stokes.
fn locate_events<const D: usize>(
    su: &SphereSetup<D>,
    st: &mut State<D>,
    opts: RunOptions,
    speed1: f64,
    depth_new: f64,
    t_new: f64,
) {
    let (d, dt, depth, t) = (su.d_m, su.dt_s, st.depth, st.t);
    let speed0 = -st.v[D - 1];
    if su.crossing && st.entry.is_none() && depth_new + 0.5 * d >= 0.0 {
        let f = (-0.5 * d - depth) / (depth_new - depth);
        st.entry = Some(speed0 + f * (speed1 - speed0));
    }
    if let Some((top, bot, _)) = su.section {
        for (level, slot) in [(top, &mut st.cross_top), (bot, &mut st.cross_bottom)] {
            if slot.is_none() && depth < level && depth_new >= level {
                let f = (level - depth) / (depth_new - depth);
                *slot = Some((t + f * dt, speed0 + f * (speed1 - speed0)));
            }
        }
    }
    for &tp in &su.probe_times_s {
        if tp > t && tp <= t_new + 1e-12 * dt {
            let speed = if let Some(&(_, s)) = st.peeked.iter().find(|p| p.0 == tp) {
                s
            } else if su.transient.is_some() && !su.crossing {
                let (v, depth) = (st.v, st.depth);
                let part = submerged_step(su, None, opts.integrator, &v, depth, tp - t, false);
                -part.velocity_m_s[D - 1]
            } else {
                let part = advance(opts.integrator, &su.drag, su.m_kg, &su.w_n, &st.v, tp - t);
                -part.velocity_m_s[D - 1]
            };
            let an = analytic_at(su, tp).map(|a| a.0);
            st.probes.push((tp, speed, an));
        }
    }
    if let (Some((vt, _)), Some((va, _))) = (su.analytic, analytic_at(su, t_new)) {
        st.max_err = st.max_err.max((speed1 - va).abs() / vt.abs());
    }
}

/// Stage 4: whether to stop after this step: the rolling terminal window is steady (with a
/// window), the bottom is reached (without one), or the yield stress holds the sphere.
fn stop_reason<const D: usize>(
    su: &SphereSetup<D>,
    st: &mut State<D>,
    speed: f64,
) -> Option<StopReason> {
    let (t, depth) = (st.t, st.depth);
    if let Some((len, tol)) = su.window {
        let trail = &mut st.trail;
        trail.push_back((t, depth, speed));
        let level = depth - len;
        while trail.len() > 2 && trail[1].1 <= level {
            trail.pop_front();
        }
        if trail[0].1 <= level {
            let (ta, da, va) = trail[0];
            let (tb, db, vb) = trail[1];
            let f = if db > da {
                (level - da) / (db - da)
            } else {
                1.0
            };
            let t_level = ta + f * (tb - ta);
            let v_level = va + f * (vb - va);
            let v_win = len / (t - t_level);
            let steady = (speed - v_level).abs() <= tol * v_win.abs();
            st.terminal = Some((v_win, steady));
            if steady {
                return Some(StopReason::Steady);
            }
        }
    } else if depth >= su.bottom_m {
        return Some(StopReason::Bottom);
    }
    (st.motion == Motion::Stuck && st.v.iter().all(|x| *x == 0.0)).then_some(StopReason::Static)
}

/// Stage 5: the readings of the finished run.
fn finish<const D: usize>(
    su: &SphereSetup<D>,
    st: State<D>,
    case: &SphereCase,
    stop: StopReason,
) -> SphereResult {
    let sp = &case.spec;
    let d = su.d_m;
    let final_speed = -st.v[D - 1];
    let (v_section, steady_in_section) = match (su.section, st.cross_top, st.cross_bottom) {
        (Some((top, bot, tol)), Some((t1, v1)), Some((t2, v2))) => {
            let vs = (bot - top) / (t2 - t1);
            (Some(vs), Some((v2 - v1).abs() <= tol * vs.abs()))
        }
        _ => (None, None),
    };
    let v_sim = if stop == StopReason::Static {
        0.0
    } else {
        st.terminal
            .map(|x| x.0)
            .or(v_section)
            .unwrap_or(final_speed)
    };
    let fb_speed = su.fb_speed_m_s;
    let regime = if stop == StopReason::Static {
        DragRegime::Static
    } else {
        su.drag.regime(
            v_sim.abs(),
            st.motion == Motion::AtJump
                || (su.fb_at_jump && (v_sim - fb_speed).abs() <= 1e-3 * fb_speed),
        )
    };
    let re_bingham = match su.drag.law {
        DragLaw::Bingham {
            yield_stress_pa,
            plastic_viscosity_pa_s,
        } => Some(reynolds_bingham(
            su.rho_fluid_kg_m3,
            v_sim.abs(),
            d,
            yield_stress_pa,
            plastic_viscosity_pa_s,
        )),
        _ => None,
    };
    let reynolds = su
        .drag
        .law
        .newtonian_viscosity_pa_s()
        .map(|viscosity_pa_s| {
            crate::fluid::newtonian::reynolds(su.rho_fluid_kg_m3, v_sim.abs(), d, viscosity_pa_s)
        });
    SphereResult {
        case: case.clone(),
        v_simulated_m_s: v_sim,
        terminal_steady: su.window.map(|_| st.terminal.is_some_and(|x| x.1)),
        v_section_m_s: v_section,
        steady_in_section,
        v_force_balance_m_s: fb_speed * su.net_weight_n.signum(),
        force_balance_at_jump: su.fb_at_jump,
        v_analytic_m_s: su.analytic.map(|a| a.0),
        regime,
        re_bingham,
        reynolds,
        max_velocity_error_rel: su.analytic.map(|_| st.max_err),
        response_time_s: su.response_time_s,
        rayleigh_time_s: match (sp.youngs_modulus_pa, sp.poisson_ratio) {
            (Some(e), Some(nu)) => Some(rayleigh_time_s(d, sp.density_kg_m3, e, nu)),
            _ => None,
        },
        probes: st.probes,
        samples: st.samples,
        steps: st.step,
        end_time_s: st.t,
        stop,
        entry_velocity_m_s: st.entry,
        final_bottom_depth_m: st.depth + 0.5 * d,
        stop_time_s: (stop == StopReason::Static).then_some(st.t),
    }
}

/// One sphere through its own Rapier world `W` with the force hook: the loop of
/// [`run_sphere_with`] with Rapier taking the steps.
fn rapier_sphere<const D: usize, W: SphereWorld<D>>(
    sc: Scene,
    case: &SphereCase,
    opts: RunOptions,
    interruptible: bool,
) -> Result<SphereResult, Halt> {
    let d = case.spec.diameter_m;
    let drag = sc.common.sphere_drag(d);
    let g = sc.common.gravity_m_s2;
    let depth0 = super::release_depth_m(sc.spec, case);
    let v_max = drag
        .balance_speed(
            (sphere_mass_kg(d, case.spec.density_kg_m3)
                - sphere_mass_kg(d, drag.fluid_density_kg_m3))
            .abs()
                * g,
        )
        .speed_m_s
        .max(sc.spec.release.velocity_m_s);
    let mut up = SVector::<f64, D>::zeros();
    up[D - 1] = 1.0;
    let (mut world, id) = W::with_sphere(
        EngineSettings::for_scene(d, 2.0 * v_max),
        g,
        -up * depth0,
        -up * sc.spec.release.velocity_m_s,
        d,
        case.spec.density_kg_m3,
        drag,
    );
    let mut prev = world.centre_m(id);
    let integrator = opts.integrator;
    let mut step = move |dt: f64| -> Result<Step<D>, Unstable> {
        world.step_s(dt, integrator).map_err(|mut u| {
            u.body = case.id.clone();
            u
        })?;
        let x = world.centre_m(id);
        let v = world.speed_m_s(id);
        let out = Step {
            velocity_m_s: v,
            displacement_m: x - prev,
            motion: if v.iter().all(|c| *c == 0.0) {
                Motion::Stuck
            } else {
                Motion::Moving
            },
            drag_slope_n_s_m: drag.slope_n_s_m(v.norm()),
        };
        prev = x;
        Ok(out)
    };
    run_sphere_with::<D>(sc, case, opts, Some(&mut step), interruptible)
}
