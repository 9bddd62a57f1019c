//! The ASTM E100 152H soil hydrometer (ASTM D422) floating in a layered suspension (seed 000
//! §4.5.1, eqs. 16–21).
//!
//! # Shape
//!
//! An axisymmetric body, from its tip up: a bulb of length L₂ made of a cylinder of radius R_b
//! between two truncated cones of length `taper` that narrow to the stem radius r_s (a flat
//! bottom of radius r_s at the tip), then a cylindrical stem of radius r_s. The bulb is
//! symmetric, so its centre of volume is at mid-length, as ASTM D422 assumes (L₂/2).
//!
//! The figures of the 152H fix everything but the taper: bulb volume V_B = 67 cm³, L₂ = 14.0 cm,
//! scale 0–60 g/L (grams of soil of G_s = 2.65 per litre), and the ASTM D422 Table 2 effective
//! depth L = 16.29 − 0.164 R cm with L = L₁ + ½ (L₂ − V_B/A), A = 27.8 cm² the cylinder's
//! section. So the stem distance from the top of the bulb to the mark R is L₁(0) = 10.495 cm
//! and L₁(60) = 0.655 cm, and the stem section follows from the floating condition in the two
//! calibration liquids: A_s = V_B (1 − 1/q₆₀)/((L₁(0) − L₁(60)) − L₁(0)(1 − 1/q₆₀)) with
//! q_R = ρ_s/ρ_f = 1 + R (1 − 1/G_s)/1000, i.e. A_s = 0.2550 cm², r_s = 2.849 mm (Ø 5.70 mm).
//! With a 2.5 cm taper at each end, V_B = 67 cm³ gives R_b = 13.87 mm (Ø 27.7 mm). The stem is
//! 14 cm long (seed Fig. 7). The mass is that of the fluid displaced with the surface at the
//! mark 0 (the hydrometer reads R = 0 in the clear fluid of the scenario: the ASTM zero
//! correction).
//!
//! The marks are where the hydrometer floats in a liquid of relative density q_R: L₁(R) =
//! (V₀/q_R − V_B)/A_s, V₀ = V_B + A_s L₁(0). They are exact at R = 0 and 60 and within 0.09 cm of
//! the linear Table 2 in between (a cylindrical stem gives a 1/ρ scale; Table 2 rounds to
//! 0.1 cm).
//!
//! # Floating depth (eqs. 20–21)
//!
//! The resultant of the hydrostatic pressures on the body equals, by the divergence theorem,
//! g ∫ ρ_s(y) A(y) dy over its submerged part, for any layered density; eq. 21 sums the same
//! pressures over the horizontal projections of the surface between layer boundaries
//! ([`Hydrometer::pressure_force_eq21_n`]). The tip depth is where that displaced mass equals the
//! hydrometer's mass, found by bisection with exact per-layer integrals (so no interpolation
//! within a layer is needed). The reading R is read on the stem at the free surface; the
//! suspension density is eq. 19, ρ_s = ρ_f m/(m − A_s (y_ow − y_o) ρ_f), which is the mean
//! density over the submerged volume (bulb and stem), not the density at the bulb centre.

use super::{Analysis, LayeredField, Point};
use crate::numerics::{bisect, Bisection, Stop};
use std::f64::consts::PI;

/// Figures of a soil hydrometer (defaults: ASTM E100 152H and ASTM D422 Table 2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HydrometerSpec {
    /// Bulb volume V_B, m³ (67 cm³).
    pub bulb_volume_m3: f64,
    /// Bulb length L₂, m (14.0 cm).
    pub bulb_length_m: f64,
    /// Length of each conical end of the bulb, m (2.5 cm).
    pub taper_m: f64,
    /// Stem length above the bulb, m (14 cm).
    pub stem_length_m: f64,
    /// Effective depth at R = 0 (Table 2), m (16.29 cm).
    pub effective_depth_zero_m: f64,
    /// Decrease of the effective depth per g/L of reading, m (0.164 cm).
    pub effective_depth_slope_m: f64,
    /// Full scale reading, g/L (60).
    pub full_scale: f64,
    /// Section A of the cylinder used in ASTM D422's L = L₁ + ½(L₂ − V_B/A), m² (27.8 cm²).
    pub astm_cylinder_area_m2: f64,
    /// Specific gravity of the soil of the scale, G_s (2.65).
    pub calibration_specific_gravity: f64,
}

