//! Error statistics of simulated against measured values.

/// Error statistics of a group of relative errors (simulated − measured)/measured.
#[derive(Clone, Debug, PartialEq)]
pub struct ErrorStats {
    /// Group label (`1`…`6`, or `all`).
    pub group: String,
    /// Number of values.
    pub n: usize,
    /// Mean of |error|.
    pub mean_abs: f64,
    /// Median of |error|.
    pub median_abs: f64,
    /// Max of |error|.
    pub max_abs: f64,
    /// Mean signed error (bias).
    pub bias: f64,
    /// Fraction of |error| ≤ 0.10.
    pub within_10pct: f64,
    /// Fraction of |error| ≤ 0.25.
    pub within_25pct: f64,
}

impl ErrorStats {
    /// Statistics of `errors` (non-finite values are skipped).
    pub fn of(group: impl Into<String>, errors: &[f64]) -> Self {
        let e: Vec<f64> = errors.iter().copied().filter(|x| x.is_finite()).collect();
        let n = e.len();
        let mut abs: Vec<f64> = e.iter().map(|x| x.abs()).collect();
        abs.sort_by(|a, b| a.total_cmp(b));
        let nf = n.max(1) as f64;
        let median_abs = if n == 0 {
            f64::NAN
        } else if n % 2 == 1 {
            abs[n / 2]
        } else {
            0.5 * (abs[n / 2 - 1] + abs[n / 2])
        };
        Self {
            group: group.into(),
            n,
            mean_abs: abs.iter().sum::<f64>() / nf,
            median_abs,
            max_abs: abs.last().copied().unwrap_or(f64::NAN),
            bias: e.iter().sum::<f64>() / nf,
            within_10pct: abs.iter().filter(|x| **x <= 0.10).count() as f64 / nf,
            within_25pct: abs.iter().filter(|x| **x <= 0.25).count() as f64 / nf,
        }
    }

    /// CSV header of [`Self::row`].
    pub const HEADER: [&'static str; 8] = [
        "group",
        "n",
        "mean_abs_rel_error",
        "median_abs_rel_error",
        "max_abs_rel_error",
        "bias_rel_error",
        "fraction_within_10pct",
        "fraction_within_25pct",
    ];

    /// CSV row.
    pub fn row(&self) -> Vec<String> {
        vec![
            self.group.clone(),
            self.n.to_string(),
            format!("{:.6}", self.mean_abs),
            format!("{:.6}", self.median_abs),
            format!("{:.6}", self.max_abs),
            format!("{:.6}", self.bias),
            format!("{:.4}", self.within_10pct),
            format!("{:.4}", self.within_25pct),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stats_of_a_small_sample() {
        let s = ErrorStats::of("x", &[0.05, -0.2, 0.3, -0.01]);
        assert_eq!(s.n, 4);
        assert!((s.mean_abs - 0.14).abs() < 1e-12);
        assert!((s.median_abs - 0.125).abs() < 1e-12);
        assert_eq!(s.max_abs, 0.3);
        assert!((s.bias - 0.035).abs() < 1e-12);
        assert_eq!(s.within_10pct, 0.5);
        assert_eq!(s.within_25pct, 0.75);
    }
}
