//! The Basset history kernel t^{−1/2} as a sum of decaying exponentials, so that the history
//! force becomes a set of ordinary differential equations carried as state (one per term).
//!
//! # Construction
//!
//! The kernel is a Laplace transform, t^{−1/2} = π^{−1/2} ∫₀^∞ λ^{−1/2} e^{−λt} dλ
//! = π^{−1/2} ∫_{−∞}^{∞} e^{x/2} exp(−eˣ t) dx (λ = eˣ). The trapezoidal rule in x with step h,
//! nodes x_j = x₀ + j h, gives
//!
//! t^{−1/2} ≈ Σ_j w_j e^{−λ_j t},   λ_j = e^{x_j},   w_j = h e^{x_j/2}/√π,
//!
//! whose relative error on the times the nodes cover is ≈ 2 e^{−π²/h} (the integrand is analytic
//! in the strip |Im x| < π/2; trapezoidal rule on an analytic integrand, Trefethen & Weideman
//! 2014, SIAM Rev. 56:385; the same construction as the exponential sums of Beylkin & Monzón
//! 2005, Appl. Comput. Harmon. Anal. 19:17, and of Jiang & Greengard's fast history
//! convolutions). The nodes run from λ ≈ 1/t_hi to λ ≈ 1/t_lo, with two spare nodes at each end.
//!
//! Times shorter than the fastest node are not resolved; the part of the kernel they carry,
//! ∫₀^∞ (t^{−1/2} − Σ) dt ≈ (2/√π) e^{−x_end/2} with x_end the upper edge of the last node's
//! cell, acts on the current acceleration as an added mass and is kept as such
//! ([`ExpSum::instant_sqrt_s`]): the history force is C_H (w₀ v′ + Σ w_j q_j), with
//! q_j′ = v′ − λ_j q_j. Times longer than the slowest node (beyond t_hi) lose the t^{−1/2} tail.
//! This is a fit made once per body from its time scales, not a table: no data file.

use std::f64::consts::PI;

/// Step of the trapezoidal rule in x = ln λ: relative kernel error ≈ 2e^{−π²/h} ≈ 1e-4.
pub const DEFAULT_STEP: f64 = 1.0;

/// The kernel t^{−1/2} as w₀ δ(t) + Σ_j w_j e^{−λ_j t}.
#[derive(Clone, Debug, PartialEq)]
pub struct ExpSum {
    /// Decay rates λ_j, 1/s, ascending.
    pub rates_per_s: Vec<f64>,
    /// Weights w_j, s^{−1/2}.
    pub weights_per_sqrt_s: Vec<f64>,
    /// Weight w₀ of the unresolved short-time part, s^{1/2} (the integral of the missing kernel).
    pub instant_sqrt_s: f64,
}

impl ExpSum {
    /// The sum whose nodes cover the times t_lo … t_hi (s, 0 < t_lo < t_hi) at step `h` in ln λ.
    pub fn covering(t_lo_s: f64, t_hi_s: f64, h: f64) -> Self {
        let x_lo = -t_hi_s.ln();
        let x_hi = -t_lo_s.ln() + 2.0 * h;
        let n = ((x_hi - x_lo) / h).ceil() as usize + 1;
        let xs: Vec<f64> = (0..n).map(|j| x_lo + j as f64 * h).collect();
        let x_end = xs[n - 1] + 0.5 * h;
        let mut rates: Vec<f64> = xs.iter().map(|x| x.exp()).collect();
        let mut weights: Vec<f64> = xs.iter().map(|x| h * (0.5 * x).exp() / PI.sqrt()).collect();
        // The slow tail below the first cell, π^{−1/2} ∫₀^{eᵃ} u^{−1/2} e^{−ut} du, as one term
        // exact to first order in t eᵃ: weight 2e^{a/2}/√π, rate eᵃ/3.
        let a = x_lo - 0.5 * h;
        rates.insert(0, a.exp() / 3.0);
        weights.insert(0, 2.0 / PI.sqrt() * (0.5 * a).exp());
        Self {
            rates_per_s: rates,
            weights_per_sqrt_s: weights,
            instant_sqrt_s: 2.0 / PI.sqrt() * (-0.5 * x_end).exp(),
        }
    }

    /// Number of exponentials (states per body).
    pub fn len(&self) -> usize {
        self.rates_per_s.len()
    }

    /// Whether the sum has no terms.
    pub fn is_empty(&self) -> bool {
        self.rates_per_s.is_empty()
    }

    /// The resolved part Σ w_j e^{−λ_j t} at time `t_s`, s^{−1/2}.
    pub fn eval(&self, t_s: f64) -> f64 {
        self.rates_per_s
            .iter()
            .zip(&self.weights_per_sqrt_s)
            .map(|(l, w)| w * (-l * t_s).exp())
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sum_is_the_kernel_on_the_covered_times() {
        // Six decades: 18 exponentials.
        let k = ExpSum::covering(1e-5, 1e1, DEFAULT_STEP);
        assert_eq!(k.len(), 18);
        let rel = |t: f64| (k.eval(t) * t.sqrt() - 1.0).abs();
        let mut t = 1e-5;
        while t <= 1e-1 {
            let bound = if t <= 1e-4 { 2e-4 } else { 1.5e-3 };
            assert!(rel(t) < bound, "t = {t:e}: relative error {:e}", rel(t));
            t *= 1.1;
        }
        // Outside: short times are under-resolved, long times decay too fast.
        assert!(k.eval(1e-10) * 1e-5 < 0.5);
        assert!(k.eval(1e5) * 1e5f64.sqrt() < 0.5);
    }

    #[test]
    fn the_instantaneous_part_carries_the_missing_short_time_integral() {
        // ∫₀^T t^{−1/2} dt = 2√T = w₀ + ∫₀^T Σ w_j e^{−λ_j t} dt.
        let k = ExpSum::covering(1e-4, 1e2, DEFAULT_STEP);
        let t_end: f64 = 1.0;
        let resolved: f64 = k
            .rates_per_s
            .iter()
            .zip(&k.weights_per_sqrt_s)
            .map(|(l, w)| w / l * -(-l * t_end).exp_m1())
            .sum();
        let total = k.instant_sqrt_s + resolved;
        assert!((total / (2.0 * t_end.sqrt()) - 1.0).abs() < 5e-4, "{total}");
        assert!(k.instant_sqrt_s > 0.0 && k.instant_sqrt_s < 2.0 * 1e-4f64.sqrt());
    }
}