impl Default for HydrometerSpec {
    fn default() -> Self {
        Self {
            bulb_volume_m3: 67e-6,
            bulb_length_m: 0.14,
            taper_m: 0.025,
            stem_length_m: 0.14,
            effective_depth_zero_m: 0.1629,
            effective_depth_slope_m: 0.00164,
            full_scale: 60.0,
            astm_cylinder_area_m2: 27.8e-4,
            calibration_specific_gravity: 2.65,
        }
    }
}

/// A calibrated hydrometer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hydrometer {
    /// Its figures.
    pub spec: HydrometerSpec,
    /// Bulb radius R_b (cylindrical part), m.
    pub bulb_radius_m: f64,
    /// Stem radius r_s, m.
    pub stem_radius_m: f64,
    /// Mass, kg.
    pub mass_kg: f64,
    /// Stem length from the top of the bulb to the mark R = 0, L₁(0), m.
    pub zero_mark_m: f64,
    /// Density of the clear fluid (reads R = 0), kg/m³.
    pub fluid_density_kg_m3: f64,
}

/// One hydrometer reading.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct HydrometerReading {
    /// Depth of the tip below the free surface, m.
    pub tip_depth_m: f64,
    /// Depth of the bulb centre (y_go of eq. 16), m.
    pub centre_depth_m: f64,
    /// Stem immersed above the bulb, L₁, m.
    pub stem_immersed_m: f64,
    /// Reading R on the stem, g/L (soil of G_s = 2.65).
    pub reading: f64,
    /// ASTM D422 effective depth L = L₁ + ½ (L₂ − V_B/A), m (shown only: the simulated
    /// suspension does not rise when the virtual hydrometer enters it).
    pub astm_effective_depth_m: f64,
    /// Suspension density from the reading (eq. 19), kg/m³.
    pub density_kg_m3: f64,
    /// Mean density of the suspension over the bulb volume, kg/m³.
    pub bulb_mean_density_kg_m3: f64,
    /// Standard deviation of the density of eq. 19 from the grain counts, kg/m³.
    pub density_sd_kg_m3: f64,
}

impl Hydrometer {
    /// The hydrometer of `spec`, reading R = 0 in a clear fluid of density `fluid_density`.
    pub fn new(spec: HydrometerSpec, fluid_density_kg_m3: f64) -> Self {
        let s = spec;
        let half = 0.5 * (s.bulb_length_m - s.bulb_volume_m3 / s.astm_cylinder_area_m2);
        let l0 = s.effective_depth_zero_m - half;
        let lf = l0 - s.effective_depth_slope_m * s.full_scale;
        let k = 1.0 - 1.0 / Self::relative_density_of(s, s.full_scale);
        let a_s = s.bulb_volume_m3 * k / ((l0 - lf) - l0 * k);
        let r_s = (a_s / PI).sqrt();
        // V_B = π R² (L₂ − 2e) + 2 (π e/3)(R² + R r_s + r_s²): a quadratic in R.
        let (e, l2) = (s.taper_m, s.bulb_length_m);
        let qa = PI * (l2 - 2.0 * e) + 2.0 * PI * e / 3.0;
        let qb = 2.0 * PI * e / 3.0 * r_s;
        let qc = 2.0 * PI * e / 3.0 * r_s * r_s - s.bulb_volume_m3;
        let r_b = (-qb + (qb * qb - 4.0 * qa * qc).sqrt()) / (2.0 * qa);
        let mut h = Self {
            spec,
            bulb_radius_m: r_b,
            stem_radius_m: r_s,
            mass_kg: 0.0,
            zero_mark_m: l0,
            fluid_density_kg_m3,
        };
        h.mass_kg = fluid_density_kg_m3 * h.volume_below(l2 + l0);
        h
    }

    /// The ASTM 152H in a clear fluid of density `fluid_density`.
    pub fn astm_152h(fluid_density_kg_m3: f64) -> Self {
        Self::new(HydrometerSpec::default(), fluid_density_kg_m3)
    }

