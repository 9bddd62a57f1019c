//! The regularised, constrained least-squares problem of one (linearised) inversion step:
//!
//! min_w Σ_i ((b_i − J_i·w)/σ_i)² + λ Σ_k (w_{k+1} − w_k)²  subject to  w ≥ 0, Σ_j w_j = 1,
//!
//! over the bins of the distribution (the finest bin holds everything finer than the readings
//! resolve, the coarsest everything coarser, so the cumulative curve is non-negative, monotone
//! and reaches 100 % by construction). The penalty is Tikhonov's (Tikhonov & Arsenin 1977) on
//! the first differences of w over the resolved bins, i.e. on the second differences of the
//! cumulative curve at the bin edges (bins are even in ln d); the two end bins are not
//! penalised.
//!
//! The quadratic programme is solved exactly by a primal active-set method (Nocedal & Wright,
//! *Numerical Optimization*, 2nd ed., Algorithm 16.3) on its KKT systems, dense: the problems
//! have at most a few dozen unknowns. λ is chosen by the discrepancy principle (Morozov 1966:
//! the largest λ whose misfit is what the readings' uncertainty explains; here χ² ≤ m − tr H,
//! the residual degrees of freedom of the fit (Hastie & Tibshirani 1990, §3.5), rather than
//! χ² ≤ m, which over-smooths a steep curve with few readings) or by generalised
//! cross-validation (Golub, Heath & Wahba 1979: the λ minimising m χ²/(m − tr H)²), H the
//! influence matrix of the free variables ([`Linear::solve`]).

use crate::numerics::{bisect, Bisection};
use nalgebra::{DMatrix, DVector};

/// One linear least-squares problem: readings b with standard deviations σ, design J
/// (row i: ∂ reading i / ∂ w).
#[derive(Clone, Debug)]
pub struct Linear {
    /// Design matrix, one row per reading, one column per bin.
    pub j: DMatrix<f64>,
    /// Readings minus what does not depend on w, in the files' units.
    pub b: DVector<f64>,
    /// Standard deviation of each reading.
    pub sigma: DVector<f64>,
}

/// How λ is chosen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LambdaRule {
    /// A fixed λ.
    Fixed(f64),
    /// The discrepancy principle: the largest λ with χ² ≤ m − tr H (m readings, tr H the
    /// effective number of parameters).
    Discrepancy,
    /// Generalised cross-validation (Golub, Heath & Wahba 1979).
    Gcv,
}

/// A solution of one problem.
#[derive(Clone, Debug)]
pub struct Solution {
    /// Mass fraction of each bin.
    pub w: Vec<f64>,
    /// The λ used.
    pub lambda: f64,
    /// χ² = Σ ((b − J w)/σ)².
    pub chi2: f64,
}

impl Linear {
    fn weighted(&self) -> (DMatrix<f64>, DVector<f64>) {
        let mut a = self.j.clone();
        let mut y = self.b.clone();
        for i in 0..a.nrows() {
            let s = self.sigma[i];
            a.row_mut(i).scale_mut(1.0 / s);
            y[i] /= s;
        }
        (a, y)
    }

    /// χ² of `w`.
    pub fn chi2(&self, w: &[f64]) -> f64 {
        let r = &self.b - &self.j * DVector::from_column_slice(w);
        r.iter()
            .zip(self.sigma.iter())
            .map(|(r, s)| (r / s).powi(2))
            .sum()
    }

    /// The penalty matrix LᵀL of the first differences of w over bins 1..n−2.
    fn penalty(n: usize) -> DMatrix<f64> {
        let mut p = DMatrix::zeros(n, n);
        for k in 1..n.saturating_sub(2) {
            p[(k, k)] += 1.0;
            p[(k + 1, k + 1)] += 1.0;
            p[(k, k + 1)] -= 1.0;
            p[(k + 1, k)] -= 1.0;
        }
        p
    }

