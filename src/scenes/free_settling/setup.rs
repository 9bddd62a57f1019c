//! Setup of a free-settling run: the options that are not in the scenario file and the
//! quantities of one sphere fixed at release (drag, weights, force balance, schedule,
//! detectors).

use super::scene::Scene;
use crate::dynamics::Integrator;
use crate::fluid::{sphere_mass_kg, DragLaw, SphereDrag};
use crate::scenario::inputs::SphereCase;
use crate::scenario::{Common, Engine, FreeSettlingSpec, Submergence};
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

impl RunOptions {
    /// The options a scenario file asks for (`time.dt_s`, `time.integrator`,
    /// `record.timeseries`), from its typed common part.
    pub fn of_common(c: &Common) -> Self {
        Self {
            dt_s: c.time.dt_s,
            integrator: c.time.integrator,
            timeseries: c.record.timeseries,
        }
    }
}

/// Whether the spheres go through Rapier worlds (`engine = "rapier"`); `auto` and `free` use
/// the free engine, as there are no contacts.
pub fn uses_rapier(c: &Common) -> bool {
    c.engine == Engine::Rapier
}

/// Depth of a sphere's centre below the free surface at release, m: above the surface by the
/// fall height plus a radius for drops; `release.depth_m`, or one radius ("just submerged") when
/// that is 0, otherwise.
pub fn release_depth_m(spec: &FreeSettlingSpec, case: &SphereCase) -> f64 {
    let d = case.spec.diameter_m;
    match case.fall_height_m {
        Some(h) => -(h + 0.5 * d),
        None if spec.release.depth_m > 0.0 => spec.release.depth_m,
        None => 0.5 * d,
    }
}

/// Everything about one sphere's run that is fixed at release, in `D` dimensions (vertical =
/// last axis, `down` = −e_D). SI units.
pub(super) struct SphereSetup<const D: usize> {
    /// Diameter, m.
    pub d_m: f64,
    /// Gravity, m/s².
    pub g_m_s2: f64,
    /// Fluid density, kg/m³.
    pub rho_fluid_kg_m3: f64,
    /// The sphere's drag.
    pub drag: SphereDrag,
    /// Sphere mass, kg.
    pub m_kg: f64,
    /// Mass of the displaced fluid when fully immersed, kg.
    pub m_fluid_kg: f64,
    /// Net weight (m − m_f) g, N (> 0: sinks).
    pub net_weight_n: f64,
    /// Unit vector down.
    pub down: SVector<f64, D>,
    /// Net weight as a vector, N.
    pub w_n: SVector<f64, D>,
    /// Time step, s.
    pub dt_s: f64,
    /// Force-balance speed (f-EDEM eq. 15), m/s, and whether it sits on a jump of the law.
    pub fb_speed_m_s: f64,
    /// The force balance sits on a jump of the drag law.
    pub fb_at_jump: bool,
    /// Force-balance velocity as a vector, m/s.
    pub v_eq_m_s: SVector<f64, D>,
    /// Response time m/(dF/dv) at rest, s.
    pub response_time_s: f64,
    /// Stokes drag only: (signed terminal speed m/s, response time s) of eq. 20–21.
    pub analytic: Option<(f64, f64)>,
    /// Centre depth at release, m.
    pub depth0_m: f64,
    /// A drop: the sphere crosses the free surface.
    pub crossing: bool,
    /// How a crossing sphere is immersed.
    pub submergence: Submergence,
    /// Centre depth at which the sphere reaches the container bottom, m (∞ without container).
    pub bottom_m: f64,
    /// Release speed (downward), m/s.
    pub v0_m_s: f64,
    /// Steps to `time.end_s`.
    pub n_steps: u64,
    /// Record a time-series row every this many steps.
    pub record_every: u64,
    /// Bound on the speed of a stable run, m/s: 2·max(v₀, v_terminal, free-fall entry speed).
    pub speed_bound_m_s: f64,
    /// Probe times `[measure].velocity_at_s`, s.
    pub probe_times_s: Vec<f64>,
    /// Detector section (top depth m, bottom depth m, steady tolerance).
    pub section: Option<(f64, f64, f64)>,
    /// Rolling terminal window (length m, tolerance).
    pub window: Option<(f64, f64)>,
    /// Transient forces (`[transient]`), None when absent or all off.
    pub transient: Option<super::transient::TransientSetup>,
}