    fn relative_density_of(s: HydrometerSpec, reading: f64) -> f64 {
        1.0 + reading * (1.0 - 1.0 / s.calibration_specific_gravity) / 1000.0
    }

    /// ρ_s/ρ_f of a suspension reading R (soil of the scale's G_s per litre).
    pub fn relative_density(&self, reading: f64) -> f64 {
        Self::relative_density_of(self.spec, reading)
    }

    /// Stem section A_s, m².
    pub fn stem_area_m2(&self) -> f64 {
        PI * self.stem_radius_m * self.stem_radius_m
    }

    /// Total length (bulb and stem), m.
    pub fn length_m(&self) -> f64 {
        self.spec.bulb_length_m + self.spec.stem_length_m
    }

    /// Radius at height `s` above the tip, m (0 outside the body).
    pub fn radius_m(&self, s: f64) -> f64 {
        let (e, l2) = (self.spec.taper_m, self.spec.bulb_length_m);
        let (rb, rs) = (self.bulb_radius_m, self.stem_radius_m);
        if s < 0.0 || s > self.length_m() {
            0.0
        } else if s < e {
            rs + (rb - rs) * s / e
        } else if s <= l2 - e {
            rb
        } else if s < l2 {
            rb - (rb - rs) * (s - (l2 - e)) / e
        } else {
            rs
        }
    }

    /// Section at height `s` above the tip, m².
    pub fn area_m2(&self, s: f64) -> f64 {
        let r = self.radius_m(s);
        PI * r * r
    }

    /// Volume of the body between the tip and height `s` above it, m³ (exact).
    pub fn volume_below(&self, s: f64) -> f64 {
        let (e, l2) = (self.spec.taper_m, self.spec.bulb_length_m);
        let (rb, rs) = (self.bulb_radius_m, self.stem_radius_m);
        // Frustum from radius r0 over length x with slope k: π ((r0 + k x)³ − r0³)/(3k).
        let frustum = |r0: f64, k: f64, x: f64| {
            if k.abs() < 1e-300 {
                PI * r0 * r0 * x
            } else {
                PI * ((r0 + k * x).powi(3) - r0.powi(3)) / (3.0 * k)
            }
        };
        let s = s.clamp(0.0, self.length_m());
        let k = (rb - rs) / e;
        let mut v = frustum(rs, k, s.min(e));
        if s > e {
            v += PI * rb * rb * (s.min(l2 - e) - e);
        }
        if s > l2 - e {
            v += frustum(rb, -k, s.min(l2) - (l2 - e));
        }
        if s > l2 {
            v += PI * rs * rs * (s - l2);
        }
        v
    }

    /// Bulb volume, m³.
    pub fn bulb_volume_m3(&self) -> f64 {
        self.volume_below(self.spec.bulb_length_m)
    }

    /// Stem length L₁ from the top of the bulb to the mark `reading`, m.
    pub fn mark_m(&self, reading: f64) -> f64 {
        let v0 = self.bulb_volume_m3() + self.stem_area_m2() * self.zero_mark_m;
        (v0 / self.relative_density(reading) - self.bulb_volume_m3()) / self.stem_area_m2()
    }

    /// Mass of the suspension displaced with the tip at depth `tip`, kg: ∫₀^tip ρ_s(y) A(tip − y) dy.
    pub fn displaced_mass_kg(&self, field: &LayeredField, tip: f64) -> f64 {
        field.integrate(0.0, tip, |y| -self.volume_below(tip - y))
    }

    /// Vertical resultant of the pressures on the body with the tip at depth `tip`, N, summed as
    /// seed eq. 21: the pressure at each layer boundary (and at the tip) times the horizontal
    /// projection of the surface between it and the boundary above. It converges to g × the
    /// displaced mass as the layers get thin (first order in h_ly).
    pub fn pressure_force_eq21_n(&self, field: &LayeredField, tip: f64, g: f64) -> f64 {
        let top = (tip - self.length_m()).max(0.0);
        let h = field.layer_m;
        // Boundaries from the tip up: the tip, every layer boundary above it, the surface or top.
        let mut depths = vec![tip];
        let mut j = (tip / h).ceil() as i64 - 1;
        while j as f64 * h > top {
            if (j as f64 * h) < tip {
                depths.push(j as f64 * h);
            }
            j -= 1;
        }
        depths.push(top);
        let mut f = field.pressure_pa(tip, g) * self.area_m2(0.0);
        for w in depths.windows(2) {
            let (lower, upper) = (w[0], w[1]);
            let da = self.area_m2(tip - upper) - self.area_m2(tip - lower);
            f += field.pressure_pa(lower, g) * da;
        }
        // The stem's top face, if under the surface, is pushed down.
        if tip - self.length_m() > 0.0 {
            f -= field.pressure_pa(top, g) * self.area_m2(self.length_m());
        }
        f
    }

