//! The forward operator of one readings file: the test's column and instrument, and what the
//! instrument reads in the suspension that a distribution `w` leaves (with its derivative in
//! `w`).
//!
//! A reading is predicted as the laboratory takes it: the instrument applied to the field
//! ρ_f + Σ_j w_j u_j (`forward::field_of`), plus the clear-fluid offset of the file (the
//! hydrometer's blank reading r_d: the meniscus correction cancels in r − r_d, so only the
//! blank matters; the pipette's blank mass of dispersant per draw).

use crate::error::Error;
use crate::instruments::buoyancy::BuoyancySphere;
use crate::instruments::forward::Column;
use crate::instruments::hydrometer::Hydrometer;
use crate::instruments::pipette::Pipette;
use crate::instruments::{Analysis, LayeredField};
use std::f64::consts::PI;
use std::path::PathBuf;

/// Where a pipette draws from in the forward model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DrawRegion {
    /// A sphere of the pipette's volume around the tip (the laboratory draw).
    Sphere,
    /// A disc of the 2D model of this radius, m, weighted by its chord.
    Disc {
        /// Radius of the disc, m.
        radius_m: f64,
    },
}

/// The instrument of a readings file, as the forward model reads it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Probe {
    /// A floating soil hydrometer (reads g/L of the 152H scale).
    Hydrometer(Hydrometer),
    /// A pipette draw (reads the oven-dry mass drawn, g).
    Pipette {
        /// Volume drawn, m³.
        volume_m3: f64,
        /// Depth of the tip (centre of the draw) below the free surface, m.
        depth_m: f64,
        /// Shape of the region drawn.
        region: DrawRegion,
    },
    /// A buoyancy sphere on a dynamometer (reads its apparent mass, g).
    Sphere(BuoyancySphere),
}

impl Probe {
    /// Its name in misfit.csv and on the console.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Hydrometer(_) => "hydrometer",
            Self::Pipette { .. } => "pipette",
            Self::Sphere(_) => "buoyancy-sphere",
        }
    }

    /// The depths (shallowest, deepest) below the free surface over which the instrument
    /// averages the suspension, m, when it reads `own` (its reading less the offset): the
    /// hydrometer's bulb floating at the mark `own` (tip L₂ + L₁(own) deep); the sphere's and
    /// the draw's extent.
    pub fn depth_span_m(&self, own: f64) -> (f64, f64) {
        match self {
            Self::Hydrometer(h) => {
                let stem = h.mark_m(own).clamp(0.0, h.spec.stem_length_m);
                (stem, stem + h.spec.bulb_length_m)
            }
            Self::Pipette {
                volume_m3,
                depth_m,
                region,
            } => {
                let r = match region {
                    DrawRegion::Sphere => (3.0 * volume_m3 / (4.0 * PI)).cbrt(),
                    DrawRegion::Disc { radius_m } => *radius_m,
                };
                ((depth_m - r).max(0.0), depth_m + r)
            }
            Self::Sphere(s) => (
                (s.depth_m - 0.5 * s.diameter_m).max(0.0),
                s.depth_m + 0.5 * s.diameter_m,
            ),
        }
    }

    /// The instrument's own reading in `field` (0 in the clear fluid for the hydrometer and the
    /// pipette; the apparent mass for the sphere), in the file's unit. None if the hydrometer
    /// does not float within its stem.
    pub fn read(&self, an: &Analysis, field: &LayeredField) -> Option<f64> {
        match self {
            Self::Hydrometer(h) => h.read(field).map(|r| r.reading),
            Self::Pipette {
                volume_m3,
                depth_m,
                region,
            } => {
                let c = match region {
                    DrawRegion::Sphere => {
                        let d = 2.0 * (3.0 * volume_m3 / (4.0 * PI)).cbrt();
                        let s = BuoyancySphere {
                            diameter_m: d,
                            mass_kg: 0.0,
                            depth_m: *depth_m,
                        };
                        an.concentration_kg_m3(s.read(field).density_kg_m3)
                    }
                    DrawRegion::Disc { radius_m } => Pipette {
                        volume_m3: *volume_m3,
                        depth_m: *depth_m,
                        wedge_fraction: 1.0,
                        thickness_m: volume_m3 / (PI * radius_m * radius_m),
                        axis_x_m: 0.0,
                    }
                    .field_concentration(an, field),
                };
                Some(c * volume_m3 * 1e3)
            }
            Self::Sphere(s) => Some(s.read(field).apparent_mass_kg * 1e3),
        }
    }
}

