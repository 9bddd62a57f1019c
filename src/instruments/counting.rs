//! The counting noise of the representative grains (issue 26, item 8).
//!
//! A run simulates N representative grains; grain i stands for the real mass m_i (its weight
//! times one grain's mass). An instrument's reading is, to first order, a weighted sum of the
//! masses of the grains in its volume, R = R_0 + Σ_i a_i m_i, where a_i is the reading's
//! sensitivity to a unit of solid mass at grain i's place (the hydrometer's and the sphere's
//! weight of the layer the grain is in, the pipette's 1 inside its draw).
//!
//! Where the grains are is random: the grains of a size class are scattered over the column
//! independently, so the number of them that land in a given volume is Poisson (the binomial of
//! N independent placements, in the limit of a volume small against the column). A sum of
//! marks over a Poisson number of points, S = Σ_{i ≤ K} X_i with K ~ Poisson(λ) and the X_i
//! independent of K, is *compound Poisson*, of variance
//!
//! Var S = λ E[X²]   (Feller, *An Introduction to Probability Theory and Its Applications*,
//! vol. 1, 3rd ed. 1968, ch. XII.2, the compound Poisson distribution; vol. 2, 2nd ed. 1971,
//! ch. VI.4; it is also Campbell's theorem for a marked Poisson process).
//!
//! With the grains actually present as the sample of the marks (λ E[X²] estimated by the sum
//! over the grains counted), the reading's counting variance is
//!
//! σ² = Σ_i (a_i m_i)²                                                               (1)
//!
//! in the reading's unit. For grains of equal contribution it is the Poisson σ = R/√n; grains
//! of unequal mass count as the effective number n_eff = (Σ a_i m_i)² / Σ (a_i m_i)² <= n
//! ([`effective_count`]). The instruments that read a layered field (hydrometer, sphere) give
//! every grain of layer k the same a_k, so (1) is Σ_k a_k² Σ_{i∈k} m_i², which is what the
//! field's per-layer noise (`LayeredField::excess_sd`) computes when its per-layer counts are
//! these effective counts.

/// The counting σ of a reading that counted its grains' contributions `sd` = √Σ c_i² (eq. 1),
/// with one more grain of the mean mass at the instrument's centre, of contribution
/// `one_grain`: σ = √(Σ c_i² + c₁²).
///
/// Eq. 1 estimates λ E[X²] by the grains present, which says σ = 0 for a reading that counted
/// none, whatever the number λ of grains it expected: a late pipette draw of a run with few
/// grains reads 0 ± 0 although a grain or two were as likely as none. Under a flat prior on λ
/// the Poisson posterior of a count n has mean n + 1 (Bayes–Laplace; the rule of succession),
/// so one grain of the mean mass is added to the grains counted: negligible for a reading of
/// many grains, the size of one grain for a reading of none.
pub fn with_one_more_grain(sd: f64, one_grain: f64) -> f64 {
    sd.hypot(one_grain)
}

/// σ = √Σ c_i² (eq. 1), the counting standard deviation of a reading whose grains contribute
/// `contributions` c_i = a_i m_i (in the reading's unit): the compound-Poisson standard
/// deviation of the sum Σ c_i. 0 for no grain.
pub fn compound_poisson_sd(contributions: impl IntoIterator<Item = f64>) -> f64 {
    contributions.into_iter().map(|c| c * c).sum::<f64>().sqrt()
}

/// The effective number of grains of a group whose masses sum to `sum` and whose squared masses
/// sum to `sum_sq`: n_eff = sum² / sum_sq, the count for which the Poisson relative noise
/// 1/√n_eff is the compound-Poisson one (√sum_sq / sum). 0 for an empty group.
pub fn effective_count(sum: f64, sum_sq: f64) -> f64 {
    if sum_sq > 0.0 {
        sum * sum / sum_sq
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Eq. 1 against a Monte Carlo of the reading: three size classes of representative grains
    /// (masses 1, 8 and 27 in some unit), each grain independently in the instrument's volume
    /// with probability p = 0.02 (the volume's share of the column), the reading the sum of
    /// a · m over the grains in it. The variance of the simulated readings is compared with
    /// the mean over the runs of Σ (a m)² of the grains counted; their ratio is 1 within the
    /// Monte Carlo's error (≈ 1.5 % for 20 000 draws at this skew: the bound is 5 %).
    #[test]
    fn matches_a_monte_carlo_of_the_weighted_sum() {
        let classes = [(1.0, 3000usize), (8.0, 400), (27.0, 60)];
        let (a, p) = (0.37, 0.02);
        let mut rng = ChaCha8Rng::seed_from_u64(26);
        let draws = 20_000;
        let (mut s, mut s2, mut formula) = (0.0, 0.0, 0.0);
        for _ in 0..draws {
            let mut inside = Vec::new();
            for &(m, n) in &classes {
                for _ in 0..n {
                    if rng.random::<f64>() < p {
                        inside.push(a * m);
                    }
                }
            }
            let r: f64 = inside.iter().sum();
            s += r;
            s2 += r * r;
            formula += compound_poisson_sd(inside.iter().copied()).powi(2);
        }
        let n = draws as f64;
        let var_mc = s2 / n - (s / n).powi(2);
        let var_eq1 = formula / n;
        // The binomial variance is the Poisson one times (1 − p).
        let ratio = var_mc / (var_eq1 * (1.0 - p));
        assert!((ratio - 1.0).abs() < 0.05, "Monte Carlo / eq. 1 = {ratio}");
        // The Poisson σ = R/√n ignores the unequal masses and is far too small here.
        let mean = s / n;
        let naive = mean * mean / (p * classes.iter().map(|c| c.1 as f64).sum::<f64>());
        assert!(var_mc > 3.0 * naive, "{var_mc} vs naive {naive}");
    }

    #[test]
    fn one_more_grain() {
        assert_eq!(with_one_more_grain(0.0, 0.2), 0.2);
        assert_eq!(with_one_more_grain(3.0, 4.0), 5.0);
    }

    #[test]
    fn effective_count_of_equal_and_unequal_grains() {
        assert_eq!(effective_count(4.0, 4.0), 4.0);
        assert!((effective_count(1.0 + 8.0, 1.0 + 64.0) - 81.0 / 65.0).abs() < 1e-15);
        assert_eq!(effective_count(0.0, 0.0), 0.0);
        assert_eq!(compound_poisson_sd([3.0, 4.0]), 5.0);
        assert_eq!(compound_poisson_sd(std::iter::empty()), 0.0);
    }
}
