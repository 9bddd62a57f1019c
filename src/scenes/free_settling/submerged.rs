//! The submerged step of one free-settling sphere with its transient forces (added mass,
//! history force, wall factors; [`super::transient`]), and the analytic solutions it is
//! compared with.

use super::setup::SphereSetup;
use crate::dynamics::transient::TransientBody;
use crate::dynamics::{advance, Integrator, Motion, Step};
use crate::fluid::transient::wall::brenner_factor;
use crate::fluid::SphereDrag;
use crate::scenario::Wall;
use nalgebra::SVector;

/// Stokes solution for a sphere started at speed v₀ (downward): returns (v(t), distance(t)).
pub(super) fn stokes_analytic(vt: f64, tau: f64, v0: f64, t: f64) -> (f64, f64) {
    let e = (-t / tau).exp();
    let em1 = -(-t / tau).exp_m1();
    (vt + (v0 - vt) * e, vt * t + (v0 - vt) * tau * em1)
}

/// Added mass C_m m_f of `su`, kg (0 without `[transient]`).
pub(super) fn added_mass_kg<const D: usize>(su: &SphereSetup<D>) -> f64 {
    su.transient.as_ref().map_or(0.0, |t| t.added_mass_kg)
}

/// The drag of `su` with the wall factors (bottom and side walls) at centre depth `depth_m`.
fn walled_drag<const D: usize>(su: &SphereSetup<D>, depth_m: f64) -> SphereDrag {
    let Some(t) = su.transient.as_ref() else {
        return su.drag;
    };
    let bottom = match t.wall {
        Wall::Brenner => brenner_factor(su.bottom_m - depth_m, 0.5 * su.d_m).min(1e12),
        Wall::Off => 1.0,
    };
    if bottom == 1.0 && t.confinement == 1.0 {
        su.drag
    } else {
        su.drag.scaled(bottom * t.confinement)
    }
}

/// One step (or the part `dt` of one, `commit = false`) of a submerged sphere with transient
/// forces from velocity `v` at depth `depth_m`.
pub(super) fn submerged_step<const D: usize>(
    su: &SphereSetup<D>,
    body: Option<&mut TransientBody>,
    integrator: Integrator,
    v: &SVector<f64, D>,
    depth_m: f64,
    dt: f64,
    commit: bool,
) -> Step<D> {
    let drag = walled_drag(su, depth_m);
    let Some(body) = body else {
        let m = su.m_kg + added_mass_kg(su);
        return advance(integrator, &drag, m, &su.w_n, v, dt);
    };
    // Along the vertical: downward speed s, drag F(s) opposing it.
    let f = |s: f64| {
        let a = s.abs();
        (drag.force_n(a).copysign(s), drag.slope_n_s_m(a))
    };
    if let Some((table, d_over_nu)) = su.transient.as_ref().and_then(|t| t.current_re.as_ref()) {
        let n = table.rates_per_s.len();
        let (mut buf, mut heap) = ([0.0; 64], Vec::new());
        let w: &mut [f64] = if n <= 64 {
            &mut buf[..n]
        } else {
            heap.resize(n, 0.0);
            &mut heap
        };
        let w0 = table.weights_into(v.norm() * d_over_nu, w);
        body.set_history_weights(w, w0);
    }
    let w = su.net_weight_n;
    let (s1, dx) = if commit {
        body.step(dt, w, f)
    } else {
        body.peek(dt, w, f)
    };
    Step {
        velocity_m_s: su.down * s1,
        displacement_m: su.down * dx,
        motion: Motion::Moving,
        drag_slope_n_s_m: drag.slope_n_s_m(s1.abs()),
    }
}

/// The analytic (velocity, distance) at `t` of `su`, when there is one (module docs).
pub(super) fn analytic_at<const D: usize>(su: &SphereSetup<D>, t: f64) -> Option<(f64, f64)> {
    if let Some(tr) = &su.transient {
        if let Some(p) = &tr.basset {
            return Some((p.velocity_m_s(t), p.displacement_m(t)));
        }
        if tr.history.is_some() || tr.wall != Wall::Off || tr.confinement != 1.0 {
            return None;
        }
    }
    su.analytic
        .map(|(vt, tau)| stokes_analytic(vt, tau, su.v0_m_s, t))
}
