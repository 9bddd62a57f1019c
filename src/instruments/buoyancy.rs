//! The buoyancy sphere (seed 000 §4.5.2): a sphere hung at a fixed depth y_bt from a
//! dynamometer, which reads its apparent mass m_sp = m_a − ρ_s V_sp with ρ_s the suspension
//! density around it. Here ρ_s is the mean over the sphere's volume of the layered density
//! (exact per layer). The percent finer is eq. 22,
//! w_o = 100 (ρ_f / c_0) (m_sp,w − m_sp)/(m_sp,w − m_sp,a) / (ρ_f/ρ_p − 1), with m_sp,w the
//! apparent mass in clear fluid and m_sp,a the mass in air (the same as eqs. 17–18 with the
//! mean density).
//!
//! The seed's default sphere is Teflon, Ø 25 mm, 20 g, at y_bt = 0.3 H. Its apparent mass is
//! 20 − 8.18 = 11.82 g in water and 11.61 g in the initial suspension of seed 000
//! (ρ_s = 1024.9 kg/m³): the seed quotes 1.52 g and 1.62 g, which do not follow from that sphere
//! (their 0.10 g difference for Δρ ≈ 15–25 kg/m³ means V_sp ≈ 4–7 cm³, not 8.18 cm³).

use super::{Analysis, LayeredField, Point};
use std::f64::consts::PI;

/// The sphere and where it hangs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BuoyancySphere {
    /// Diameter, m (0.025).
    pub diameter_m: f64,
    /// Mass in air m_sp,a, kg (0.020).
    pub mass_kg: f64,
    /// Depth of its centre below the free surface y_bt, m (0.3 H).
    pub depth_m: f64,
}

/// One reading of the dynamometer.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct BuoyancyReading {
    /// Apparent mass m_sp, kg.
    pub apparent_mass_kg: f64,
    /// Apparent mass in clear fluid m_sp,w, kg.
    pub clear_apparent_mass_kg: f64,
    /// Mean suspension density over the sphere, kg/m³.
    pub density_kg_m3: f64,
    /// Standard deviation of that density from the grain counts, kg/m³.
    pub density_sd_kg_m3: f64,
}

impl BuoyancySphere {
    /// Volume V_sp, m³.
    pub fn volume_m3(&self) -> f64 {
        PI * self.diameter_m.powi(3) / 6.0
    }

    /// ∫ of the horizontal section of the sphere from its centre to a vertical offset u (clamped
    /// to the sphere): π (R² u − u³/3).
    fn section_integral(&self, y: f64) -> f64 {
        let r = 0.5 * self.diameter_m;
        let u = (y - self.depth_m).clamp(-r, r);
        PI * (r * r * u - u * u * u / 3.0)
    }

    /// Weighs the sphere in `field`.
    pub fn read(&self, field: &LayeredField) -> BuoyancyReading {
        let r = 0.5 * self.diameter_m;
        let (a, b) = (self.depth_m - r, self.depth_m + r);
        let displaced = field.integrate(a, b, |y| self.section_integral(y));
        let v = self.volume_m3();
        BuoyancyReading {
            apparent_mass_kg: self.mass_kg - displaced,
            clear_apparent_mass_kg: self.mass_kg - field.fluid_density_kg_m3 * v,
            density_kg_m3: displaced / v,
            density_sd_kg_m3: field.excess_sd(a, b, |y| self.section_integral(y)) / v,
        }
    }

    /// The (φ_o, w_o) pair of a reading at time `t`: eq. 16 with y_bt, eq. 22.
    pub fn point(&self, an: &Analysis, r: &BuoyancyReading, time_s: f64) -> Point {
        let rf = an.fluid_density_kg_m3;
        let w = 100.0 * rf / an.c0_kg_m3 * (r.clear_apparent_mass_kg - r.apparent_mass_kg)
            / (r.clear_apparent_mass_kg - self.mass_kg)
            / (rf / an.grain_density_kg_m3 - 1.0);
        Point {
            time_s,
            depth_m: self.depth_m,
            diameter_m: an.limiting_diameter_m(self.depth_m, time_s),
            percent_finer: w,
            sd_percent: an.percent_finer_from_density(rf + r.density_sd_kg_m3),
        }
    }
}
