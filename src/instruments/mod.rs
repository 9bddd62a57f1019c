//! The laboratory instruments of seed 000 §4.5 applied to a simulated suspension: the ASTM
//! E100 152H hydrometer (ASTM D422, §4.5.1), the buoyancy sphere (§4.5.2) and the pipette
//! (§4.5.3).
//!
//! Every instrument is a plain function of a field and a time:
//!
//! - [`LayeredField`]: the suspension density in horizontal layers of equal thickness (top first),
//!   as in `profiles.csv` (`suspension_density_kg_m3`). The 2D model is 1/180 of the cylinder,
//!   but its layer densities are real densities: the hydrometer and the sphere, which are
//!   axisymmetric bodies on the axis, are floated / weighed in that layered density as if it
//!   filled the whole cylinder.
//! - the pipette reads grains ([`pipette::GrainSample`]), as the laboratory one dries and weighs
//!   what it draws; it also has a field version ([`pipette::Pipette::field_concentration`]) for
//!   the ideal reference.
//!
//! From a reading, [`Analysis`] gives the limiting diameter φ_o (seed eq. 16, Stokes) and the
//! percent finer w_o (eqs. 17–18: w_o = 100 c_o / c_0 with c_o = ρ_p (ρ_s − ρ_f)/(ρ_p − ρ_f)).
//!
//! [`ideal_field`] is the suspension that an ideal Stokes settling of a given cumulative curve
//! leaves at time t (c(y, t) = c_0 F(φ(y, t))): applying an instrument to it gives what that
//! instrument reads in the absence of any statistical noise or hindered settling, so its
//! difference to the input curve is the instrument's own approximation (finite bulb, sphere or
//! disc).

pub mod buoyancy;
pub mod counting;
pub mod forward;
pub mod hydrometer;
pub mod pipette;
pub mod reduction;

/// Suspension density in horizontal layers of equal thickness, the first at the free surface.
/// Below the last layer the density of the last layer holds.
#[derive(Clone, Debug, PartialEq)]
pub struct LayeredField {
    /// Layer thickness h_ly, m.
    pub layer_m: f64,
    /// Density of each layer, kg/m³ (top first).
    pub density_kg_m3: Vec<f64>,
    /// Density of the clear fluid ρ_f, kg/m³.
    pub fluid_density_kg_m3: f64,
    /// Representative grains in each layer (for the statistical uncertainty; `None` for exact
    /// fields).
    pub grains: Option<Vec<f64>>,
}

impl LayeredField {
    /// A field of `layers` layers over `height_m` with density `f(depth of the layer centre)`.
    pub fn from_fn(
        height_m: f64,
        layers: usize,
        fluid_density_kg_m3: f64,
        f: impl Fn(f64) -> f64,
    ) -> Self {
        let h = height_m / layers as f64;
        Self {
            layer_m: h,
            density_kg_m3: (0..layers).map(|k| f((k as f64 + 0.5) * h)).collect(),
            fluid_density_kg_m3,
            grains: None,
        }
    }

    /// A uniform field of density `rho`.
    pub fn uniform(height_m: f64, layers: usize, fluid_density_kg_m3: f64, rho: f64) -> Self {
        Self::from_fn(height_m, layers, fluid_density_kg_m3, |_| rho)
    }

    /// Height of the field (depth of the bottom of the last layer), m.
    pub fn height_m(&self) -> f64 {
        self.layer_m * self.density_kg_m3.len() as f64
    }

    /// Density at depth `y` (m below the free surface), kg/m³; the fluid's above the surface is
    /// not used (depths are clamped to the field).
    pub fn density_at(&self, y: f64) -> f64 {
        let k = ((y.max(0.0) / self.layer_m) as usize).min(self.density_kg_m3.len() - 1);
        self.density_kg_m3[k]
    }

    /// Pressure at depth `y` above the atmospheric one, Pa: p(y) = g ∫₀ʸ ρ (seed §4.5.1).
    pub fn pressure_pa(&self, y: f64, g: f64) -> f64 {
        g * self.integrate(0.0, y, |u| u)
    }

    /// ∫ₐᵇ ρ(y) w(y) dy, exact for the piecewise-constant field, given an antiderivative `big_w`
    /// of the weight w (W' = w). Depths beyond the field use the last layer.
    pub fn integrate(&self, a: f64, b: f64, big_w: impl Fn(f64) -> f64) -> f64 {
        self.layer_sums(a, b, big_w)
            .map(|(_, rho, wk)| rho * wk)
            .sum()
    }

