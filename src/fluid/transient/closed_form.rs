//! The exact velocity and displacement of a sphere released from rest under a constant force,
//! with Stokes drag, added mass and the Basset–Boussinesq history force (Boussinesq 1885,
//! Basset 1888): the reference the state integrator of [`crate::dynamics::transient`] is checked
//! against.
//!
//! # Equation
//!
//! M dv/dt = W − 3π μ d v − (3/2) d² √(π ρ_f μ) ∫₀ᵗ v′(τ) (t − τ)^{−1/2} dτ,   v(0) = 0,
//!
//! with M = m_p + C_m m_f (C_m = ½ for a sphere) and W = (m_p − m_f) g (Maxey & Riley 1983 for a
//! fluid at rest). Divided by M: v′ = A − B v − C ∫ v′ (t−τ)^{−1/2} dτ, A = W/M, B = 3πμd/M,
//! C = (3/2)d²√(πρ_fμ)/M.
//!
//! # Solution (Laplace transform)
//!
//! s V = A/s − B V − C √π √s · s V gives V(s) = A / (s (√s + α)(√s + β)), with α, β the roots of
//! x² − C√π x + B = 0 (complex conjugates when C²π < 4B; Re α, Re β > 0 always). With
//! L⁻¹[1/(s(√s + a))] = (1 − E(a√t))/a and L⁻¹[1/(s²(√s + a))] = t/a − 2√t/(√π a²) +
//! (1 − E(a√t))/a³, E(z) = e^{z²} erfc(z) ([`super::faddeeva::erfcx`]):
//!
//! v(t) = A/(β − α) · [g_v(α) − g_v(β)],   g_v(a) = (1 − E(a√t))/a,
//! x(t) = A/(β − α) · [g_x(α) − g_x(β)],   g_x(a) = t/a − 2√t/(√π a²) + (1 − E(a√t))/a³,
//!
//! and v(∞) = A/(αβ) = A/B, the Stokes terminal velocity. Near a double root (β → α) the
//! divided difference becomes −A g′(α). For |a√t| < 1 the g's are summed from the series
//! E(z) = Σ (−z)ⁿ/Γ(n/2 + 1), which removes the cancellation of their terms at small t.
//! Verified against an independent quadrature of the integral equation (tests of
//! [`crate::dynamics::transient`] and src/scenes/free_settling/tests/transient.rs).

use super::faddeeva::erfcx;
use nalgebra::Complex;
use std::f64::consts::PI;

type C64 = Complex<f64>;

/// The coefficients of v′ = A − B v − C ∫ v′ (t−τ)^{−1/2} dτ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BassetProblem {
    /// A = W/M, m/s².
    pub a_m_s2: f64,
    /// B = 3πμd/M, 1/s.
    pub b_per_s: f64,
    /// C = (3/2) d² √(πρ_f μ)/M, 1/s^{1/2}.
    pub c_per_sqrt_s: f64,
}

impl BassetProblem {
    /// The problem of a sphere of diameter `d_m` and density `rho_p` in a fluid of density
    /// `rho_f` and viscosity `mu_pa_s`, with added-mass coefficient `cm` and gravity `g`.
    pub fn sphere(d_m: f64, rho_p: f64, rho_f: f64, mu_pa_s: f64, cm: f64, g: f64) -> Self {
        let vol = PI * d_m.powi(3) / 6.0;
        let m = (rho_p + cm * rho_f) * vol;
        Self {
            a_m_s2: (rho_p - rho_f) * vol * g / m,
            b_per_s: 3.0 * PI * mu_pa_s * d_m / m,
            c_per_sqrt_s: 1.5 * d_m * d_m * (PI * rho_f * mu_pa_s).sqrt() / m,
        }
    }

    /// Terminal velocity A/B, m/s.
    pub fn terminal_m_s(&self) -> f64 {
        self.a_m_s2 / self.b_per_s
    }

    /// The roots α, β of x² − C√π x + B = 0 (α with the larger real part, or the positive
    /// imaginary part when complex).
    pub fn roots(&self) -> (C64, C64) {
        let p = self.c_per_sqrt_s * PI.sqrt();
        let disc = C64::new(p * p - 4.0 * self.b_per_s, 0.0).sqrt();
        (
            (C64::new(p, 0.0) + disc) * 0.5,
            (C64::new(p, 0.0) - disc) * 0.5,
        )
    }

    /// Velocity at time `t_s` ≥ 0 after release from rest, m/s.
    pub fn velocity_m_s(&self, t_s: f64) -> f64 {
        self.combine(t_s, g_v, dg_v)
    }

