//! Time integration of one sphere under a constant body force (gravity + buoyancy) and a drag
//! law, in 2D or 3D (`D` = 2 or 3). Pure functions: the engine calls them for free bodies and
//! uses their result as the target of Rapier's step for bodies it hands to the contact solver.
//!
//! Three schemes, all advancing velocity `v` and displacement `dx` over one step `dt`:
//!
//! - [`Integrator::Explicit`]: forward Euler on the drag, `v₁ = v₀ + (W − F(v₀))dt/m`,
//!   `x₁ = x₀ + v₁ dt` (symplectic Euler, the usual DEM update). Stable only for
//!   dt < 2 m / (dF/dv): 2τ for Stokes drag. Kept to show where naive coupling fails.
//! - [`Integrator::Implicit`]: backward Euler, `m (v₁ − v₀)/dt = W − F(v₁)`, solved exactly
//!   with the set-valued drag at rest and at jumps (radial return, as for Coulomb friction).
//!   Unconditionally stable; exact steady states (terminal velocity, rest, a speed held on a jump).
//! - [`Integrator::Exponential`] (default): the drag linearised about the backward-Euler end state,
//!   `F(v) ≈ F₀ + k v` along its direction, and the resulting linear ODE solved exactly
//!   (exponential Euler with φ-functions). Exact at any dt for linear (Stokes) and affine drag
//!   (the Bingham law below Re' = 1), exact steady states, unconditionally stable.

pub mod stability;
pub mod transient;

use crate::fluid::SphereDrag;
use nalgebra::SVector;
pub use stability::{DtBasis, Monitor, Unstable};

/// Time-integration scheme for the fluid forces. Default: `Exponential`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Integrator {
    /// Forward Euler on the drag (diverges for dt > 2τ under linear drag).
    Explicit,
    /// Backward Euler with the exact set-valued drag.
    Implicit,
    /// Exponential integrator, exact for linear and affine drag.
    #[default]
    Exponential,
}

impl Integrator {
    /// Name as written in scenario files and CSV: `explicit`, `implicit`, `exponential`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Explicit => "explicit",
            Self::Implicit => "implicit",
            Self::Exponential => "exponential",
        }
    }

    /// All schemes, in the order above.
    pub const ALL: [Integrator; 3] = [Self::Explicit, Self::Implicit, Self::Exponential];
}

/// What the sphere does over a step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Motion {
    /// Moving with a drag on one continuous branch of the law.
    Moving,
    /// At rest, held by the static (yield-stress) resistance.
    Stuck,
    /// Speed held exactly on a jump of the drag law.
    AtJump,
}

/// Result of one step of [`advance`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Step<const D: usize> {
    /// Velocity at the end of the step, m/s.
    pub velocity_m_s: SVector<f64, D>,
    /// Displacement over the step, m.
    pub displacement_m: SVector<f64, D>,
    /// Motion state at the end of the step.
    pub motion: Motion,
    /// Local drag stiffness dF/dv at the end state, N s/m (for stability reports).
    pub drag_slope_n_s_m: f64,
}

/// Advances a sphere of mass `mass_kg` by `dt_s` under the constant body force `body_force_n`
/// (gravity + buoyancy + any other non-drag force) and the drag `drag`, from velocity `v0`
/// (relative to the fluid at rest).
pub fn advance<const D: usize>(
    integrator: Integrator,
    drag: &SphereDrag,
    mass_kg: f64,
    body_force_n: &SVector<f64, D>,
    v0: &SVector<f64, D>,
    dt_s: f64,
) -> Step<D> {
    match integrator {
        Integrator::Explicit => explicit(drag, mass_kg, body_force_n, v0, dt_s),
        Integrator::Implicit => {
            let be = backward_euler(drag, mass_kg, body_force_n, v0, dt_s);
            Step {
                displacement_m: be.velocity_m_s * dt_s,
                ..be
            }
        }
        Integrator::Exponential => exponential(drag, mass_kg, body_force_n, v0, dt_s),
    }
}

fn explicit<const D: usize>(
    drag: &SphereDrag,
    m: f64,
    w: &SVector<f64, D>,
    v0: &SVector<f64, D>,
    dt: f64,
) -> Step<D> {
    let s0 = v0.norm();
    let fd = if s0 > 0.0 {
        v0 * (drag.force_n(s0) / s0)
    } else {
        SVector::zeros()
    };
    let v1 = v0 + (w - fd) * (dt / m);
    Step {
        velocity_m_s: v1,
        displacement_m: v1 * dt,
        motion: Motion::Moving,
        drag_slope_n_s_m: drag.slope_n_s_m(s0),
    }
}

