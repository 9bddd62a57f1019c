//! Bounded minimisers of a few-parameter objective, written here (no crate): Brent's method for
//! one parameter and Nelder–Mead on the unit box for several, plus the Gauss–Newton covariance
//! of a least-squares fit. Pure: the objective is a closure (each call of `settle fit`'s is a
//! whole run), so the methods count their evaluations and stop at a tolerance in the parameter.
//!
//! Sources: Brent, R. P. (1973), *Algorithms for Minimization without Derivatives*, ch. 5
//! (golden section with parabolic steps); Nelder, J. A. & Mead, R. (1965), *Comput. J.* 7, 308
//! (reflection 1, expansion 2, contraction ½, shrink ½).

use crate::numerics::{try_bisect, Bisection, Stop};

/// The outcome of a minimisation.
#[derive(Clone, Debug, PartialEq)]
pub struct Minimum {
    /// The best point found, one value per parameter.
    pub x: Vec<f64>,
    /// The objective there.
    pub f: f64,
    /// Objective evaluations made.
    pub evaluations: usize,
    /// Whether the tolerance was reached within the evaluation limit.
    pub converged: bool,
}

// Kept over argmin's BrentOpt (same runs, same x): docs/validation/numerics.md.
/// Brent's method on `[lo, hi]`: the minimum of `f` to within `xtol` (absolute, in x) using at
/// most `max_evals` evaluations. An error of `f` stops the search and is returned.
pub fn brent<E>(
    f: &mut dyn FnMut(f64) -> Result<f64, E>,
    lo: f64,
    hi: f64,
    xtol: f64,
    max_evals: usize,
) -> Result<Minimum, E> {
    const GOLD: f64 = 0.381_966_011_250_105_1; // (3 − √5)/2
    let (mut a, mut b) = (lo, hi);
    let mut x = a + GOLD * (b - a);
    let (mut w, mut v) = (x, x);
    let mut fx = f(x)?;
    let (mut fw, mut fv) = (fx, fx);
    let mut evals = 1;
    let (mut d, mut e) = (0.0_f64, 0.0_f64);
    let mut converged = false;
    while evals < max_evals {
        let m = 0.5 * (a + b);
        let tol = 1e-10 * x.abs() + xtol / 3.0;
        if (x - m).abs() <= 2.0 * tol - 0.5 * (b - a) {
            converged = true;
            break;
        }
        let mut golden = true;
        if e.abs() > tol {
            // Parabola through x, w, v.
            let r = (x - w) * (fx - fv);
            let q0 = (x - v) * (fx - fw);
            let mut p = (x - v) * q0 - (x - w) * r;
            let mut q = 2.0 * (q0 - r);
            if q > 0.0 {
                p = -p;
            }
            q = q.abs();
            if p.abs() < (0.5 * q * e).abs() && p > q * (a - x) && p < q * (b - x) {
                e = d;
                d = p / q;
                let u = x + d;
                if u - a < 2.0 * tol || b - u < 2.0 * tol {
                    d = if x < m { tol } else { -tol };
                }
                golden = false;
            }
        }
        if golden {
            e = if x < m { b - x } else { a - x };
            d = GOLD * e;
        }
        let u = if d.abs() >= tol {
            x + d
        } else {
            x + tol.copysign(d)
        };
        let fu = f(u)?;
        evals += 1;
        if fu <= fx {
            if u < x {
                b = x;
            } else {
                a = x;
            }
            (v, fv, w, fw, x, fx) = (w, fw, x, fx, u, fu);
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w == x {
                (v, fv, w, fw) = (w, fw, u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    Ok(Minimum {
        x: vec![x],
        f: fx,
        evaluations: evals,
        converged,
    })
}

// Kept over argmin's NelderMead (stops on χ² spread, unbounded): docs/validation/numerics.md.
/// Nelder–Mead on the box `lo[i] ≤ x[i] ≤ hi[i]`, worked in unit coordinates (each parameter
/// scaled to [0, 1], points clamped to the box), from the box's centre with a simplex of side
/// ¼; stops when every vertex is within `xtol_unit` of the best in every unit coordinate, or
/// after `max_evals` evaluations (not converged).
pub fn nelder_mead<E>(
    f: &mut dyn FnMut(&[f64]) -> Result<f64, E>,
    lo: &[f64],
    hi: &[f64],
    xtol_unit: f64,
    max_evals: usize,
) -> Result<Minimum, E> {
    let n = lo.len();
    let to_x = |u: &[f64]| -> Vec<f64> {
        u.iter()
            .enumerate()
            .map(|(i, &t)| lo[i] + t.clamp(0.0, 1.0) * (hi[i] - lo[i]))
            .collect()
    };
    let mut evals = 0;
    let mut eval = |u: &[f64], evals: &mut usize| -> Result<f64, E> {
        *evals += 1;
        f(&to_x(u))
    };
    let centre = vec![0.5; n];
    let mut simplex: Vec<(Vec<f64>, f64)> = Vec::with_capacity(n + 1);
    simplex.push((centre.clone(), eval(&centre, &mut evals)?));
    for i in 0..n {
        let mut u = centre.clone();
        u[i] += 0.25;
        let fu = eval(&u, &mut evals)?;
        simplex.push((u, fu));
    }
    let mut converged = false;
    let clamp = |u: Vec<f64>| -> Vec<f64> { u.into_iter().map(|t| t.clamp(0.0, 1.0)).collect() };
    while evals < max_evals {
        simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
        let best = simplex[0].0.clone();
        let spread = simplex
            .iter()
            .flat_map(|(u, _)| u.iter().zip(&best).map(|(a, b)| (a - b).abs()))
            .fold(0.0_f64, f64::max);
        if spread <= xtol_unit {
            converged = true;
            break;
        }
        let worst = simplex[n].clone();
        let c: Vec<f64> = (0..n)
            .map(|i| simplex[..n].iter().map(|(u, _)| u[i]).sum::<f64>() / n as f64)
            .collect();
        let along = |t: f64| clamp((0..n).map(|i| c[i] + t * (worst.0[i] - c[i])).collect());
        let r = along(-1.0);
        let fr = eval(&r, &mut evals)?;
        if fr < simplex[0].1 {
            let e = along(-2.0);
            let fe = eval(&e, &mut evals)?;
            simplex[n] = if fe < fr { (e, fe) } else { (r, fr) };
        } else if fr < simplex[n - 1].1 {
            simplex[n] = (r, fr);
        } else {
            let k = if fr < worst.1 {
                along(-0.5)
            } else {
                along(0.5)
            };
            let fk = eval(&k, &mut evals)?;
            if fk < worst.1.min(fr) {
                simplex[n] = (k, fk);
            } else {
                for vertex in simplex.iter_mut().skip(1) {
                    let u: Vec<f64> = (0..n)
                        .map(|i| best[i] + 0.5 * (vertex.0[i] - best[i]))
                        .collect();
                    let fu = eval(&u, &mut evals)?;
                    *vertex = (u, fu);
                }
            }
        }
    }
    simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
    Ok(Minimum {
        x: to_x(&simplex[0].0),
        f: simplex[0].1,
        evaluations: evals,
        converged,
    })
}

/// The Gauss–Newton covariance (JᵀWJ)⁻¹ of a weighted least-squares fit: `jac[i][j]` is
/// ∂model_i/∂x_j at the minimum and `sigma[i]` the uncertainty of measurement i (W = 1/σ²).
/// None when JᵀWJ is singular (a parameter the measurements do not constrain).
pub fn covariance(jac: &[Vec<f64>], sigma: &[f64]) -> Option<Vec<Vec<f64>>> {
    let p = jac.first().map_or(0, Vec::len);
    let mut a = vec![vec![0.0; 2 * p]; p];
    for (row, s) in jac.iter().zip(sigma) {
        for j in 0..p {
            for k in 0..p {
                a[j][k] += row[j] * row[k] / (s * s);
            }
        }
    }
    for (j, r) in a.iter_mut().enumerate() {
        r[p + j] = 1.0;
    }
    // Gauss–Jordan with partial pivoting.
    let scale = a
        .iter()
        .flat_map(|r| r[..p].iter())
        .fold(0.0_f64, |m, x| m.max(x.abs()));
    for col in 0..p {
        let piv = (col..p).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[piv][col].abs() <= 1e-12 * scale || a[piv][col].is_nan() {
            return None;
        }
        a.swap(col, piv);
        let d = a[col][col];
        a[col].iter_mut().for_each(|x| *x /= d);
        for r in 0..p {
            if r != col {
                let k = a[r][col];
                let pivot_row = a[col].clone();
                a[r].iter_mut()
                    .zip(&pivot_row)
                    .for_each(|(x, y)| *x -= k * y);
            }
        }
    }
    Some(a.into_iter().map(|r| r[p..].to_vec()).collect())
}

/// Where a 1-D objective `f` crosses `level` between `inside` (below the level) and `outside`
/// (above it, or the bound if it never rises there): bisection to within `xtol`, at most
/// `max_evals` evaluations. None when `f(outside)` is still below the level (the crossing lies
/// beyond the bound).
pub fn crossing<E>(
    f: &mut dyn FnMut(f64) -> Result<f64, E>,
    level: f64,
    inside: f64,
    outside: f64,
    xtol: f64,
    max_evals: usize,
) -> Result<Option<f64>, E> {
    if f(outside)? < level {
        return Ok(None);
    }
    let rule = Bisection::until(Stop::Width(xtol), max_evals);
    let (a, b) = try_bisect(inside, outside, rule, |m| Ok(f(m)? < level))?;
    Ok(Some(0.5 * (a + b)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::convert::Infallible;

    #[test]
    fn brent_finds_a_parabola_minimum() {
        let mut f = |x: f64| Ok::<_, Infallible>((x - 0.7).powi(2) + 3.0);
        let m = brent(&mut f, 0.1, 3.0, 1e-8, 100).unwrap();
        assert!(m.converged);
        assert!((m.x[0] - 0.7).abs() < 1e-7, "{m:?}");
        assert!(m.evaluations < 40, "{m:?}");
    }

    #[test]
    fn brent_at_a_bound_and_with_few_evaluations() {
        let mut f = |x: f64| Ok::<_, Infallible>(x);
        let m = brent(&mut f, 1.0, 2.0, 1e-6, 200).unwrap();
        assert!((m.x[0] - 1.0).abs() < 1e-5, "{m:?}");
        let mut g = |x: f64| Ok::<_, Infallible>((x - 0.3).powi(2));
        assert!(!brent(&mut g, 0.0, 1.0, 1e-12, 3).unwrap().converged);
    }

    #[test]
    fn nelder_mead_finds_a_bowl_minimum() {
        let mut f = |x: &[f64]| {
            Ok::<_, Infallible>((x[0] - 2.0).powi(2) + 10.0 * (x[1] + 1.0).powi(2) + x[0] * x[1])
        };
        // grad = 0: 2(x0 − 2) + x1 = 0, 20(x1 + 1) + x0 = 0 → x0 = 100/39, x1 = −44/39.
        let m = nelder_mead(&mut f, &[0.0, -3.0], &[4.0, 1.0], 1e-7, 2000).unwrap();
        assert!(m.converged);
        assert!((m.x[0] - 100.0 / 39.0).abs() < 1e-5, "{m:?}");
        assert!((m.x[1] + 44.0 / 39.0).abs() < 1e-5, "{m:?}");
    }

    #[test]
    fn covariance_of_a_line_fit() {
        // model = a x at x = 1, 2 with σ = 1: JᵀJ = 5 → var(a) = 0.2.
        let c = covariance(&[vec![1.0], vec![2.0]], &[1.0, 1.0]).unwrap();
        assert!((c[0][0] - 0.2).abs() < 1e-12);
        assert!(covariance(&[vec![1.0, 2.0], vec![2.0, 4.0]], &[1.0, 1.0]).is_none());
    }

    #[test]
    fn crossing_of_a_parabola() {
        let mut f = |x: f64| Ok::<_, Infallible>(x * x);
        let c = crossing(&mut f, 1.0, 0.0, 3.0, 1e-9, 100).unwrap().unwrap();
        assert!((c - 1.0).abs() < 1e-8);
        assert_eq!(crossing(&mut f, 100.0, 0.0, 3.0, 1e-9, 100).unwrap(), None);
    }
}
