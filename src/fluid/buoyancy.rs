//! Gravity and buoyancy on a sphere (f-EDEM eqs. 3 and 4).

use std::f64::consts::PI;

/// Volume of a sphere of diameter `d_m`, m³: V = π d³ / 6.
pub fn sphere_volume_m3(d_m: f64) -> f64 {
    PI * d_m.powi(3) / 6.0
}

/// Projected (cross-section) area of a sphere, m²: A = π d² / 4 (f-EDEM, below eq. 5).
pub fn sphere_area_m2(d_m: f64) -> f64 {
    PI * d_m * d_m / 4.0
}

/// Mass of a sphere, kg: m = ρ_p π d³ / 6.
pub fn sphere_mass_kg(d_m: f64, density_kg_m3: f64) -> f64 {
    density_kg_m3 * sphere_volume_m3(d_m)
}

/// Weight of a sphere, N: F_g = π ρ_p d³ g / 6 (f-EDEM eq. 3).
pub fn weight_n(d_m: f64, density_kg_m3: f64, g_m_s2: f64) -> f64 {
    sphere_mass_kg(d_m, density_kg_m3) * g_m_s2
}

/// Buoyancy on a fully submerged sphere, N: F_b = π ρ_f d³ g / 6 (f-EDEM eq. 4, Archimedes).
pub fn buoyancy_n(d_m: f64, fluid_density_kg_m3: f64, g_m_s2: f64) -> f64 {
    weight_n(d_m, fluid_density_kg_m3, g_m_s2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_sphere_volume_and_area() {
        assert!((sphere_volume_m3(2.0) - 4.0 / 3.0 * PI).abs() < 1e-14);
        assert!((sphere_area_m2(2.0) - PI).abs() < 1e-14);
    }

    #[test]
    fn buoyancy_equals_weight_of_displaced_fluid() {
        // 1 cm sphere in water: 0.5236 cm³ of water weighs 5.136e-3 N.
        let fb = buoyancy_n(0.01, 1000.0, 9.81);
        assert!((fb - 1000.0 * PI * 1e-6 / 6.0 * 9.81).abs() < 1e-15);
        assert!((fb / weight_n(0.01, 2700.0, 9.81) - 1000.0 / 2700.0).abs() < 1e-14);
    }
}