/// Backward Euler: v₁ = p − (dt/m) F(|v₁|) v̂₁ with p = v₀ + W dt/m, so v₁ ∥ p and
/// |v₁| + (dt/m) F(|v₁|) = |p| (a scalar monotone equation, see [`SphereDrag::solve_implicit`]).
fn backward_euler<const D: usize>(
    drag: &SphereDrag,
    m: f64,
    w: &SVector<f64, D>,
    v0: &SVector<f64, D>,
    dt: f64,
) -> Step<D> {
    let p = v0 + w * (dt / m);
    let pn = p.norm();
    let sol = drag.solve_implicit(dt / m, pn, v0.norm());
    let (v1, motion) = if sol.speed_m_s <= 0.0 || pn == 0.0 {
        (SVector::zeros(), Motion::Stuck)
    } else {
        let motion = if sol.at_jump {
            Motion::AtJump
        } else {
            Motion::Moving
        };
        (p * (sol.speed_m_s / pn), motion)
    };
    Step {
        velocity_m_s: v1,
        displacement_m: v1 * dt,
        motion,
        drag_slope_n_s_m: drag.slope_n_s_m(sol.speed_m_s),
    }
}

/// φ₁(z) = (e^z − 1)/z and φ₂(z) = (e^z − 1 − z)/z², accurate for small |z| (z ≤ 0 here): the
/// factors of the exponential update (Hochbruck & Ostermann 2010, Acta Numerica 19, §2.1).
pub fn phi12(z: f64) -> (f64, f64) {
    if z.abs() < 1e-3 {
        let phi1 = 1.0 + z / 2.0 + z * z / 6.0 + z * z * z / 24.0;
        let phi2 = 0.5 + z / 6.0 + z * z / 24.0 + z * z * z / 120.0;
        (phi1, phi2)
    } else {
        let em1 = z.exp_m1();
        (em1 / z, (em1 - z) / (z * z))
    }
}

fn exponential<const D: usize>(
    drag: &SphereDrag,
    m: f64,
    w: &SVector<f64, D>,
    v0: &SVector<f64, D>,
    dt: f64,
) -> Step<D> {
    if let crate::fluid::DragLaw::Stokes { .. } = drag.law {
        // Linear drag: the exponential solution needs no implicit solve.
        let k = drag.slope_n_s_m(0.0);
        let a0 = (w - v0 * k) / m;
        let (phi1, phi2) = phi12(-k / m * dt);
        return Step {
            velocity_m_s: v0 + a0 * (dt * phi1),
            displacement_m: v0 * dt + a0 * (dt * dt * phi2),
            motion: Motion::Moving,
            drag_slope_n_s_m: k,
        };
    }
    let be = backward_euler(drag, m, w, v0, dt);
    let s0 = v0.norm();
    match be.motion {
        Motion::AtJump => Step {
            displacement_m: (v0 + be.velocity_m_s) * (0.5 * dt),
            ..be
        },
        Motion::Stuck => {
            if s0 == 0.0 {
                return Step {
                    displacement_m: SVector::zeros(),
                    ..be
                };
            }
            // Decelerates to rest within the step: along v̂₀ the speed obeys
            // m ds/dt = W·v̂₀ − F₀ − k s with F₀ = F(0⁺), k = dF/dv(0⁺); it reaches 0 at t*.
            let dir = v0 / s0;
            let f0 = drag.static_resistance_n() - w.dot(&dir);
            let k = drag.slope_n_s_m(0.0);
            let lambda = k / m;
            // s(t) = (s0 + f0/k) e^{−λt} − f0/k; t* = ln(1 + k s0/f0)/λ.
            let dist = if lambda * dt < 1e-12 || f0 <= 0.0 {
                let a = f0.max(0.0) / m;
                let t = if a > 0.0 { (s0 / a).min(dt) } else { dt };
                s0 * t - 0.5 * a * t * t
            } else {
                let t = ((1.0 + k * s0 / f0).ln() / lambda).min(dt);
                let c = s0 + f0 / k;
                c * (-(-lambda * t).exp_m1()) / lambda - f0 / k * t
            };
            Step {
                displacement_m: dir * dist.max(0.0),
                ..be
            }
        }
        Motion::Moving => {
            let s1 = be.velocity_m_s.norm();
            let dir = be.velocity_m_s / s1;
            let k = be.drag_slope_n_s_m;
            let f0 = drag.force_n(s1) - k * s1;
            // m dv/dt = W − F₀ û − k v; exact: v₁ = v₀ + a₀ dt φ₁(−λdt), dx = v₀dt + a₀dt² φ₂(−λdt).
            let a0 = (w - dir * f0 - v0 * k) / m;
            let (phi1, phi2) = phi12(-k / m * dt);
            Step {
                velocity_m_s: v0 + a0 * (dt * phi1),
                displacement_m: v0 * dt + a0 * (dt * dt * phi2),
                motion: Motion::Moving,
                drag_slope_n_s_m: k,
            }
        }
    }
}

/// Largest dt for which the explicit drag update is stable at drag stiffness `slope_n_s_m`:
/// dt < 2 m / (dF/dv) (2τ for Stokes drag). Infinite for zero stiffness.
pub fn explicit_stable_dt_s(mass_kg: f64, slope_n_s_m: f64) -> f64 {
    if slope_n_s_m > 0.0 {
        2.0 * mass_kg / slope_n_s_m
    } else {
        f64::INFINITY
    }
}

#[cfg(test)]
mod tests;