    /// The scale of λ: trace(JᵀΣ⁻²J)/trace(LᵀL), so that λ = 1 weighs both terms alike.
    pub fn lambda_scale(&self) -> f64 {
        let (a, _) = self.weighted();
        let n = a.ncols();
        let t = (a.transpose() * &a).trace();
        let p = Self::penalty(n).trace().max(1.0);
        (t / p).max(1e-300)
    }

    /// Solves at a given λ, starting from the free set of `start` (all bins if None).
    pub fn solve_at(&self, lambda: f64, start: Option<&[f64]>) -> Solution {
        self.solve_towards(lambda, start, None)
    }

    /// Solves at λ with the penalty λ Σ_k (w_{k+1} − w_k − η_k)² (η = 0 if None): with η drawn
    /// from the prior N(0, 1/λ) and the readings from their error, the solution is a draw of the
    /// (constrained) posterior of the Gaussian reading of Tikhonov's problem
    /// (randomise-then-optimise, Bardsley et al. 2014).
    pub fn solve_towards(
        &self,
        lambda: f64,
        start: Option<&[f64]>,
        eta: Option<&[f64]>,
    ) -> Solution {
        let (a, y) = self.weighted();
        let n = a.ncols();
        let mut q = a.transpose() * &a + Self::penalty(n) * lambda;
        let ridge = 1e-12 * (q.trace() / n as f64).max(1e-300);
        for k in 0..n {
            q[(k, k)] += ridge;
        }
        let mut c = a.transpose() * &y;
        if let Some(eta) = eta {
            for (k, e) in (1..n.saturating_sub(2)).zip(eta) {
                c[k + 1] += lambda * e;
                c[k] -= lambda * e;
            }
        }
        let w = simplex_qp(&q, &c, start);
        let chi2 = self.chi2(&w);
        Solution { w, lambda, chi2 }
    }

    /// tr H of the solution `w` at λ: H = A_F P A_Fᵀ with P the block of the inverse KKT
    /// matrix of the free variables F (w_j > 0) and the sum constraint.
    fn influence_trace(&self, lambda: f64, w: &[f64]) -> f64 {
        let (a, _) = self.weighted();
        let n = a.ncols();
        let free: Vec<usize> = (0..n).filter(|&j| w[j] > 0.0).collect();
        let q = a.transpose() * &a + Self::penalty(n) * lambda;
        let kkt = kkt_matrix(&q, &free);
        let Some(inv) = kkt.try_inverse() else {
            return free.len() as f64;
        };
        let f = free.len();
        let af = a.select_columns(&free);
        let p = inv.view((0, 0), (f, f)).into_owned();
        (p * (af.transpose() * af)).trace()
    }

