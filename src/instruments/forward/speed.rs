//! Terminal settling speeds of the hindered forward model: Dallavalle's drag coefficient with the
//! Di Felice voidage factor, the law of the sedimentation scenes' `physics = "full"`
//! ([`crate::fluid::DragLaw::Dallavalle`]), solved in closed form per iteration, and a table of
//! each grain size's speed over the voidages a suspension reaches.

use crate::fluid::newtonian::di_felice_chi;
use crate::instruments::Analysis;
use std::f64::consts::PI;

/// Voidage range of the drag law: the scenes clamp the local ε = 1 − φ to [0.3, 1].
pub const VOIDAGE_MIN: f64 = 0.3;

/// Terminal speed of a sphere of diameter `d_m` settling in fluid of local voidage `voidage`
/// (clamped to [[`VOIDAGE_MIN`], 1]), m/s: the speed v at which the drag of seed 000 eqs. 7–9,
///
/// F = ½ C_d(Re) ρ_f (π d²/4) v² ε^(1−χ(Re)),  C_d = (0.63 + 4.8/√Re)² (Dallavalle 1948),
/// χ = 3.7 − 0.65 exp(−(1.5 − log₁₀ Re)²/2) (Di Felice 1994),  Re = ε ρ_f v d / μ,
///
/// balances the buoyant weight W = (ρ_p − ρ_f) g π d³/6 (the scene's grains reach it within a
/// few Stokes response times ρ_p d²/(18 μ), under a millisecond for silt). Writing v through Re
/// turns the balance into (0.63 Re + 4.8 √Re)² = K ε^(1+χ) with K = 8 ρ_f W/(π μ²): a quadratic
/// in √Re for a given χ, iterated on χ(Re) (a contraction: |dχ/d ln Re| ≤ 0.17). At small Re it
/// is (1/0.96) ε^χ times Stokes' speed (Dallavalle's C_d → 23.04/Re, 0.96 of Stokes' 24/Re).
pub fn terminal_speed_m_s(an: &Analysis, d_m: f64, voidage: f64) -> f64 {
    let eps = voidage.clamp(VOIDAGE_MIN, 1.0);
    let (rho_f, mu) = (an.fluid_density_kg_m3, an.viscosity_pa_s);
    let w = (an.grain_density_kg_m3 - rho_f) * an.gravity_m_s2 * PI * d_m.powi(3) / 6.0;
    if w <= 0.0 || d_m <= 0.0 {
        return 0.0;
    }
    let k = 8.0 * rho_f * w / (PI * mu * mu);
    let mut chi = 3.7;
    let mut re = 0.0;
    for _ in 0..100 {
        let q = (k * eps.powf(1.0 + chi)).sqrt();
        // √Re = (−4.8 + √(4.8² + 4·0.63 q)) / (2·0.63), in the form without cancellation.
        let s = 2.0 * q / (4.8 + (23.04 + 2.52 * q).sqrt());
        let next = s * s;
        let done = (next - re).abs() <= 1e-15 * next;
        re = next;
        if done {
            break;
        }
        chi = di_felice_chi(re);
    }
    re * mu / (eps * rho_f * d_m)
}

/// One grain size's terminal speed over the voidages [ε_lo, 1]: v tabulated on a uniform grid
/// of ε (steps of at most 5e-4) and interpolated linearly, so that the forward model's many
/// evaluations cost a multiplication. v ∝ ε^χ at small Re (χ ≈ 3.7): the interpolation error is
/// below h² χ(χ − 1)/(8 ε²) ≈ 3e-7 relative for ε ≥ 0.9, 3e-6 at ε = 0.3.
#[derive(Clone, Debug)]
pub struct SpeedTable {
    lo: f64,
    step: f64,
    v: Vec<f64>,
}

impl SpeedTable {
    /// The table of diameter `d_m` over ε from `eps_lo` (raised to [`VOIDAGE_MIN`]) to 1, with
    /// grid steps of at most 5e-4 in ε (at least 2 nodes, at most 1401).
    pub fn new(an: &Analysis, d_m: f64, eps_lo: f64) -> Self {
        let lo = eps_lo.clamp(VOIDAGE_MIN, 1.0);
        let n = (((1.0 - lo) / 5e-4).ceil() as usize).clamp(1, 1400) + 1;
        let step = (1.0 - lo) / (n - 1) as f64;
        let v = (0..n)
            .map(|i| {
                let e = if i + 1 == n {
                    1.0
                } else {
                    lo + step * i as f64
                };
                terminal_speed_m_s(an, d_m, e)
            })
            .collect();
        Self { lo, step, v }
    }