impl<const D: usize> SphereSetup<D> {
    /// The setup of `case` in the scene `sc` with the options `opts`.
    pub fn new(sc: Scene, case: &SphereCase, opts: RunOptions) -> Self {
        let (c, f) = (sc.common, sc.spec);
        let sp = &case.spec;
        let d = sp.diameter_m;
        let g = c.gravity_m_s2;
        let rho_f = c.fluid_density_kg_m3;
        let drag: SphereDrag = c.sphere_drag(d);
        let m = sphere_mass_kg(d, sp.density_kg_m3);
        let net_weight = (m - sphere_mass_kg(d, rho_f)) * g; // > 0: sinks
        let mut down = SVector::<f64, D>::zeros();
        down[D - 1] = -1.0;
        let dt = opts.dt_s;
        let fb = drag.balance_speed(net_weight.abs());
        let response_time_s = m / drag.slope_n_s_m(0.0);
        let transient =
            super::transient::TransientSetup::new(sc, d, m, sphere_mass_kg(d, rho_f), &drag);
        // With added mass alone the Stokes solution keeps its form, with τ = (m + C_m m_f)/k;
        // with the history force or the wall it is replaced ([`super::transient::analytic_at`]).
        let added = transient.as_ref().map_or(0.0, |t| t.added_mass_kg);
        let plain = transient.as_ref().is_none_or(|t| {
            t.basset.is_some()
                || (t.history.is_none()
                    && t.wall == crate::scenario::Wall::Off
                    && t.confinement == 1.0)
        });
        let analytic = match drag.law {
            DragLaw::Stokes { .. } if plain => Some((
                fb.speed_m_s * net_weight.signum(),
                (m + added) / drag.slope_n_s_m(0.0),
            )),
            _ => None,
        };
        let n_steps = (c.time.end_s / dt).round().max(1.0) as u64;
        let v0 = f.release.velocity_m_s;
        // Released in a still fluid under a constant force with a monotone drag, a sphere's speed
        // never exceeds max(v₀, v_terminal); an explicit step overshoots past 2× that exactly when
        // dt > 2 m/(dF/dv).
        let fall = case
            .fall_height_m
            .map(|h| (v0 * v0 + 2.0 * g * (h + d)).sqrt())
            .unwrap_or(0.0);
        let measure = f.measure.as_ref();
        Self {
            d_m: d,
            g_m_s2: g,
            rho_fluid_kg_m3: rho_f,
            drag,
            m_kg: m,
            m_fluid_kg: sphere_mass_kg(d, rho_f),
            net_weight_n: net_weight,
            down,
            w_n: down * net_weight,
            dt_s: dt,
            fb_speed_m_s: fb.speed_m_s,
            fb_at_jump: fb.at_jump,
            v_eq_m_s: down * (fb.speed_m_s * net_weight.signum()),
            response_time_s,
            analytic,
            depth0_m: release_depth_m(f, case),
            // Spheres released submerged stay submerged: constant forces. Drops cross the surface.
            crossing: case.fall_height_m.is_some(),
            submergence: c.submergence,
            bottom_m: f
                .container
                .as_ref()
                .map(|c| c.height_m - 0.5 * d)
                .unwrap_or(f64::INFINITY),
            v0_m_s: v0,
            n_steps,
            record_every: c
                .record
                .every_s
                .map(|e| ((e / dt).round() as u64).max(1))
                .unwrap_or_else(|| (n_steps / 2000).max(1)),
            speed_bound_m_s: 2.0 * v0.abs().max(fb.speed_m_s).max(fall),
            probe_times_s: measure.map(|m| m.velocity_at_s.clone()).unwrap_or_default(),
            section: measure.and_then(|m| {
                Some((
                    m.section_top_depth_m?,
                    m.section_bottom_depth_m?,
                    m.steady_tolerance,
                ))
            }),
            window: measure.and_then(|m| Some((m.terminal_window_m?, m.terminal_tolerance))),
            transient,
        }
    }
}