    /// Distance travelled from release by time `t_s` ≥ 0, m.
    pub fn displacement_m(&self, t_s: f64) -> f64 {
        self.combine(t_s, g_x, dg_x)
    }

    /// A/(β − α)·[g(α) − g(β)], or −A g′((α+β)/2) near a double root.
    fn combine(&self, t: f64, g: fn(C64, f64) -> C64, dg: fn(C64, f64) -> C64) -> f64 {
        if t <= 0.0 {
            return 0.0;
        }
        let (al, be) = self.roots();
        let gap = be - al;
        let v = if gap.norm() < 1e-5 * (al + be).norm() {
            -dg((al + be) * 0.5, t) * self.a_m_s2
        } else {
            (g(al, t) - g(be, t)) / gap * self.a_m_s2
        };
        v.re
    }
}

/// 1/Γ(n/2 + 1) for n = 0, 1, 2, …: Γ(n/2 + 1) = (n/2)Γ(n/2) by recursion from Γ(1) = 1 and
/// Γ(3/2) = √π/2.
fn inv_gamma_half(n: usize) -> f64 {
    let mut g = if n.is_multiple_of(2) {
        1.0
    } else {
        PI.sqrt() / 2.0
    };
    let mut k = if n.is_multiple_of(2) { 2 } else { 3 };
    while k <= n {
        g *= k as f64 / 2.0;
        k += 2;
    }
    1.0 / g
}

/// Σ_{n ≥ n0} (−1)^{n+1} z^{n−n0} / Γ(n/2 + 1), for |z| < 1 (series of (1 − E(z)) after the
/// first n0 terms are removed).
fn tail_series(z: C64, n0: usize) -> C64 {
    let mut sum = C64::new(0.0, 0.0);
    let mut zp = C64::new(1.0, 0.0);
    for n in n0..n0 + 60 {
        let sign = if n % 2 == 1 { 1.0 } else { -1.0 };
        sum += zp * (sign * inv_gamma_half(n));
        zp *= z;
    }
    sum
}

/// g_v(a) = (1 − E(a√t))/a.
fn g_v(a: C64, t: f64) -> C64 {
    let st = t.sqrt();
    let z = a * st;
    if z.norm() < 1.0 {
        tail_series(z, 1) * st
    } else {
        (C64::new(1.0, 0.0) - erfcx(z)) / a
    }
}

/// g_x(a) = t/a − 2√t/(√π a²) + (1 − E(a√t))/a³.
fn g_x(a: C64, t: f64) -> C64 {
    let st = t.sqrt();
    let z = a * st;
    if z.norm() < 1.0 {
        tail_series(z, 3) * (t * st)
    } else {
        C64::new(t, 0.0) / a - C64::new(2.0 * st / PI.sqrt(), 0.0) / (a * a)
            + (C64::new(1.0, 0.0) - erfcx(z)) / (a * a * a)
    }
}

/// dg/da by a centred difference of step 1e-4|a| (used only at a double root, where the
/// divided difference of [`BassetProblem::combine`] degenerates).
fn derivative(g: fn(C64, f64) -> C64, a: C64, t: f64) -> C64 {
    let h = a * 1e-4;
    (g(a + h, t) - g(a - h, t)) / (h * 2.0)
}

fn dg_v(a: C64, t: f64) -> C64 {
    derivative(g_v, a, t)
}

