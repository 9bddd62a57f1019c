//! Contact mechanics: the quantities that set DEM time steps, and the restitution law.

use std::f64::consts::PI;

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

/// Rayleigh time of a sphere, s: T_R = π r / (0.8766 + 0.163 ν) · √(ρ_p / G), G = E / (2(1 + ν))
/// (f-EDEM eq. 22; Li et al. 2005). The usual DEM rule takes 10–20 % of it as the time step.
pub fn rayleigh_time_s(
    diameter_m: f64,
    density_kg_m3: f64,
    youngs_modulus_pa: f64,
    poisson_ratio: f64,
) -> f64 {
    let g = youngs_modulus_pa / (2.0 * (1.0 + poisson_ratio));
    PI * 0.5 * diameter_m / (0.8766 + 0.163 * poisson_ratio) * (density_kg_m3 / g).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fedem_table1_rayleigh_time() {
        // f-EDEM §3: d = 0.1 mm, ρ = 2700, E = 30 GPa, ν = 0.25 → T_R = 8.12e-8 s.
        let tr = rayleigh_time_s(1e-4, 2700.0, 30e9, 0.25);
        assert!((tr - 8.12e-8).abs() < 0.005e-8, "{tr}");
    }

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
