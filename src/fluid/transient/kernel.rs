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

/// The finite-Reynolds history kernel of Mei & Adrian (1992, J. Fluid Mech. 237:323, eq. 4.5 as
/// generalised by Dorgan & Loth 2007 with c₁ = 2, c₂ = 0.105), in the units of the Basset
/// kernel t^{−1/2} (s^{−1/2}): F_H = C_H ∫ v′(τ) K(t − τ) dτ with C_H = (3/2) d² √(π ρ_f μ) and
///
/// K(t) = √(4π/τ_d) · {(4π t/τ_d)^{1/4} + [π Re³ t²/(f_H³ τ_d²)]^{1/2}}^{−2},
///
/// τ_d = d²/ν the viscous diffusion time (s), Re the particle Reynolds number and
/// f_H = 0.75 + 0.105 Re. At short times (t ≪ t_c = (4/π)^{1/3} (f_H/Re)² τ_d) it is t^{−1/2}
/// (Basset); beyond t_c it decays as t^{−2}. The same form, reduced to K = (ξ^{1/4} + r ξ)^{−2}
/// with ξ = t/t_c, is in CFDEMcoupling-PFM's `ParmarBassetForce.C` (eqs. 3.1–3.4 there).
pub fn mei_adrian_kernel(t_s: f64, tau_d_s: f64, reynolds: f64) -> f64 {
    let f_h = 0.75 + 0.105 * reynolds;
    let a = (4.0 * PI * t_s / tau_d_s).powf(0.25);
    let b = (PI * reynolds.powi(3) * t_s * t_s / (f_h.powi(3) * tau_d_s * tau_d_s)).sqrt();
    (4.0 * PI / tau_d_s).sqrt() / ((a + b) * (a + b))
}

/// The crossover time t_c = (4/π)^{1/3} (f_H/Re)² τ_d of [`mei_adrian_kernel`] (s): the kernel is
/// Basset's before it and decays as t^{−2} after it.
pub fn mei_adrian_crossover_s(tau_d_s: f64, reynolds: f64) -> f64 {
    let f_h = 0.75 + 0.105 * reynolds;
    (4.0 / PI).powf(1.0 / 3.0) * (f_h / reynolds).powi(2) * tau_d_s
}

/// Sample times per unit of ln t in [`ExpSum::fit`].
const FIT_SAMPLES_PER_E_FOLD: f64 = 6.0;

impl ExpSum {
    /// A kernel `kernel(t)` (s^{−1/2}) that behaves as t^{−1/2} at short times, fitted on the
    /// times t_lo … t_hi by non-negative weights on the nodes of [`ExpSum::covering`] (the same
    /// log-spaced rates): the weights minimise the relative error Σ_i (Σ_j w_j e^{−λ_j t_i} /
    /// K(t_i) − 1)² over log-spaced t_i (non-negative least squares, Lawson & Hanson 1974,
    /// *Solving Least Squares Problems*, ch. 23). Terms with zero weight are dropped. The weight
    /// w₀ of the unresolved short times is ∫₀^{t_hi} (K − Σ) dt (with K = t^{−1/2} below
    /// 1e-6 t_lo), so the impulse of the kernel is kept.
    pub fn fit(t_lo_s: f64, t_hi_s: f64, h: f64, kernel: impl Fn(f64) -> f64) -> Self {
        let all = Self::fit_all(t_lo_s, t_hi_s, h, kernel);
        let keep: Vec<usize> = (0..all.len())
            .filter(|&j| all.weights_per_sqrt_s[j] > 0.0)
            .collect();
        Self {
            rates_per_s: keep.iter().map(|&j| all.rates_per_s[j]).collect(),
            weights_per_sqrt_s: keep.iter().map(|&j| all.weights_per_sqrt_s[j]).collect(),
            instant_sqrt_s: all.instant_sqrt_s,
        }
    }