    /// Tip depth at which the hydrometer floats in `field`, m (None if it sinks through the
    /// field or does not reach equilibrium within its stem).
    pub fn float_tip_depth_m(&self, field: &LayeredField) -> Option<f64> {
        let f = |tip: f64| self.displaced_mass_kg(field, tip) - self.mass_kg;
        let hi = self.length_m().min(field.height_m());
        if f(hi) < 0.0 {
            return None;
        }
        let rule = Bisection::until(Stop::WidthBelow(1e-12), 200);
        let (lo, hi) = bisect(0.0, hi, rule, |tip| f(tip) < 0.0);
        Some(0.5 * (lo + hi))
    }

    /// Tip depth in the clear fluid (y_ow), m.
    pub fn clear_tip_depth_m(&self) -> f64 {
        self.spec.bulb_length_m + self.zero_mark_m
    }

    /// Reads the hydrometer floating in `field` (None if it does not float).
    pub fn read(&self, field: &LayeredField) -> Option<HydrometerReading> {
        let tip = self.float_tip_depth_m(field)?;
        let l2 = self.spec.bulb_length_m;
        let stem = tip - l2;
        let rho_f = self.fluid_density_kg_m3;
        // Eq. 19: ρ_s = ρ_f m / (m − A_s (y_ow − y_o) ρ_f).
        let rho_s = rho_f * self.mass_kg
            / (self.mass_kg - self.stem_area_m2() * (self.clear_tip_depth_m() - tip) * rho_f);
        let reading =
            1000.0 * (rho_s / rho_f - 1.0) / (1.0 - 1.0 / self.spec.calibration_specific_gravity);
        let bulb_mass = field.integrate(stem.max(0.0), tip, |y| -self.volume_below(tip - y));
        let v_sub = self.volume_below(tip);
        let sd = field.excess_sd(0.0, tip, |y| -self.volume_below(tip - y)) / v_sub;
        Some(HydrometerReading {
            tip_depth_m: tip,
            centre_depth_m: tip - 0.5 * l2,
            stem_immersed_m: stem,
            reading,
            astm_effective_depth_m: stem
                + 0.5 * (l2 - self.spec.bulb_volume_m3 / self.spec.astm_cylinder_area_m2),
            density_kg_m3: rho_s,
            bulb_mean_density_kg_m3: bulb_mass / self.bulb_volume_m3(),
            density_sd_kg_m3: sd,
        })
    }

    /// The (φ_o, w_o) pair of a reading at time `t` (eqs. 16–19; depth = bulb centre).
    pub fn point(&self, an: &Analysis, r: &HydrometerReading, time_s: f64) -> Point {
        let w = an.percent_finer_from_density(r.density_kg_m3);
        let sd = an.percent_finer_from_density(an.fluid_density_kg_m3 + r.density_sd_kg_m3);
        Point {
            time_s,
            depth_m: r.centre_depth_m,
            diameter_m: an.limiting_diameter_m(r.centre_depth_m, time_s),
            percent_finer: w,
            sd_percent: sd,
        }
    }

    /// Suspension density along the bulb at a reading, from its top down: (distance below the
    /// top of the bulb h_hd, depth, density) per layer crossed (seed Fig. 13).
    pub fn bulb_profile(&self, field: &LayeredField, tip: f64) -> Vec<(f64, f64, f64)> {
        let top = tip - self.spec.bulb_length_m;
        field
            .layer_sums(top, tip, |y| y)
            .map(|(k, rho, _)| {
                let y = ((k as f64 + 0.5) * field.layer_m).clamp(top.max(0.0), tip);
                (y - top, y, rho)
            })
            .collect()
    }
}