    /// Strict bounds of a linear functional of the distribution (Backus 1970, "Inference from
    /// inadequate and inaccurate data"; Stark 1992, J. Geophys. Res. 97 B10, 14055): the smallest
    /// and largest value of c·w over every distribution of the bins (w ≥ 0, Σw = 1) whose
    /// χ² = Σ ((b − J w)/σ)² is at most `chi2_max`, no smoothing. With c_j the fraction of bin j
    /// finer than d (`Bins::fraction_finer`), c·w is F(d): the range of the cumulative curve at
    /// d that the readings allow. None if no distribution fits within `chi2_max`.
    ///
    /// Convex (a linear objective over the intersection of an ellipsoid and the simplex), solved
    /// through its Lagrangian: w(μ) = argmin χ²(w) ± μ c·w over the simplex ([`simplex_qp`])
    /// has χ²(w(μ)) non-decreasing in μ ≥ 0, and μ is bisected (in ln μ) until χ² = `chi2_max`.
    pub fn strict_bounds(&self, c: &[f64], chi2_max: f64) -> Option<(f64, f64)> {
        let (a, y) = self.weighted();
        let n = a.ncols();
        let mut q = a.transpose() * &a * 2.0;
        let s = (q.trace() / n as f64).max(1e-300);
        for k in 0..n {
            q[(k, k)] += 1e-10 * s;
        }
        let g = a.transpose() * &y * 2.0;
        let cv = DVector::from_column_slice(c);
        let at = |mu: f64, sign: f64| {
            let w = simplex_qp(&q, &(&g - &cv * (sign * mu)), None);
            (self.chi2(&w), cv.dot(&DVector::from_column_slice(&w)))
        };
        // w(0): the feasible point of least χ² (μ = 0, either sign).
        let (least_chi2, at_least) = at(0.0, 1.0);
        if least_chi2 > chi2_max {
            return None;
        }
        // μ up to 10⁶ s: beyond, the linear term swamps the quadratic one in simplex_qp and
        // w(μ) turns to rounding noise (issue 26: at 10¹² s, χ² jumped between 4 and 18 and
        // the upper bound of sample 4 fell below the recovered curve's own 100 %); at 10⁶ s
        // w(μ) is within ~10⁻⁶ of the extreme face. The bounds are at least as wide as the
        // feasible point of least χ², w(0).
        let extreme = |sign: f64| {
            let (lo, hi) = ((1e-12 * s).ln(), (1e6 * s).ln());
            let (chi2_hi, extreme_hi) = at(hi.exp(), sign);
            if chi2_hi <= chi2_max {
                return extreme_hi;
            }
            if at(lo.exp(), sign).0 > chi2_max {
                return at_least;
            }
            let (lo, _) = bisect(lo, hi, Bisection::halvings(48), |mid| {
                at(mid.exp(), sign).0 <= chi2_max
            });
            at(lo.exp(), sign).1
        };
        Some((extreme(1.0).min(at_least), extreme(-1.0).max(at_least)))
    }

    /// Solves with λ chosen by `rule` over a grid of λ/scale from 10⁻¹⁰ to 10⁴ (8 per decade).
    pub fn solve(&self, rule: LambdaRule) -> Solution {
        self.solve_drawn(rule, None)
    }

    /// [`Linear::solve`] with the prior draw η = z/√λ of [`Linear::solve_towards`] at each λ
    /// (z standard normal; none if None).
    pub fn solve_drawn(&self, rule: LambdaRule, z: Option<&[f64]>) -> Solution {
        let at = |l: f64| match z {
            Some(z) => {
                let eta: Vec<f64> = z.iter().map(|x| x / l.max(1e-300).sqrt()).collect();
                self.solve_towards(l, None, Some(&eta))
            }
            None => self.solve_at(l, None),
        };
        if let LambdaRule::Fixed(l) = rule {
            return at(l);
        }
        let scale = self.lambda_scale();
        let m = self.b.len() as f64;
        let grid: Vec<f64> = (0..=112)
            .map(|k| scale * 10f64.powf(-10.0 + k as f64 / 8.0))
            .collect();
        let sols: Vec<Solution> = grid.iter().map(|&l| at(l)).collect();
        match rule {
            LambdaRule::Discrepancy => sols
                .iter()
                .rev()
                .find(|s| s.chi2 <= m - self.influence_trace(s.lambda, &s.w))
                .unwrap_or(&sols[0])
                .clone(),
            _ => {
                let gcv = |s: &Solution| {
                    let t = self.influence_trace(s.lambda, &s.w);
                    m * s.chi2 / (m - t).max(1e-3).powi(2)
                };
                sols.iter()
                    .map(|s| (gcv(s), s))
                    .min_by(|x, y| x.0.total_cmp(&y.0))
                    .map(|(_, s)| s.clone())
                    .unwrap_or_else(|| sols[0].clone())
            }
        }
    }
}

/// The KKT matrix [Q_FF 1; 1ᵀ 0] of the free set F.
fn kkt_matrix(q: &DMatrix<f64>, free: &[usize]) -> DMatrix<f64> {
    let f = free.len();
    let mut k = DMatrix::zeros(f + 1, f + 1);
    for (a, &i) in free.iter().enumerate() {
        for (b, &j) in free.iter().enumerate() {
            k[(a, b)] = q[(i, j)];
        }
        k[(a, f)] = 1.0;
        k[(f, a)] = 1.0;
    }
    k
}

