//! Free settling: independent spheres released in a still fluid, each in its own world, no
//! contacts (f-EDEM §3 single sphere in water; §4.1 Valentik & Whitmore's 3 m tank).
//!
//! Each sphere is advanced by [`crate::dynamics::advance`] alone (`engine = "free"`, the
//! default for this kind: there is nothing for a contact solver to do), or through a Rapier
//! world with the force hook (`engine = "rapier"`), which must give the same answer.
//!
//! Measurements per sphere:
//! - the section reading, as the experiment takes it: the section length divided by the transit
//!   time between two detectors (`[measure]`), flagged steady when the velocities at the two
//!   detectors differ by less than `steady_tolerance` of the section velocity;
//! - the terminal velocity of the simulation: the mean velocity over a rolling window of
//!   `terminal_window_m` once the velocities at its two ends differ by less than
//!   `terminal_tolerance` (the sphere keeps falling past the tank bottom if it needs to);
//! - the force-balance solution of f-EDEM eq. 15 (drag = net weight), which may sit on a jump of
//!   eq. 19 or be zero (`static`: the yield stress holds the sphere);
//! - for Stokes drag, the analytic solution v(t) = v_t + (v₀ − v_t) e^{−t/τ} (f-EDEM eq. 20–21).

use super::sphere_drag;
use super::spheres::SphereCase;
use crate::contact::rayleigh_time_s;
use crate::dynamics::{advance, explicit_stable_dt_s, Integrator, Monitor, Motion, Step, Unstable};
use crate::fluid::bingham::reynolds_bingham;
use crate::fluid::{sphere_mass_kg, DragLaw, DragRegime, SphereDrag};
use crate::scenario::{Scenario, Submergence};
use nalgebra::SVector;

/// Options of one run that do not belong in the scenario file.
#[derive(Clone, Copy, Debug)]
pub struct RunOptions {
    /// Time step, s.
    pub dt_s: f64,
    /// Integrator.
    pub integrator: Integrator,
    /// Keep the time series (off in sweeps).
    pub timeseries: bool,
}

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
    /// The force balance sits on a jump of the drag law.
    pub force_balance_at_jump: bool,
    /// Stokes terminal velocity (eq. 21) when the law is Stokes, m/s.
    pub v_analytic_m_s: Option<f64>,
    /// Regime label at the end (`static`, `jump`, a branch of eq. 19, or `smooth`).
    pub regime: DragRegime,
    /// Bingham Reynolds number at the simulated terminal velocity (eq. 18), if Bingham.
    pub re_bingham: Option<f64>,
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

pub use crate::fluid::immersion::immersion;

/// Depth of a sphere's centre below the free surface at release, m: above the surface by the
/// fall height plus a radius for drops; `release.depth_m`, or one radius ("just submerged") when
/// that is 0, otherwise.
pub fn release_depth_m(scenario: &Scenario, case: &SphereCase) -> f64 {
    let d = case.spec.diameter_m;
    match case.fall_height_m {
        Some(h) => -(h + 0.5 * d),
        None if scenario.release.depth_m > 0.0 => scenario.release.depth_m,
        None => 0.5 * d,
    }
}

/// Stokes solution for a sphere started at speed v₀ (downward): returns (v(t), distance(t)).
fn stokes_analytic(vt: f64, tau: f64, v0: f64, t: f64) -> (f64, f64) {
    let e = (-t / tau).exp();
    let em1 = -(-t / tau).exp_m1();
    (vt + (v0 - vt) * e, vt * t + (v0 - vt) * tau * em1)
}

/// Runs every sphere of a free-settling scenario in parallel (rayon); results in input order.
pub fn run(
    scenario: &Scenario,
    cases: &[SphereCase],
    opts: RunOptions,
) -> Result<Vec<SphereResult>, Unstable> {
    run_all(cases, |c| match scenario.dimension {
        2 => run_sphere::<2>(scenario, c, opts),
        _ => run_sphere::<3>(scenario, c, opts),
    })
}

/// Runs `one` on every case in parallel, results in input order, the first instability wins.
fn run_all(
    cases: &[SphereCase],
    one: impl Fn(&SphereCase) -> Result<SphereResult, Unstable> + Sync + Send,
) -> Result<Vec<SphereResult>, Unstable> {
    use rayon::prelude::*;
    cases.par_iter().map(one).collect()
}

/// Runs one sphere in `D` dimensions (vertical = last axis).
pub fn run_sphere<const D: usize>(
    scenario: &Scenario,
    case: &SphereCase,
    opts: RunOptions,
) -> Result<SphereResult, Unstable> {
    run_sphere_with::<D>(scenario, case, opts, None)
}

