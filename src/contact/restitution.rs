//! The restitution law e(v) and its calibration on drop tests (f-EDEM App. II: a ball dropped
//! from rest from H_f rebounds to H_r = e² H_f, eq. A4, without air).

/// Largest restitution a law may return. Rapier treats a contact with e ≥ 1 as bouncy even when
/// it persists (it could never come to rest), so the law stays just below 1.
pub const MAX_RESTITUTION: f64 = 0.999;

/// Coefficient of restitution as a function of the impact (approach) speed v, m/s:
///
/// e(v) = e_ref · (v / v_ref)^(−k), clamped to [0, [`MAX_RESTITUTION`]].
///
/// k = 0 (the default) is the usual constant coefficient. A positive k lets e fall slowly with
/// the impact speed, as plastic work in the contact grows with it (Johnson, *Contact Mechanics*,
/// 1985, §11.5: e ∝ v^(−1/4) once the impact is fully plastic; Kuwabara & Kono 1987 for
/// viscoelastic losses). The power law with a small k is an empirical form of both, calibrated on
/// drop tests (see [`RestitutionLaw::minimax_fit`]); for f-EDEM's Appendix II data it gives
/// k ≈ 0.049 (a 5 % drop in e from 1.4 to 2.8 m/s).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RestitutionLaw {
    /// e_ref: the restitution at the reference speed, 0 ≤ e_ref ≤ 1.
    pub coefficient: f64,
    /// k ≥ 0, dimensionless; 0 = constant restitution.
    pub exponent: f64,
    /// v_ref > 0, m/s (default 1 m/s).
    pub reference_speed_m_s: f64,
}

impl RestitutionLaw {
    /// A constant coefficient e (k = 0, v_ref = 1 m/s).
    pub fn constant(coefficient: f64) -> Self {
        Self {
            coefficient,
            exponent: 0.0,
            reference_speed_m_s: 1.0,
        }
    }

    /// Whether e depends on the impact speed (k ≠ 0).
    pub fn is_speed_dependent(&self) -> bool {
        self.exponent != 0.0
    }

    /// e(v) for an approach speed `speed_m_s` (its magnitude is used); at v = 0 a speed-dependent
    /// law returns its cap, [`MAX_RESTITUTION`] (a contact that persists is not bouncy in Rapier
    /// unless e ≥ 1, so this only matters for new contacts at vanishing speed).
    pub fn at(&self, speed_m_s: f64) -> f64 {
        if !self.is_speed_dependent() {
            return self.coefficient;
        }
        let v = speed_m_s.abs() / self.reference_speed_m_s;
        let e = if v > 0.0 {
            self.coefficient * v.powf(-self.exponent)
        } else {
            MAX_RESTITUTION
        };
        if e.is_nan() {
            0.0
        } else {
            e.clamp(0.0, MAX_RESTITUTION)
        }
    }

    /// The law (with reference speed `reference_speed_m_s`) that minimises the largest relative
    /// rebound-height error against drop tests: balls dropped from rest from `drop_m` reach the
    /// plate at v = √(2 g H_f) and rebound to e(v)² H_f (no air), measured `rebound_m`.
    ///
    /// In ln e the problem is a minimax line fit: for a given k the best ln e_ref is the midrange
    /// of ln √(H_r/H_f) + k ln(v/v_ref), with half-range δ(k); δ is convex in k, so k is found by
    /// golden-section search on [−1, 1]. Returns the law and the largest relative height error,
    /// e^(2δ) − 1. `None` without at least two heights or with a non-positive value.
    pub fn minimax_fit(
        drop_m: &[f64],
        rebound_m: &[f64],
        gravity_m_s2: f64,
        reference_speed_m_s: f64,
    ) -> Option<(Self, f64)> {
        if drop_m.len() < 2
            || drop_m.len() != rebound_m.len()
            || drop_m
                .iter()
                .chain(rebound_m)
                .chain([&gravity_m_s2, &reference_speed_m_s])
                .any(|h| !h.is_finite() || *h <= 0.0)
        {
            return None;
        }
        let points: Vec<(f64, f64)> = drop_m
            .iter()
            .zip(rebound_m)
            .map(|(h, r)| {
                let v = (2.0 * gravity_m_s2 * h).sqrt();
                ((v / reference_speed_m_s).ln(), 0.5 * (r / h).ln())
            })
            .collect();
        let range = |k: f64| {
            let (lo, hi) = points
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |acc, (x, y)| {
                    let r = y + k * x;
                    (acc.0.min(r), acc.1.max(r))
                });
            (0.5 * (hi - lo), 0.5 * (hi + lo))
        };
        let (mut a, mut b) = (-1.0f64, 1.0f64);
        let phi = 0.5 * (5f64.sqrt() - 1.0);
        for _ in 0..200 {
            let c = b - phi * (b - a);
            let d = a + phi * (b - a);
            if range(c).0 <= range(d).0 {
                b = d;
            } else {
                a = c;
            }
        }
        let k = 0.5 * (a + b);
        let (half, mid) = range(k);
        Some((
            Self {
                coefficient: mid.exp(),
                exponent: k,
                reference_speed_m_s,
            },
            (2.0 * half).exp() - 1.0,
        ))
    }
}