fn dg_x(a: C64, t: f64) -> C64 {
    derivative(g_x, a, t)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// f-EDEM's sphere in water (d = 0.1 mm, ρ_p = 2700 kg/m³; complex roots).
    fn fedem() -> BassetProblem {
        BassetProblem::sphere(1e-4, 2700.0, 1000.0, 1e-3, 0.5, 9.81)
    }

    #[test]
    fn reaches_the_stokes_terminal_velocity_from_rest() {
        let p = fedem();
        assert_eq!(p.velocity_m_s(0.0), 0.0);
        let vt = p.terminal_m_s();
        // v_t − v(t) → v_t C/(B √(π t))·√π... decays as t^{−1/2}: still 0.3 % short at t = 100 s.
        let late = p.velocity_m_s(100.0);
        assert!(late < vt && (vt - late) / vt < 1e-2, "{late} vs {vt}");
        // Early: v ≈ A t (the history force starts at zero).
        let t = 1e-9;
        assert!((p.velocity_m_s(t) / (p.a_m_s2 * t) - 1.0).abs() < 1e-3);
    }

    #[test]
    fn without_history_it_is_the_exponential_approach() {
        let mut p = fedem();
        p.c_per_sqrt_s = 1e-12;
        for t in [1e-4, 1e-3, 5e-3] {
            let want = p.terminal_m_s() * -(-p.b_per_s * t).exp_m1();
            let got = p.velocity_m_s(t);
            assert!((got / want - 1.0).abs() < 1e-6, "t {t}: {got} vs {want}");
            let x = p.terminal_m_s() * (t + (-p.b_per_s * t).exp_m1() / p.b_per_s);
            assert!((p.displacement_m(t) / x - 1.0).abs() < 1e-5);
        }
    }

    #[test]
    fn series_and_direct_forms_agree_where_they_meet() {
        let p = fedem();
        let (al, _) = p.roots();
        let t = 1.0 / al.norm_sqr(); // |a√t| = 1
        for (g, name) in [(g_v as fn(C64, f64) -> C64, "g_v"), (g_x, "g_x")] {
            let below = g(al, t * (1.0 - 1e-9));
            let st = t.sqrt();
            let z = al * st;
            let direct = if name == "g_v" {
                (C64::new(1.0, 0.0) - erfcx(z)) / al
            } else {
                C64::new(t, 0.0) / al - C64::new(2.0 * st / PI.sqrt(), 0.0) / (al * al)
                    + (C64::new(1.0, 0.0) - erfcx(z)) / (al * al * al)
            };
            assert!((below - direct).norm() / direct.norm() < 1e-8, "{name}");
        }
    }

    #[test]
    fn velocity_is_the_derivative_of_displacement() {
        let p = fedem();
        for t in [1e-4, 2e-3, 0.05] {
            let h = t * 1e-4;
            let dx = (p.displacement_m(t + h) - p.displacement_m(t - h)) / (2.0 * h);
            assert!((dx / p.velocity_m_s(t) - 1.0).abs() < 1e-7, "t {t}");
        }
    }

    #[test]
    fn a_double_root_is_handled() {
        let mut p = fedem();
        // C²π = 4B: α = β.
        p.c_per_sqrt_s = (4.0 * p.b_per_s / PI).sqrt();
        let v = p.velocity_m_s(1e-3);
        p.c_per_sqrt_s *= 1.0 + 1e-3; // distinct real roots nearby
        let v2 = p.velocity_m_s(1e-3);
        assert!((v / v2 - 1.0).abs() < 1e-3, "{v} vs {v2}");
    }
    /// Independent check: the Laplace transform V(s) = A/(s(s + C√π√s + B)) (and V/s) inverted
    /// numerically by Talbot's contour method (`mpmath.invertlaplace`, 30 digits), for complex
    /// roots (f-EDEM's sphere, ten Cate's E1) and real roots (a light sphere rising).
    #[test]
    #[allow(clippy::excessive_precision)] // reference values as printed by mpmath
    fn matches_a_numerical_laplace_inversion() {
        let cases = [
            (
                BassetProblem::sphere(1e-4, 2700.0, 1000.0, 1e-3, 0.5, 9.81),
                [
                    (1e-4, 0.00041800782588896234, 2.1879985400137981e-8),
                    (1e-3, 0.0025281082581468971, 1.4759624999991414e-6),
                    (1e-2, 0.0065695151432162883, 4.9481220669597008e-5),
                    (0.3, 0.0087869914424924991, 0.0025003869883659177),
                ],
            ),
            (
                BassetProblem::sphere(0.015, 1120.0, 970.0, 0.373, 0.5, 9.81),
                [
                    (1e-4, 8.6922020948024423e-5, 4.3927559974845163e-9),
                    (1e-3, 0.00077558005780365979, 4.0102972097892916e-7),
                    (1e-2, 0.0054860115590715096, 3.0405745480928719e-5),
                    (0.3, 0.031205331557030974, 0.0069227016233202543),
                ],
            ),
            (
                BassetProblem::sphere(1e-3, 100.0, 1000.0, 1e-3, 0.5, 9.81),
                [
                    (1e-4, -0.0013187822553441443, -6.7382099479665182e-8),
                    (1e-3, -0.010615975796229658, -5.6526424719355873e-6),
                    (1e-2, -0.060963304637447531, -0.00035730908918169435),
                    (0.3, -0.28378046233447752, -0.063680442064853331),
                ],
            ),
        ];
        for (p, rows) in cases {
            for (t, v, x) in rows {
                let (gv, gx) = (p.velocity_m_s(t), p.displacement_m(t));
                assert!((gv / v - 1.0).abs() < 1e-11, "v({t}) = {gv}, want {v}");
                assert!((gx / x - 1.0).abs() < 1e-10, "x({t}) = {gx}, want {x}");
            }
        }
    }
}