/// The χ² bar of strict bounds at confidence `confidence` (0 < P < 1) for `m` readings: the
/// P-quantile of the χ² distribution with m degrees of freedom, so that χ² of the true curve,
/// a sum of m squared standard normal misfits when the readings' σ are right, stays below it
/// with probability P (Stark 1992, the data constraint of strict bounds; e.g. χ²₂₇(0.95) =
/// 40.11, NIST/SEMATECH e-Handbook 1.3.6.7.4). Computed by `statrs` (the inverse of the
/// regularised lower incomplete gamma function).
pub fn chi2_bar(m: usize, confidence: f64) -> f64 {
    use statrs::distribution::{ChiSquared, ContinuousCDF};
    ChiSquared::new(m.max(1) as f64)
        .map(|d| d.inverse_cdf(confidence))
        .unwrap_or(f64::NAN)
}

// Kept over clarabel (exact, 6× faster, no failures): docs/validation/numerics.md.
/// min ½ wᵀQw − cᵀw subject to w ≥ 0 and Σw = 1 (Q positive definite on {Σw = 0}), by the
/// primal active-set method: solve the equality-constrained problem on the free set, step back
/// to feasibility when a free variable would go negative (freeing it no more), and free the
/// bound variable of most negative multiplier until none is negative.
pub fn simplex_qp(q: &DMatrix<f64>, c: &DVector<f64>, start: Option<&[f64]>) -> Vec<f64> {
    let n = c.len();
    let mut w: Vec<f64> = match start {
        Some(s) if s.len() == n && s.iter().any(|&x| x > 0.0) => {
            let t: f64 = s.iter().map(|x| x.max(0.0)).sum();
            s.iter().map(|x| x.max(0.0) / t).collect()
        }
        _ => vec![1.0 / n as f64; n],
    };
    let mut free: Vec<bool> = w.iter().map(|&x| x > 0.0).collect();
    for _ in 0..(20 * n + 50) {
        let idx: Vec<usize> = (0..n).filter(|&j| free[j]).collect();
        let f = idx.len();
        let mut rhs = DVector::zeros(f + 1);
        for (a, &i) in idx.iter().enumerate() {
            rhs[a] = c[i];
        }
        rhs[f] = 1.0;
        let Some(sol) = kkt_matrix(q, &idx).lu().solve(&rhs) else {
            break;
        };
        let target: Vec<f64> = idx.iter().enumerate().map(|(a, _)| sol[a]).collect();
        if target.iter().all(|&x| x >= 0.0) {
            for (a, &i) in idx.iter().enumerate() {
                w[i] = target[a];
            }
            // Multipliers of the bounds: g_j = (Qw − c)_j + ν ≥ 0 at the optimum.
            let nu = sol[f];
            let g = q * DVector::from_column_slice(&w) - c;
            let worst = (0..n)
                .filter(|&j| !free[j])
                .map(|j| (j, g[j] + nu))
                .min_by(|x, y| x.1.total_cmp(&y.1));
            match worst {
                Some((j, m)) if m < -1e-12 * (1.0 + nu.abs()) => free[j] = true,
                _ => return w,
            }
        } else {
            // Step from w towards the target until the first free variable reaches 0.
            let (mut alpha, mut block) = (1.0f64, None);
            for (a, &i) in idx.iter().enumerate() {
                if target[a] < 0.0 {
                    let r = w[i] / (w[i] - target[a]);
                    if r < alpha {
                        (alpha, block) = (r, Some(i));
                    }
                }
            }
            for (a, &i) in idx.iter().enumerate() {
                w[i] = (w[i] + alpha * (target[a] - w[i])).max(0.0);
            }
            if let Some(b) = block {
                w[b] = 0.0;
                free[b] = false;
            }
            let t: f64 = w.iter().sum();
            w.iter_mut().for_each(|x| *x /= t);
        }
    }
    w
}
