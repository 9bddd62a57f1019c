//! A drop compared with the law and the measurement, and the count of heights within tolerance.

use super::DropOutcome;
use crate::contact::RestitutionLaw;
use crate::io::fmt::{g, pct, short};

/// One simulated drop against the ideal rebound of its law and the measured rebound.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Comparison {
    /// e(v) of the law at the ideal impact speed v = √(2 g H) (no air).
    pub law_restitution: f64,
    /// Ideal rebound e(v)² H (no air, f-EDEM eq. A4), m.
    pub ideal_rebound_m: f64,
    /// Simulated rebound / ideal rebound − 1 (None when the ideal rebound is 0).
    pub rel_error_vs_ideal: Option<f64>,
    /// Measured rebound, m (None when not given).
    pub measured_rebound_m: Option<f64>,
    /// Simulated rebound / measured rebound − 1.
    pub rel_error: Option<f64>,
}

impl Comparison {
    /// Compares the drop `o` with `law` under gravity `g_m_s2` and with the rebound `measured_m`.
    pub fn of(o: &DropOutcome, law: &RestitutionLaw, g_m_s2: f64, measured_m: Option<f64>) -> Self {
        let h = o.drop_height_m;
        let e = law.at((2.0 * g_m_s2 * h).sqrt());
        let ideal = e * e * h;
        Self {
            law_restitution: e,
            ideal_rebound_m: ideal,
            rel_error_vs_ideal: (ideal > 0.0).then(|| o.rebound_height_m / ideal - 1.0),
            measured_rebound_m: measured_m,
            rel_error: measured_m.map(|m| o.rebound_height_m / m - 1.0),
        }
    }

    /// The console line of the drop `o` (heights in mm, errors in %).
    pub fn line(&self, o: &DropOutcome) -> String {
        format!(
            "H = {} mm: rebound {} mm{} (e²H = {} mm{}), contact e = {} (law {})",
            short(o.drop_height_m * 1e3),
            g(o.rebound_height_m * 1e3),
            match (self.measured_rebound_m, self.rel_error) {
                (Some(m), Some(err)) =>
                    format!(", measured {} mm, {}", short(m * 1e3), pct(err, 3)),
                _ => String::new(),
            },
            g(self.ideal_rebound_m * 1e3),
            self.rel_error_vs_ideal
                .map(|x| format!(", {}", pct(x, 3)))
                .unwrap_or_default(),
            g(o.restitution_effective),
            g(self.law_restitution),
        )
    }
}

/// How the simulated drops meet the measurements.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Tally {
    /// Heights whose |relative error| is at most the tolerance.
    pub within: usize,
    /// Largest |relative error| (0 without measurements).
    pub worst: f64,
}

impl Tally {
    /// Tallies the measured comparisons of `rows` against `tolerance` (relative).
    pub fn of(rows: &[Comparison], tolerance: f64) -> Self {
        rows.iter()
            .filter_map(|c| c.rel_error)
            .fold(Self::default(), |t, err| Self {
                within: t.within + usize::from(err.abs() <= tolerance),
                worst: t.worst.max(err.abs()),
            })
    }
}

/// Number of drop heights `drop_m` at which the ideal rebound of `law` (no air, gravity
/// `g_m_s2`) is within `tolerance` (relative) of the measured rebound `measured_m`.
pub fn heights_within(
    law: &RestitutionLaw,
    drop_m: &[f64],
    measured_m: &[f64],
    g_m_s2: f64,
    tolerance: f64,
) -> usize {
    drop_m
        .iter()
        .zip(measured_m)
        .filter(|(h, r)| {
            (law.at((2.0 * g_m_s2 * **h).sqrt()).powi(2) * **h / **r - 1.0).abs() <= tolerance
        })
        .count()
}