    /// Position of ε on the grid: (node index, fraction towards the next node), ε clamped to the
    /// table's range.
    fn locate(&self, eps: f64) -> (usize, f64) {
        let n = self.v.len();
        if n == 1 || self.step <= 0.0 {
            return (0, 0.0);
        }
        let x = ((eps - self.lo) / self.step).clamp(0.0, (n - 1) as f64);
        let i = (x as usize).min(n - 2);
        (i, x - i as f64)
    }

    /// Terminal speed at voidage `eps` (clamped to the table), m/s.
    pub fn speed(&self, eps: f64) -> f64 {
        if self.v.len() == 1 {
            return self.v[0];
        }
        let (i, f) = self.locate(eps);
        self.v[i] + f * (self.v[i + 1] - self.v[i])
    }

    /// dv/dε at voidage `eps` (of the interpolant), m/s.
    pub fn slope(&self, eps: f64) -> f64 {
        if self.v.len() == 1 || self.step <= 0.0 {
            return 0.0;
        }
        let (i, _) = self.locate(eps);
        (self.v[i + 1] - self.v[i]) / self.step
    }

    /// The voidage at which the speed reaches `v_m_s`, if it does within the table (the speed
    /// does not decrease with ε); None if it stays below `v_m_s` up to ε = 1.
    pub fn voidage_at(&self, v_m_s: f64) -> Option<f64> {
        let n = self.v.len();
        if self.v[n - 1] < v_m_s {
            return None;
        }
        if n == 1 || self.v[0] >= v_m_s {
            return Some(self.lo);
        }
        // First node at or above the target.
        let i = self.v.partition_point(|&x| x < v_m_s);
        let (a, b) = (self.v[i - 1], self.v[i]);
        let f = if b > a { (v_m_s - a) / (b - a) } else { 1.0 };
        Some(self.lo + self.step * ((i - 1) as f64 + f))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluid::{DragLaw, SphereDrag};

    fn an() -> Analysis {
        Analysis {
            viscosity_pa_s: 1e-3,
            grain_density_kg_m3: 2500.0,
            fluid_density_kg_m3: 1000.0,
            gravity_m_s2: 9.81,
            c0_kg_m3: 40.0,
        }
    }

    #[test]
    fn the_speed_balances_the_scenes_drag_law() {
        let a = an();
        for d in [1e-6, 5e-6, 3e-5, 7e-5, 3e-4, 2e-3] {
            for eps in [0.3, 0.6, 0.9, 0.976, 1.0] {
                let v = terminal_speed_m_s(&a, d, eps);
                let drag = SphereDrag::new(
                    DragLaw::Dallavalle {
                        viscosity_pa_s: 1e-3,
                        voidage: eps,
                    },
                    d,
                    1000.0,
                );
                let w = 1500.0 * 9.81 * PI * d * d * d / 6.0;
                assert!((drag.force_n(v) / w - 1.0).abs() < 1e-12, "d {d} ε {eps}");
            }
        }
        // Small Re: 1/0.96 of Stokes' speed, times ε^3.7.
        let st = 1500.0 * 9.81 * 1e-12 / 18e-3;
        assert!((terminal_speed_m_s(&a, 1e-6, 1.0) / st * 0.96 - 1.0).abs() < 1e-3);
        let r = terminal_speed_m_s(&a, 1e-6, 0.9) / terminal_speed_m_s(&a, 1e-6, 1.0);
        assert!((r / 0.9f64.powf(3.7) - 1.0).abs() < 1e-3, "{r}");
    }

    #[test]
    fn the_table_interpolates_within_1e6() {
        let a = an();
        let t = SpeedTable::new(&a, 3e-5, 0.9);
        for i in 0..=1000 {
            let e = 0.9 + 0.1 * i as f64 / 1000.0;
            let exact = terminal_speed_m_s(&a, 3e-5, e);
            assert!((t.speed(e) / exact - 1.0).abs() < 1e-6, "{e}");
        }
        let v = terminal_speed_m_s(&a, 3e-5, 0.95);
        assert!((t.voidage_at(v).unwrap() - 0.95).abs() < 1e-9);
        assert!(t.voidage_at(2.0 * v).is_none());
        assert_eq!(t.voidage_at(0.1 * v), Some(0.9));
    }
}