/// One readings file as the inversion sees it.
#[derive(Clone, Debug)]
pub struct Test {
    /// The file.
    pub file: PathBuf,
    /// The column (height, layers, conversions of the test).
    pub col: Column,
    /// The instrument.
    pub probe: Probe,
    /// Reading times, s.
    pub times_s: Vec<f64>,
    /// Readings, in the file's unit.
    pub readings: Vec<f64>,
    /// Clear-fluid offset of each reading (hydrometer: the blank reading; pipette: the blank
    /// mass per draw; sphere: 0), in the file's unit.
    pub offsets: Vec<f64>,
    /// Resolution of the readings Δ, in the file's unit.
    pub resolution: f64,
    /// Counting σ of each reading, in the file's unit: the file's `counting_sigma` column (a
    /// run's readings: the noise of its representative grains,
    /// [`crate::instruments::counting`]), 0 for a laboratory's readings.
    pub counting_sigma: Vec<f64>,
    /// How the file was read (the format layer's `[input]` keys: format, sheet, encoding,
    /// delimiter, decimal mark) and its doubtful values, for invert.toml and the warnings.
    pub input: Option<(crate::io::lab_file::Detected, Vec<String>)>,
}

impl Test {
    /// Standard deviation σ = Δ/2 of each reading, in the file's unit: the rounding to the
    /// resolution (uniform, Δ/√12) and a reading error of Δ/√6 (σ² = Δ²/12 + Δ²/6 = Δ²/4).
    pub fn sigma(&self) -> f64 {
        0.5 * self.resolution
    }

    /// Standard deviation of reading `i`: the resolution's σ and the reading's counting σ
    /// together, independent errors: σ_i² = σ_res² + σ_count,i².
    pub fn sigma_at(&self, i: usize) -> f64 {
        let c = self.counting_sigma.get(i).copied().unwrap_or(0.0);
        self.sigma().hypot(c)
    }

    /// The predicted reading `i` in the suspension of distribution `w` (unit fields `unit` of
    /// reading i's time: `unit[j][k]`), and its derivative in each w_j.
    ///
    /// Pipette and sphere are affine in w: the derivative is the reading of each unit field.
    /// The hydrometer floats where its displaced mass D(tip, w) = ∫₀^tip ρ A(tip − y) dy equals
    /// its mass, so ∂tip/∂w_j = −(∂D/∂w_j)/(∂D/∂tip) (implicit function), and its reading R(tip)
    /// (eq. 19) gives ∂R/∂w_j = R′(tip) ∂tip/∂w_j.
    pub fn predict(
        &self,
        i: usize,
        unit: &[Vec<f64>],
        w: &[f64],
    ) -> Result<(f64, Vec<f64>), Error> {
        let col = &self.col;
        let an = &col.analysis;
        let field = crate::instruments::forward::field_of(col, unit, w);
        let Some(own) = self.probe.read(an, &field) else {
            return Err(Error::bad_input(
                &self.file,
                None,
                format!(
                    "reading {} (t = {} s): the hydrometer does not float in the suspension the \
                     model predicts (off its stem): check dry_mass_g and suspension_volume_ml",
                    i + 1,
                    crate::io::fmt::g(self.times_s[i])
                ),
            ));
        };
        let jac = match &self.probe {
            Probe::Hydrometer(h) => {
                let tip = h.float_tip_depth_m(&field).expect("floated a moment ago");
                let dh = 1e-7;
                let d_dtip = (h.displaced_mass_kg(&field, tip + dh)
                    - h.displaced_mass_kg(&field, tip - dh))
                    / (2.0 * dh);
                let r_of = |t: f64| {
                    let rf = h.fluid_density_kg_m3;
                    let rho = rf * h.mass_kg
                        / (h.mass_kg - h.stem_area_m2() * (h.clear_tip_depth_m() - t) * rf);
                    1000.0 * (rho / rf - 1.0) / (1.0 - 1.0 / h.spec.calibration_specific_gravity)
                };
                let dr_dtip = (r_of(tip + dh) - r_of(tip - dh)) / (2.0 * dh);
                // ∂D/∂w_j = Σ_k u_jk W_k, W_k = ∫ A(tip − y) dy over layer k (one pass).
                let weights: Vec<(usize, f64)> = field
                    .layer_sums(0.0, tip, |y| -h.volume_below(tip - y))
                    .map(|(k, _, wk)| (k, wk))
                    .collect();
                unit.iter()
                    .map(|u| {
                        let dd: f64 = weights.iter().map(|&(k, wk)| u[k] * wk).sum();
                        -dr_dtip * dd / d_dtip
                    })
                    .collect()
            }
            _ => {
                let clear = self
                    .probe
                    .read(an, &crate::instruments::forward::field_of(col, unit, &[]))
                    .unwrap_or(0.0);
                unit.iter()
                    .enumerate()
                    .map(|(j, _)| {
                        let mut e = vec![0.0; unit.len()];
                        e[j] = 1.0;
                        let f = crate::instruments::forward::field_of(col, unit, &e);
                        self.probe.read(an, &f).unwrap_or(clear) - clear
                    })
                    .collect()
            }
        };
        Ok((own + self.offsets[i], jac))
    }
}