    /// [`ExpSum::fit`] keeping the terms of zero weight: every kernel fitted on the same times
    /// has the same rates, term by term (for weights that change with the Reynolds number).
    pub fn fit_all(t_lo_s: f64, t_hi_s: f64, h: f64, kernel: impl Fn(f64) -> f64) -> Self {
        let grid = Self::covering(t_lo_s, t_hi_s, h);
        let (s_lo, s_hi) = (t_lo_s.ln(), t_hi_s.ln());
        let n_t = ((s_hi - s_lo) * FIT_SAMPLES_PER_E_FOLD).ceil() as usize + 1;
        let times: Vec<f64> = (0..n_t)
            .map(|i| (s_lo + (s_hi - s_lo) * i as f64 / (n_t - 1) as f64).exp())
            .collect();
        let a = nalgebra::DMatrix::from_fn(n_t, grid.len(), |i, j| {
            (-grid.rates_per_s[j] * times[i]).exp() / kernel(times[i])
        });
        let b = nalgebra::DVector::from_element(n_t, 1.0);
        let w = nnls(&a, &b);
        let mut sum = Self {
            rates_per_s: grid.rates_per_s,
            weights_per_sqrt_s: w.iter().copied().collect(),
            instant_sqrt_s: 0.0,
        };
        // ∫₀^{t_hi} (K − Σ) dt: analytic below t_a, trapezoidal in ln t above.
        let t_a = 1e-6 * t_lo_s;
        let resolved = |t: f64| -> f64 {
            sum.rates_per_s
                .iter()
                .zip(&sum.weights_per_sqrt_s)
                .map(|(l, w)| w / l * -(-l * t).exp_m1())
                .sum()
        };
        let mut missing = 2.0 * t_a.sqrt() - resolved(t_a);
        let (u0, u1) = (t_a.ln(), s_hi);
        let n = ((u1 - u0) * 200.0).ceil() as usize;
        let du = (u1 - u0) / n as f64;
        let f = |u: f64| {
            let t = u.exp();
            (kernel(t) - sum.eval(t)) * t
        };
        for i in 0..n {
            let (ua, ub) = (u0 + i as f64 * du, u0 + (i + 1) as f64 * du);
            missing += 0.5 * du * (f(ua) + f(ub));
        }
        sum.instant_sqrt_s = missing.max(0.0);
        sum
    }
}