/// What constant restitution coefficients make of measured rebounds `measured_m` from heights
/// `drop_m` (f-EDEM eq. A4: e = √(H_r/H_f)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConstantFit {
    /// Mean of the per-height √(H_r/H_f) (f-EDEM's "average", 0.612).
    pub e_mean: f64,
    /// Least-squares e on the heights: e² = Σ H_r H_f / Σ H_f².
    pub e_least_squares: f64,
    /// The e minimising the largest relative height error: e² = 2 r_min r_max/(r_min + r_max),
    /// r = H_r/H_f.
    pub e_minimax: f64,
    /// That smallest achievable largest relative error, (r_max − r_min)/(r_max + r_min): no
    /// constant e matches every height better.
    pub minimax_rel_error: f64,
}

/// Fits constant restitution coefficients to measured rebounds (see [`ConstantFit`]). `None`
/// without data or with a non-positive height.
pub fn constant_fit(drop_m: &[f64], measured_m: &[f64]) -> Option<ConstantFit> {
    if drop_m.is_empty()
        || drop_m.len() != measured_m.len()
        || drop_m
            .iter()
            .chain(measured_m)
            .any(|h| !h.is_finite() || *h <= 0.0)
    {
        return None;
    }
    let ratios: Vec<f64> = drop_m.iter().zip(measured_m).map(|(h, r)| r / h).collect();
    let e_mean = ratios.iter().map(|r| r.sqrt()).sum::<f64>() / ratios.len() as f64;
    let sxy: f64 = drop_m.iter().zip(measured_m).map(|(h, r)| h * r).sum();
    let sxx: f64 = drop_m.iter().map(|h| h * h).sum();
    let r_min = ratios.iter().copied().fold(f64::INFINITY, f64::min);
    let r_max = ratios.iter().copied().fold(0.0, f64::max);
    Some(ConstantFit {
        e_mean,
        e_least_squares: (sxy / sxx).sqrt(),
        e_minimax: (2.0 * r_min * r_max / (r_min + r_max)).sqrt(),
        minimax_rel_error: (r_max - r_min) / (r_max + r_min),
    })
}

/// One restitution model calibrated on drop tests: a row of the restitution-drop scene's `fit.csv`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LawFit {
    /// Model name: `constant_mean` (f-EDEM's e, the mean of √(H_r/H_f)),
    /// `constant_least_squares`, `constant_minimax` (see [`ConstantFit`]) or `power_minimax`
    /// ([`RestitutionLaw::minimax_fit`]).
    pub model: &'static str,
    /// The calibrated law.
    pub law: RestitutionLaw,
    /// Largest |e(v)² H_f / H_r − 1| over the heights (no air), v = √(2 g H_f).
    pub max_rel_error: f64,
    /// Largest error at a height left out of the calibration, the model refitted on the others
    /// (leave-one-out cross-validation: what the model predicts, not what it fits). `None` for
    /// models that are not refitted (the mean and least squares) or with fewer than 3 heights.
    pub leave_one_out_max_rel_error: Option<f64>,
}

/// A calibration of a restitution law on (drop heights, measured rebounds).
type Calibration<'a> = &'a dyn Fn(&[f64], &[f64]) -> Option<RestitutionLaw>;

/// Largest relative rebound error of `law` against drop tests (no air).
fn law_max_error(law: &RestitutionLaw, drop_m: &[f64], measured_m: &[f64], g: f64) -> f64 {
    drop_m
        .iter()
        .zip(measured_m)
        .map(|(h, r)| (law.at((2.0 * g * h).sqrt()).powi(2) * h / r - 1.0).abs())
        .fold(0.0, f64::max)
}