    /// The layers overlapping [a, b]: (index, density, ∫ w over the overlap). The last layer
    /// extends to infinity.
    pub fn layer_sums<'a, F: Fn(f64) -> f64 + 'a>(
        &'a self,
        a: f64,
        b: f64,
        big_w: F,
    ) -> impl Iterator<Item = (usize, f64, f64)> + 'a {
        let a = a.max(0.0);
        let n = self.density_kg_m3.len();
        let h = self.layer_m;
        let (k0, k1) = if b > a {
            (
                ((a / h) as usize).min(n - 1),
                (((b / h).ceil() as usize).max(1) - 1).min(n - 1),
            )
        } else {
            (1, 0)
        };
        (k0..=k1).filter_map(move |k| {
            let top = (k as f64 * h).max(a);
            let bot = if k + 1 == n {
                b
            } else {
                ((k + 1) as f64 * h).min(b)
            };
            (bot > top).then(|| (k, self.density_kg_m3[k], big_w(bot) - big_w(top)))
        })
    }

    /// Standard deviation of ∫ (ρ − ρ_f) w over [a, b] from the grain counts: each layer's excess
    /// density has the relative standard deviation 1/√n of its n grains (0 for exact fields).
    pub fn excess_sd(&self, a: f64, b: f64, big_w: impl Fn(f64) -> f64) -> f64 {
        let Some(n) = &self.grains else {
            return 0.0;
        };
        self.layer_sums(a, b, big_w)
            .map(|(k, rho, wk)| {
                let x = (rho - self.fluid_density_kg_m3) * wk;
                if n[k] > 0.0 {
                    x * x / n[k]
                } else {
                    0.0
                }
            })
            .sum::<f64>()
            .sqrt()
    }
}

/// The conversions of the standard analysis: Stokes limiting diameter (seed eq. 16) and percent
/// finer from a concentration or a density (eqs. 17–18).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Analysis {
    /// Dynamic viscosity μ of the fluid, Pa s.
    pub viscosity_pa_s: f64,
    /// Grain density ρ_p, kg/m³.
    pub grain_density_kg_m3: f64,
    /// Fluid density ρ_f, kg/m³.
    pub fluid_density_kg_m3: f64,
    /// Gravity |g|, m/s².
    pub gravity_m_s2: f64,
    /// Initial mass concentration of the suspension c_0 (dry soil per volume), kg/m³.
    pub c0_kg_m3: f64,
}

impl Analysis {
    /// φ_o = √(18 μ y / ((ρ_p − ρ_f) g t)) (seed eq. 16), m.
    pub fn limiting_diameter_m(&self, depth_m: f64, time_s: f64) -> f64 {
        (18.0 * self.viscosity_pa_s * depth_m
            / ((self.grain_density_kg_m3 - self.fluid_density_kg_m3) * self.gravity_m_s2 * time_s))
            .sqrt()
    }

    /// Mass concentration from a suspension density, c_o = ρ_p (ρ_s − ρ_f)/(ρ_p − ρ_f) (eq. 18),
    /// kg/m³.
    pub fn concentration_kg_m3(&self, suspension_density_kg_m3: f64) -> f64 {
        let (rp, rf) = (self.grain_density_kg_m3, self.fluid_density_kg_m3);
        rp * (suspension_density_kg_m3 - rf) / (rp - rf)
    }

    /// w_o = 100 c_o / c_0 (eq. 17), %.
    pub fn percent_finer_from_concentration(&self, c_kg_m3: f64) -> f64 {
        100.0 * c_kg_m3 / self.c0_kg_m3
    }

    /// w_o from a suspension density (eqs. 17–18), %.
    pub fn percent_finer_from_density(&self, suspension_density_kg_m3: f64) -> f64 {
        self.percent_finer_from_concentration(self.concentration_kg_m3(suspension_density_kg_m3))
    }

    /// Suspension density of a mass concentration c (inverse of eq. 18), kg/m³.
    pub fn density_of_concentration(&self, c_kg_m3: f64) -> f64 {
        let (rp, rf) = (self.grain_density_kg_m3, self.fluid_density_kg_m3);
        rf + c_kg_m3 * (rp - rf) / rp
    }
}

/// The suspension left at time `t` by ideal Stokes settling of a homogeneous suspension of
/// concentration c_0 whose cumulative curve is `finer` (fraction 0–1 of mass finer than a
/// diameter): c(y, t) = c_0 F(φ(y, t)) at every depth (a bottomless cylinder; seed eq. 16).
pub fn ideal_field(
    an: &Analysis,
    height_m: f64,
    layers: usize,
    time_s: f64,
    finer: impl Fn(f64) -> f64,
) -> LayeredField {
    LayeredField::from_fn(height_m, layers, an.fluid_density_kg_m3, |y| {
        let f = if time_s > 0.0 {
            finer(an.limiting_diameter_m(y, time_s))
        } else {
            1.0
        };
        an.density_of_concentration(an.c0_kg_m3 * f)
    })
}

/// Default reading times of the hydrometer, s: ASTM D422, 2, 5, 15, 30, 60, 250 and 1440 min.
pub const HYDROMETER_TIMES_MIN: [f64; 7] = [2.0, 5.0, 15.0, 30.0, 60.0, 250.0, 1440.0];

/// Default reading times of the buoyancy sphere and the pipette, min (seed §4.5.2).
pub const SPHERE_TIMES_MIN: [f64; 10] = [0.5, 1.0, 2.0, 4.0, 15.0, 30.0, 60.0, 120.0, 240.0, 480.0];

/// One reading of an instrument, reduced to the pair of the granulometric curve.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Point {
    /// Time of the reading, s.
    pub time_s: f64,
    /// Depth used in eq. 16 (hydrometer: bulb centre; sphere: centre; pipette: tip), m.
    pub depth_m: f64,
    /// Limiting diameter φ_o, m.
    pub diameter_m: f64,
    /// Percent finer w_o, %.
    pub percent_finer: f64,
    /// Standard deviation of w_o from the grain count, % (0 for exact fields).
    pub sd_percent: f64,
}
