//! The pipette (seed 000 §4.5.3): a volume V (35 ml) drawn at depth y_pt on the axis, dried and
//! weighed; c_o = m_pt / V, then φ_o and w_o as for the hydrometer with y_pt.
//!
//! In the 2D projection (a fraction f of the cylinder, thickness h_z) the draw is a disc of the
//! plane centred on the axis at depth y_pt, of area A with A h_z = f V (for 35 ml, f = 1/180,
//! h_z = 2.771e-4 m: A = 7.02 cm², radius 14.9 mm). Its dry mass is that of the grains whose
//! centre lies in the disc; in real units the pipette's mass is that over f.

use super::{Analysis, LayeredField, Point};
use std::f64::consts::PI;

/// The pipette and where it draws.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pipette {
    /// Volume drawn in the real cylinder, m³ (35e-6).
    pub volume_m3: f64,
    /// Depth of the tip below the free surface y_pt, m (0.3 H).
    pub depth_m: f64,
    /// Fraction f of the cylinder simulated (1/180).
    pub wedge_fraction: f64,
    /// Thickness h_z of the 2D projection, m.
    pub thickness_m: f64,
    /// Horizontal position of the axis in the 2D plane (B/2), m.
    pub axis_x_m: f64,
}

/// A grain as the pipette sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GrainSample {
    /// Horizontal position, m.
    pub x_m: f64,
    /// Depth of the centre below the free surface, m.
    pub depth_m: f64,
    /// Dry mass it stands for (real grains of the simulated wedges), kg.
    pub mass_kg: f64,
}

/// What one draw weighs.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PipetteReading {
    /// Dry mass drawn in the real cylinder (the simulated mass over f), kg.
    pub mass_kg: f64,
    /// Mass concentration c_o = m_pt / V, kg/m³.
    pub concentration_kg_m3: f64,
    /// Representative grains in the disc.
    pub grains: usize,
    /// Standard deviation of c_o from the grain masses (√Σm²/Σm relative), kg/m³.
    pub concentration_sd_kg_m3: f64,
}

impl Pipette {
    /// Radius of the sampling disc in the 2D plane, m: π r² h_z = f V.
    pub fn radius_m(&self) -> f64 {
        (self.wedge_fraction * self.volume_m3 / (self.thickness_m * PI)).sqrt()
    }

    /// Draws from grains: the dry mass of those whose centre is in the disc.
    pub fn read(&self, grains: impl IntoIterator<Item = GrainSample>) -> PipetteReading {
        let r = self.radius_m();
        let (mut m, mut m2, mut n) = (0.0, 0.0, 0usize);
        for g in grains {
            let (dx, dy) = (g.x_m - self.axis_x_m, g.depth_m - self.depth_m);
            if dx * dx + dy * dy <= r * r {
                m += g.mass_kg;
                m2 += g.mass_kg * g.mass_kg;
                n += 1;
            }
        }
        let v = self.wedge_fraction * self.volume_m3;
        PipetteReading {
            mass_kg: m / self.wedge_fraction,
            concentration_kg_m3: m / v,
            grains: n,
            concentration_sd_kg_m3: m2.sqrt() / v,
        }
    }

    /// Concentration of a horizontally uniform suspension of density `field` averaged over the
    /// disc (weight: its chord 2√(r² − u²)), kg/m³, with c = ρ_p (ρ_s − ρ_f)/(ρ_p − ρ_f).
    pub fn field_concentration(&self, an: &Analysis, field: &LayeredField) -> f64 {
        let r = self.radius_m();
        let chord = |y: f64| {
            let u = (y - self.depth_m).clamp(-r, r);
            u * (r * r - u * u).max(0.0).sqrt() + r * r * (u / r).asin()
        };
        let (a, b) = (self.depth_m - r, self.depth_m + r);
        // Mean over the disc: divided by the integral of the same weight (π r² up to the
        // rounding of the chord at the disc's edges).
        let mean = field.integrate(a, b, chord) / (chord(b) - chord(a));
        an.concentration_kg_m3(mean)
    }

    /// The (φ_o, w_o) pair of a reading at time `t` (eqs. 16–17 with y_pt).
    pub fn point(&self, an: &Analysis, r: &PipetteReading, time_s: f64) -> Point {
        Point {
            time_s,
            depth_m: self.depth_m,
            diameter_m: an.limiting_diameter_m(self.depth_m, time_s),
            percent_finer: an.percent_finer_from_concentration(r.concentration_kg_m3),
            sd_percent: an.percent_finer_from_concentration(r.concentration_sd_kg_m3),
        }
    }
}