/// A step taken by an engine instead of [`advance`]: given dt, advance the sphere and report its
/// new velocity and displacement.
pub type ExternalStep<'a, const D: usize> = &'a mut dyn FnMut(f64) -> Result<Step<D>, Unstable>;

/// As [`run_sphere`], with the steps taken by `external` (a Rapier world) when given.
pub fn run_sphere_with<const D: usize>(
    scenario: &Scenario,
    case: &SphereCase,
    opts: RunOptions,
    mut external: Option<ExternalStep<'_, D>>,
) -> Result<SphereResult, Unstable> {
    let sp = &case.spec;
    let d = sp.diameter_m;
    let g = scenario.gravity_m_s2;
    let rho_f = scenario.fluid.density_kg_m3;
    let drag: SphereDrag = sphere_drag(scenario, d);
    let m = sphere_mass_kg(d, sp.density_kg_m3);
    let net_weight = (m - sphere_mass_kg(d, rho_f)) * g; // > 0: sinks
    let mut down = SVector::<f64, D>::zeros();
    down[D - 1] = -1.0;
    let w = down * net_weight;
    let dt = opts.dt_s;

    let fb = drag.balance_speed(net_weight.abs());
    let v_eq = down * (fb.speed_m_s * net_weight.signum());
    let response_time_s = m / drag.slope_n_s_m(0.0);
    let analytic = match drag.law {
        DragLaw::Stokes { .. } => Some((fb.speed_m_s * net_weight.signum(), response_time_s)),
        _ => None,
    };

    let depth0 = release_depth_m(scenario, case);
    // Spheres released submerged stay submerged: constant forces. Drops cross the surface.
    let crossing = case.fall_height_m.is_some();
    let submergence = scenario.fluid.submergence;
    let m_fluid = sphere_mass_kg(d, rho_f);
    let bottom = scenario
        .container
        .as_ref()
        .map(|c| c.height_m - 0.5 * d)
        .unwrap_or(f64::INFINITY);
    let v0 = scenario.release.velocity_m_s;
    let n_steps = (scenario.time.end_s / dt).round().max(1.0) as u64;
    let record_every = scenario
        .record
        .every_s
        .map(|e| ((e / dt).round() as u64).max(1))
        .unwrap_or_else(|| (n_steps / 2000).max(1));

    let mut v: SVector<f64, D> = down * v0;
    let mut depth = depth0;
    let mut monitor = Monitor::default();
    // Released in a still fluid under a constant force with a monotone drag, a sphere's speed
    // never exceeds max(v₀, v_terminal); an explicit step overshoots past 2× that exactly when
    // dt > 2 m/(dF/dv).
    let fall = case
        .fall_height_m
        .map(|h| (v0 * v0 + 2.0 * g * (h + d)).sqrt())
        .unwrap_or(0.0);
    let speed_bound = 2.0 * v0.abs().max(fb.speed_m_s).max(fall);
    let mut entry: Option<f64> = if crossing && depth0 + 0.5 * d >= 0.0 {
        Some(v0)
    } else {
        None
    };
    let mut samples = Vec::new();
    let sample = |t: f64, depth: f64, vel: f64| -> Sample {
        let an = analytic.map(|(vt, tau)| stokes_analytic(vt, tau, v0, t));
        Sample {
            time_s: t,
            depth_m: depth,
            velocity_m_s: vel,
            velocity_analytic_m_s: an.map(|a| a.0),
            depth_analytic_m: an.map(|a| depth0 + a.1),
        }
    };
    if opts.timeseries {
        samples.push(sample(0.0, depth, v0));
    }
    let probe_times = scenario
        .measure
        .as_ref()
        .map(|m| m.velocity_at_s.clone())
        .unwrap_or_default();
    let mut probes = Vec::with_capacity(probe_times.len());
    let section = scenario.measure.as_ref().and_then(|m| {
        Some((
            m.section_top_depth_m?,
            m.section_bottom_depth_m?,
            m.steady_tolerance,
        ))
    });
    let window = scenario
        .measure
        .as_ref()
        .and_then(|m| Some((m.terminal_window_m?, m.terminal_tolerance)));
    // Rolling window of (time, depth, speed), oldest first; the front stays at or above the
    // depth one window length up.
    let mut trail: std::collections::VecDeque<(f64, f64, f64)> = std::collections::VecDeque::new();
    trail.push_back((0.0, depth, v0));
    let mut terminal: Option<(f64, bool)> = None;
    let mut cross_top: Option<(f64, f64)> = None; // (time, velocity)
    let mut cross_bottom: Option<(f64, f64)> = None;
    let mut max_err: f64 = 0.0;
    let mut motion = Motion::Moving;
    let mut stop = StopReason::EndTime;
    let mut step = 0u64;
    let mut t = 0.0;
    while step < n_steps {
        let s = if let Some(ext) = external.as_mut() {
            ext(dt)?
        } else if crossing {
            let gap = -(depth + 0.5 * d); // lowest point above the surface, m
            let s_down = -v[D - 1];
            let free_fall = s_down * dt + 0.5 * g * dt * dt;
            if submergence == Submergence::Full && gap > 0.0 && free_fall > gap {
                // Entry inside the step: fall exactly to the surface, then the rest of the step
                // with the full fluid forces (event location, so entry is not late by a step).
                let t_c = 2.0 * gap / (s_down + (s_down * s_down + 2.0 * g * gap).sqrt());
                let v_c = v + down * (g * t_c);
                entry = Some(s_down + g * t_c);
                let rest = advance(opts.integrator, &drag, m, &w, &v_c, dt - t_c);
                Step {
                    displacement_m: down * gap + rest.displacement_m,
                    ..rest
                }
            } else {
                let (fv, fa) = immersion(depth, d, submergence);
                let w_now = down * (m * g - fv * m_fluid * g);
                advance(opts.integrator, &drag.scaled(fa), m, &w_now, &v, dt)
            }
        } else {
            advance(opts.integrator, &drag, m, &w, &v, dt)
        };
        let v_new = s.velocity_m_s;
        let overshoot = v_new.norm() > speed_bound;
        let growing = monitor.check((v - v_eq).as_slice(), (v_new - v_eq).as_slice());
        if overshoot || growing.is_some() {
            let what = growing.unwrap_or_else(|| {
                format!(
                    "speed {:.3e} m/s is above the physical bound 2·max(v₀, v_terminal) = {speed_bound:.3e} m/s",
                    v_new.norm()
                )
            });
            // A velocity that reverses under a yield-stress drag is the explicit scheme failing to
            // hold the body at rest (the drag is set-valued there): no dt cures that.
            let yield_chatter = drag.static_resistance_n() > 0.0 && v.dot(&v_new) < 0.0;
            return Err(Unstable {
                body: case.id.clone(),
                time_s: (step + 1) as f64 * dt,
                step: step + 1,
                what: if yield_chatter {
                    format!("{what}: the velocity reverses at the yield-stress stop (explicit drag chatters about rest)")
                } else {
                    what
                },
                dt_s: dt,
                stable_dt_s: if yield_chatter {
                    0.0
                } else {
                    explicit_stable_dt_s(m, s.drag_slope_n_s_m)
                },
                dt_basis: crate::dynamics::DtBasis::ExplicitDrag,
            });
        }
        let speed0 = -v[D - 1];
        let speed1 = -v_new[D - 1];
        let depth_new = depth - s.displacement_m[D - 1];
        step += 1;
        let t_new = step as f64 * dt;
        if crossing && entry.is_none() && depth_new + 0.5 * d >= 0.0 {
            let f = (-0.5 * d - depth) / (depth_new - depth);
            entry = Some(speed0 + f * (speed1 - speed0));
        }
        // Detector crossings, interpolated within the step.
        if let Some((top, bot, _)) = section {
            for (level, slot) in [(top, &mut cross_top), (bot, &mut cross_bottom)] {
                if slot.is_none() && depth < level && depth_new >= level {
                    let f = (level - depth) / (depth_new - depth);
                    *slot = Some((t + f * dt, speed0 + f * (speed1 - speed0)));
                }
            }
        }
        for &tp in &probe_times {
            if tp > t && tp <= t_new + 1e-12 * dt {
                // Dense output: the same scheme over the part of the step up to the probe.
                let part = advance(opts.integrator, &drag, m, &w, &v, tp - t);
                let an = analytic.map(|(vt, tau)| stokes_analytic(vt, tau, v0, tp).0);
                probes.push((tp, -part.velocity_m_s[D - 1], an));
            }
        }
        if let Some((vt, tau)) = analytic {
            let va = stokes_analytic(vt, tau, v0, t_new).0;
            max_err = max_err.max((speed1 - va).abs() / vt.abs());
        }
        v = v_new;
        depth = depth_new;
        t = t_new;
        motion = s.motion;
        if opts.timeseries && (step.is_multiple_of(record_every) || step == n_steps) {
            samples.push(sample(t, depth, speed1));
        }
        if let Some((len, tol)) = window {
            trail.push_back((t, depth, speed1));
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
                let steady = (speed1 - v_level).abs() <= tol * v_win.abs();
                terminal = Some((v_win, steady));
                if steady {
                    stop = StopReason::Steady;
                    break;
                }
            }
        } else if depth >= bottom {
            stop = StopReason::Bottom;
            break;
        }
        if s.motion == Motion::Stuck && v.iter().all(|x| *x == 0.0) {
            stop = StopReason::Static;
            break;
        }
    }
    if opts.timeseries && samples.last().map(|s| s.time_s) != Some(t) {
        samples.push(sample(t, depth, -v[D - 1]));
    }

    let final_speed = -v[D - 1];
    let (v_section, steady_in_section) = match (section, cross_top, cross_bottom) {
        (Some((top, bot, tol)), Some((t1, v1)), Some((t2, v2))) => {
            let vs = (bot - top) / (t2 - t1);
            (Some(vs), Some((v2 - v1).abs() <= tol * vs.abs()))
        }
        _ => (None, None),
    };
    let v_sim = if stop == StopReason::Static {
        0.0
    } else {
        terminal.map(|x| x.0).or(v_section).unwrap_or(final_speed)
    };
    let regime = if stop == StopReason::Static {
        DragRegime::Static
    } else {
        drag.regime(
            v_sim.abs(),
            motion == Motion::AtJump
                || (fb.at_jump && (v_sim - fb.speed_m_s).abs() <= 1e-3 * fb.speed_m_s),
        )
    };
    let re_bingham = match drag.law {
        DragLaw::Bingham {
            yield_stress_pa,
            plastic_viscosity_pa_s,
        } => Some(reynolds_bingham(
            rho_f,
            v_sim.abs(),
            d,
            yield_stress_pa,
            plastic_viscosity_pa_s,
        )),
        _ => None,
    };
    Ok(SphereResult {
        case: case.clone(),
        v_simulated_m_s: v_sim,
        terminal_steady: window.map(|_| terminal.is_some_and(|x| x.1)),
        v_section_m_s: v_section,
        steady_in_section,
        v_force_balance_m_s: fb.speed_m_s * net_weight.signum(),
        force_balance_at_jump: fb.at_jump,
        v_analytic_m_s: analytic.map(|a| a.0),
        regime,
        re_bingham,
        max_velocity_error_rel: analytic.map(|_| max_err),
        response_time_s,
        rayleigh_time_s: match (sp.youngs_modulus_pa, sp.poisson_ratio) {
            (Some(e), Some(nu)) => Some(rayleigh_time_s(d, sp.density_kg_m3, e, nu)),
            _ => None,
        },
        probes,
        samples,
        steps: step,
        end_time_s: t,
        stop,
        entry_velocity_m_s: entry,
        final_bottom_depth_m: depth + 0.5 * d,
        stop_time_s: (stop == StopReason::Static).then_some(t),
    })
}

