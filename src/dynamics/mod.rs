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
pub mod terminal;
pub mod transient;

use crate::fluid::SphereDrag;
use crate::numerics::safeguarded_newton;
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

/// Below this z, e^z − 1 rounds to −1 in double precision (e^z < 2⁻⁵⁷ ≈ 6.9e-18, under half
/// an ulp of 1), so `z.exp_m1()` is exactly −1 and [`phi12`] needs no exponential.
pub const PHI_SATURATED: f64 = -40.0;

/// φ₁(z) = (e^z − 1)/z and φ₂(z) = (e^z − 1 − z)/z², accurate for small |z| (z ≤ 0 here): the
/// factors of the exponential update (Hochbruck & Ostermann 2010, Acta Numerica 19, §2.1).
pub fn phi12(z: f64) -> (f64, f64) {
    if z < PHI_SATURATED {
        // e^z − 1 rounds to −1 (e^z < 2⁻⁵⁷): the general branch's result bit for bit, without
        // the exponential.
        return (-1.0 / z, (-1.0 - z) / (z * z));
    }
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

/// One grain of [`exponential_dallavalle_1d`]: its drag law (Dallavalle with the Di Felice
/// factor, [`crate::fluid::DragLaw::Dallavalle`]) at one voidage, its mass and body force. SI.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DallavalleGrain {
    /// Diameter d, m.
    pub diameter_m: f64,
    /// Fluid density ρ_f, kg/m³.
    pub fluid_density_kg_m3: f64,
    /// Viscosity η, Pa s.
    pub viscosity_pa_s: f64,
    /// Voidage ε ∈ (0, 1].
    pub voidage: f64,
    /// ln ε.
    pub ln_voidage: f64,
    /// Mass m, kg.
    pub mass_kg: f64,
    /// Body force W (gravity + buoyancy), N, along the one axis.
    pub body_force_n: f64,
}

/// The exponential step of [`advance`] ([`Integrator::Exponential`]) in one dimension for
/// Dallavalle drag with the Di Felice factor, from velocity `v0_m_s` over `dt_s`: (velocity, m/s;
/// displacement, m). None when the sphere stops within the step (backward-Euler speed 0, or a
/// non-finite input): the caller then uses [`advance`].
///
/// The same scheme as [`advance`]: the backward-Euler speed s₁ solves
/// h(s) = s + (dt/m) F(s) = |p|, p = v₀ + W dt/m, by safeguarded Newton from |v₀| on [0, |p|];
/// the drag is linearised about s₁, F(v) ≈ F₀ + k v, k = dF/dv(s₁), and
/// v₁ = v₀ + a₀ dt φ₁(−λdt), dx = v₀ dt + a₀ dt² φ₂(−λdt), a₀ = (W − F₀ p̂ − k v₀)/m, λ = k/m
/// (Hochbruck & Ostermann 2010, §2.1). It differs from [`advance`] only in rounding, because:
/// - F, F' and F'' come together from
///   [`crate::fluid::newtonian::dallavalle_di_felice_derivatives`] (one set of transcendentals;
///   exact slope, where [`advance`] takes a central difference of relative step 1e-6, itself
///   accurate to about 1e-10);
/// - Newton stops when the error left after its step, h''/(2h') c² for a correction c
///   (quadratic convergence), is below 1e-18 |s| (and c below 1e-6 |s|), or when the correction
///   is below four ulps as in [`advance`]. Near steady settling the evaluation at |v₀| is then
///   the only one;
/// - F and k at s₁ are the last evaluation carried to s₁ by Taylor to second order when
///   |s₁ − s| ≤ 1e-6 s (the rest is of order F''' (s₁ − s)³, 1e-18 relatively), evaluated
///   afresh otherwise.
///
/// The differences are of the order of the rounding of F itself (about 1e-15 relative; the unit
/// test `exponential_dallavalle_matches_advance` bounds them).
pub fn exponential_dallavalle_1d(
    g: &DallavalleGrain,
    v0_m_s: f64,
    dt_s: f64,
) -> Option<(f64, f64)> {
    let m = g.mass_kg;
    let w = g.body_force_n;
    let v0 = v0_m_s;
    let dt = dt_s;
    let law = |s: f64| {
        crate::fluid::newtonian::dallavalle_di_felice_derivatives(
            s,
            g.voidage,
            g.ln_voidage,
            g.diameter_m,
            g.fluid_density_kg_m3,
            g.viscosity_pa_s,
        )
    };
    let kk = dt / m;
    let p = v0 + w * kk;
    let target = p.abs();
    if !(target > 0.0 && target.is_finite()) {
        return None;
    }
    // Safeguarded Newton on h(s) = s + kk F(s) − |p| over [0, |p|] (h(s) ≥ s).
    let (lo, hi) = (0.0, target);
    let guess = v0.abs();
    let start = if guess > lo && guess < hi {
        guess
    } else {
        0.5 * (lo + hi)
    };
    let end = safeguarded_newton(
        lo,
        hi,
        start,
        200,
        |s| {
            let (f, k, k2) = law(s);
            (s + kk * f - target, 1.0 + kk * k, (f, k, k2))
        },
        |it| {
            let (s, k2) = (it.at, it.extra.2);
            let c = (it.next - s).abs();
            let left = (kk * k2).abs() / (2.0 * it.slope) * c * c;
            (it.newton && c <= 1e-6 * s && left <= 1e-18 * s)
                || c <= 4.0 * f64::EPSILON * s.abs().max(f64::MIN_POSITIVE)
                || it.hi - it.lo <= 4.0 * f64::EPSILON * it.hi
        },
    );
    let s = end.x;
    let last = end.last?;
    let (mut at, (mut f, mut k, mut k2)) = (last.at, last.extra);
    if !(s > 0.0 && s.is_finite()) {
        return None;
    }
    if (s - at).abs() > 1e-6 * s {
        (f, k, k2) = law(s);
        at = s;
    }
    // F and its slope at s (Taylor from the evaluation at `at`).
    let ds = s - at;
    let f = f + (k + 0.5 * k2 * ds) * ds;
    let k = k + k2 * ds;
    // As `advance`: the end velocity p s/|p|, its speed s₁ and direction; F(s₁) − k s₁.
    let vel = p * (s / target);
    let s1 = vel.abs();
    let dir = vel / s1;
    let f0 = f + k * (s1 - s) - k * s1;
    let a0 = (w - dir * f0 - v0 * k) / m;
    let (phi1, phi2) = phi12(-k / m * dt);
    Some((v0 + a0 * (dt * phi1), v0 * dt + a0 * (dt * dt * phi2)))
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