/// The four restitution models of [`LawFit`] calibrated on drop heights `drop_m` and measured
/// rebounds `measured_m` under gravity `g` (m/s²), the power law about `reference_speed_m_s`.
/// Empty if the data cannot be fitted (see [`constant_fit`]).
pub fn restitution_fits(
    drop_m: &[f64],
    measured_m: &[f64],
    g: f64,
    reference_speed_m_s: f64,
) -> Vec<LawFit> {
    let Some(c) = constant_fit(drop_m, measured_m) else {
        return Vec::new();
    };
    let minimax =
        |d: &[f64], m: &[f64]| constant_fit(d, m).map(|f| RestitutionLaw::constant(f.e_minimax));
    let power = |d: &[f64], m: &[f64]| {
        RestitutionLaw::minimax_fit(d, m, g, reference_speed_m_s).map(|(law, _)| law)
    };
    let leave_one_out = |fit: Calibration| {
        if drop_m.len() < 3 {
            return None;
        }
        let mut worst: f64 = 0.0;
        for i in 0..drop_m.len() {
            let keep = |x: &[f64]| -> Vec<f64> {
                x.iter()
                    .enumerate()
                    .filter(|(j, _)| *j != i)
                    .map(|(_, v)| *v)
                    .collect()
            };
            let law = fit(&keep(drop_m), &keep(measured_m))?;
            worst = worst.max(law_max_error(&law, &drop_m[i..=i], &measured_m[i..=i], g));
        }
        Some(worst)
    };
    let mut fits = Vec::new();
    let mut push = |model, law: RestitutionLaw, loo| {
        fits.push(LawFit {
            model,
            law,
            max_rel_error: law_max_error(&law, drop_m, measured_m, g),
            leave_one_out_max_rel_error: loo,
        })
    };
    push("constant_mean", RestitutionLaw::constant(c.e_mean), None);
    push(
        "constant_least_squares",
        RestitutionLaw::constant(c.e_least_squares),
        None,
    );
    push(
        "constant_minimax",
        RestitutionLaw::constant(c.e_minimax),
        leave_one_out(&minimax),
    );
    if let Some(law) = power(drop_m, measured_m) {
        push("power_minimax", law, leave_one_out(&power));
    }
    fits
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constant_law_ignores_speed() {
        let law = RestitutionLaw::constant(0.612);
        for v in [0.0, 1e-6, 1.0, 10.0] {
            assert_eq!(law.at(v), 0.612);
        }
        assert_eq!(RestitutionLaw::constant(1.0).at(3.0), 1.0);
    }

    #[test]
    fn power_law_values_and_cap() {
        let law = RestitutionLaw {
            coefficient: 0.6,
            exponent: 0.25,
            reference_speed_m_s: 2.0,
        };
        assert!((law.at(2.0) - 0.6).abs() < 1e-15);
        assert!((law.at(-32.0) - 0.6 * 16f64.powf(-0.25)).abs() < 1e-15);
        assert_eq!(law.at(0.0), MAX_RESTITUTION);
        assert_eq!(law.at(1e-9), MAX_RESTITUTION);
    }

    #[test]
    fn minimax_fit_recovers_an_exact_power_law() {
        // Rebounds generated by e = 0.63 (v / 1 m/s)^(-0.05): the fit returns it, error ~0.
        let law = RestitutionLaw {
            coefficient: 0.63,
            exponent: 0.05,
            reference_speed_m_s: 1.0,
        };
        let drops: [f64; 4] = [0.1, 0.2, 0.3, 0.4];
        let rebounds: Vec<f64> = drops
            .iter()
            .map(|h| law.at((2.0 * 9.81 * h).sqrt()).powi(2) * h)
            .collect();
        let (fit, err) = RestitutionLaw::minimax_fit(&drops, &rebounds, 9.81, 1.0).unwrap();
        assert!((fit.exponent - 0.05).abs() < 1e-9, "{fit:?}");
        assert!((fit.coefficient - 0.63).abs() < 1e-9, "{fit:?}");
        assert!(err < 1e-9, "{err}");
        assert!(RestitutionLaw::minimax_fit(&[0.1], &[0.04], 9.81, 1.0).is_none());
        assert!(RestitutionLaw::minimax_fit(&[0.1, -0.2], &[0.04, 0.05], 9.81, 1.0).is_none());
    }
}