// Kept over the nnls crate (its weights break the kernel's impulse): docs/validation/numerics.md.
/// Non-negative least squares min ‖A x − b‖, x ≥ 0 (Lawson & Hanson's active-set algorithm;
/// the unconstrained sub-problems by SVD).
fn nnls(a: &nalgebra::DMatrix<f64>, b: &nalgebra::DVector<f64>) -> nalgebra::DVector<f64> {
    let n = a.ncols();
    let mut x = nalgebra::DVector::zeros(n);
    let mut passive = vec![false; n];
    let tol = 1e-12 * a.norm() * b.norm();
    for _ in 0..3 * n {
        let grad = a.transpose() * (b - a * &x);
        let Some((j, g)) = (0..n)
            .filter(|&j| !passive[j])
            .map(|j| (j, grad[j]))
            .max_by(|p, q| p.1.total_cmp(&q.1))
        else {
            break;
        };
        if g <= tol {
            break;
        }
        passive[j] = true;
        for _ in 0..3 * n {
            let cols: Vec<usize> = (0..n).filter(|&k| passive[k]).collect();
            let ap = a.select_columns(&cols);
            let svd = ap.svd(true, true);
            let eps = 1e-13 * svd.singular_values.max();
            let zp = svd.solve(b, eps).expect("SVD with U and V");
            if zp.iter().all(|&z| z > 0.0) {
                x.fill(0.0);
                for (k, &c) in cols.iter().enumerate() {
                    x[c] = zp[k];
                }
                break;
            }
            // Step back to the boundary and free the variables that reach zero.
            let mut alpha = 1.0f64;
            for (k, &c) in cols.iter().enumerate() {
                if zp[k] <= 0.0 {
                    alpha = alpha.min(x[c] / (x[c] - zp[k]));
                }
            }
            for (k, &c) in cols.iter().enumerate() {
                x[c] += alpha * (zp[k] - x[c]);
                if x[c] <= 1e-300 {
                    x[c] = 0.0;
                    passive[c] = false;
                }
            }
        }
    }
    x
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

    /// The fitted Mei–Adrian sum follows the kernel within 1 % (relative) on the fitted times, at
    /// the Reynolds numbers of ten Cate's E1 and E4, with at most 20 terms; its impulse
    /// w₀ + Σ w_j/λ_j is the kernel's integral (an independent quadrature) within 1 %.
    #[test]
    fn the_mei_adrian_fit_follows_the_kernel() {
        // E1: d = 15 mm, ν = 0.373/970 m²/s, Re 1.5; E4: ν = 0.058/960, Re 32.
        for (nu, re) in [(0.373 / 970.0, 1.5), (0.058 / 960.0, 32.0)] {
            let tau_d = 0.015f64.powi(2) / nu;
            let k = |t: f64| mei_adrian_kernel(t, tau_d, re);
            let (t_lo, t_hi) = (1e-5, 40.0);
            let fit = ExpSum::fit(t_lo, t_hi, DEFAULT_STEP, k);
            assert!(fit.len() <= 20, "{} terms", fit.len());
            let mut worst: f64 = 0.0;
            let mut t = t_lo;
            while t <= t_hi {
                worst = worst.max((fit.eval(t) / k(t) - 1.0).abs());
                t *= 1.05;
            }
            eprintln!("Re {re}: {} terms, max relative error {worst:e}", fit.len());
            assert!(worst < 1e-2, "Re {re}: {worst}");
            // ∫₀^∞ K dt in ln t (K ≈ t^{−1/2} below 1e-9 s, K ∝ t^{−2} above 1e4 s).
            let (u0, u1) = (1e-9f64.ln(), 1e4f64.ln());
            let n = 200_000;
            let du = (u1 - u0) / n as f64;
            let total: f64 = 2.0 * 1e-9f64.sqrt()
                + (0..=n)
                    .map(|i| {
                        let t = (u0 + i as f64 * du).exp();
                        let w = if i == 0 || i == n { 0.5 } else { 1.0 };
                        w * k(t) * t * du
                    })
                    .sum::<f64>()
                + k(1e4) * 1e4;
            let impulse = fit.instant_sqrt_s
                + fit
                    .rates_per_s
                    .iter()
                    .zip(&fit.weights_per_sqrt_s)
                    .map(|(l, w)| w / l)
                    .sum::<f64>();
            assert!((impulse / total - 1.0).abs() < 1e-2, "{impulse} vs {total}");
        }
    }

    /// Mei & Adrian's kernel is Basset's at short times and falls as t^{−2} beyond t_c.
    #[test]
    fn the_mei_adrian_kernel_limits() {
        let (tau_d, re) = (3.7, 32.0);
        let tc = mei_adrian_crossover_s(tau_d, re);
        let t = 1e-6 * tc;
        assert!((mei_adrian_kernel(t, tau_d, re) * t.sqrt() - 1.0).abs() < 0.05);
        let (t1, t2) = (1e3 * tc, 2e3 * tc);
        let ratio = mei_adrian_kernel(t1, tau_d, re) / mei_adrian_kernel(t2, tau_d, re);
        assert!((ratio / 4.0 - 1.0).abs() < 0.05, "{ratio}");
        // The two terms are equal at t_c: K = K_Basset / 4 there.
        assert!((mei_adrian_kernel(tc, tau_d, re) * tc.sqrt() - 0.25).abs() < 1e-9);
    }

    /// Fitted to t^{−1/2} itself, the non-negative fit gives back the trapezoidal sum's accuracy.
    #[test]
    fn the_fit_of_the_basset_kernel_matches_the_trapezoidal_sum() {
        let fit = ExpSum::fit(1e-4, 1e2, DEFAULT_STEP, |t: f64| t.powf(-0.5));
        let mut t = 1e-4;
        while t <= 1e2 {
            let e = (fit.eval(t) * t.sqrt() - 1.0).abs();
            assert!(e < 2e-3, "t {t:e}: {e:e}");
            t *= 1.1;
        }
    }
}