/// Runs every sphere through its own Rapier world with the force hook (`engine = "rapier"`):
/// the same scene as the free engine, through the contact pipeline. It must give the same answer
/// (tests/engine_free_settling.rs); it costs ~300× more per step.
pub fn run_rapier(
    scenario: &Scenario,
    cases: &[SphereCase],
    opts: RunOptions,
) -> Result<Vec<SphereResult>, Unstable> {
    run_all(cases, |c| match scenario.dimension {
        2 => rapier_sphere_dim2(scenario, c, opts),
        _ => rapier_sphere_dim3(scenario, c, opts),
    })
}

macro_rules! rapier_sphere {
    ($name:ident, $dim:ident, $D:literal) => {
        fn $name(
            scenario: &Scenario,
            case: &SphereCase,
            opts: RunOptions,
        ) -> Result<SphereResult, Unstable> {
            use crate::engine::{$dim, EngineSettings};
            let d = case.spec.diameter_m;
            let drag = sphere_drag(scenario, d);
            let g = scenario.gravity_m_s2;
            let depth0 = release_depth_m(scenario, case);
            let v_max = drag
                .balance_speed(
                    (sphere_mass_kg(d, case.spec.density_kg_m3)
                        - sphere_mass_kg(d, drag.fluid_density_kg_m3))
                    .abs()
                        * g,
                )
                .speed_m_s
                .max(scenario.release.velocity_m_s);
            let mut world = $dim::World::new(EngineSettings::for_scene(d, 2.0 * v_max), g);
            let mut body =
                $dim::FluidBody::at_rest(-$dim::up() * depth0, d, case.spec.density_kg_m3, drag, g);
            body.velocity_m_s = -$dim::up() * scenario.release.velocity_m_s;
            let id = world.add_sphere(body);
            let mut prev = world.position_m(id);
            let integrator = opts.integrator;
            let mut step = move |dt: f64| -> Result<Step<$D>, Unstable> {
                world.step(dt, integrator).map_err(|mut u| {
                    u.body = case.id.clone();
                    u
                })?;
                let x = world.position_m(id);
                let v = world.velocity_m_s(id);
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
            run_sphere_with::<$D>(scenario, case, opts, Some(&mut step))
        }
    };
}

rapier_sphere!(rapier_sphere_dim2, dim2, 2);
rapier_sphere!(rapier_sphere_dim3, dim3, 3);
