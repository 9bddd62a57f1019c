//! The container, the release and the spheres: `[container]`, `[release]`, `[[spheres]]`,
//! `[spheres_csv]`.

use super::base::Dim;
use crate::error::BadInput;
use crate::scenario::check::{oc, Check};
use serde::{Deserialize, Serialize};

/// The container.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Container {
    /// Height of the fluid column from the bottom to the free surface, m (> 0).
    pub height_m: f64,
    /// Diameter of a cylindrical container, m (3D only). Walls are not modelled in free settling.
    #[serde(default)]
    pub diameter_m: Option<f64>,
    /// Width of a rectangular container, m (2D, or 3D square section).
    #[serde(default)]
    pub width_m: Option<f64>,
}

/// Release of the bodies.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct Release {
    /// Depth of the sphere's centre below the free surface at release, m. Default 0, which
    /// means "just submerged": the centre at one radius below the surface.
    #[serde(default)]
    pub depth_m: f64,
    /// Initial downward speed, m/s. Default 0 (from rest).
    #[serde(default)]
    pub velocity_m_s: f64,
    /// Fall heights of the sphere's lowest point above the free surface, m (kind `drop`): every
    /// sphere is dropped from each, from rest, as an independent case.
    #[serde(default)]
    pub fall_heights_m: Vec<f64>,
}

/// One sphere.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SphereSpec {
    /// Identifier in outputs. Default `sphere-<index>`.
    #[serde(default)]
    pub id: Option<String>,
    /// Diameter d, m (0 < d ≤ 10).
    pub diameter_m: f64,
    /// Density ρ_p, kg/m³ (0 < ρ_p ≤ 25 000).
    pub density_kg_m3: f64,
    /// Young's modulus E, Pa (optional; for the Rayleigh time, f-EDEM eq. 22).
    #[serde(default)]
    pub youngs_modulus_pa: Option<f64>,
    /// Poisson's ratio ν (optional; −1 < ν < 0.5).
    #[serde(default)]
    pub poisson_ratio: Option<f64>,
    /// Measured terminal velocity, m/s (optional; compared in the summary).
    #[serde(default)]
    pub v_measured_m_s: Option<f64>,
    /// Suspension or group number (optional; reported in the summary).
    #[serde(default)]
    pub suspension: Option<u32>,
}

/// Measured curves a free-settling run draws beside its own (`velocity.svg`, `gap.svg`):
/// `[reference]`. The files are read and checked while the scenario is prepared
/// ([`crate::scenario::inputs::read_reference`]).
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ReferenceSpec {
    /// Where the curves come from, named in the charts' legends (e.g. `ten Cate et al. (2002),
    /// Fig. 5, digitised`).
    pub source: String,
    /// CSV of the measured settling velocity against time, relative to the scenario file's
    /// folder: columns `time_s` and `velocity_m_s` (downward speed), others ignored.
    #[serde(default)]
    pub velocity_csv: Option<String>,
    /// CSV of the measured gap between the sphere's lowest point and the container bottom
    /// against time, relative to the scenario file's folder: columns `time_s` and `gap_m`,
    /// others ignored.
    #[serde(default)]
    pub gap_csv: Option<String>,
}

/// Spheres from a CSV file, as `data/valentik_whitmore_1965_spheres.csv`. Its columns are named
/// like the keys of `[[spheres]]`: `id`, `suspension`, `diameter_m`, `density_kg_m3`,
/// `youngs_modulus_pa`, `poisson_ratio`, `v_measured_m_s`; the old names `sphere_id` and
/// `v_terminal_measured_m_s` still read, and the reference columns `re_bingham_tabulated`,
/// `cd_tabulated` are allowed and not read. Any other column is refused; an empty field is an
/// absent optional value. See [`crate::scenario::inputs::spheres`].
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SpheresCsv {
    /// Path, relative to the scenario file.
    pub path: String,
    /// Keep only rows of this suspension (optional).
    #[serde(default)]
    pub suspension: Option<u32>,
}

impl Container {
    /// Height, diameter (3D only) and width within (0, 10 km].
    pub(crate) fn check(&self, c: &Check, dimension: Dim) -> Result<(), BadInput> {
        c.range("container.height_m", self.height_m, oc(0.0, 1e4, "m"))?;
        if let Some(dia) = self.diameter_m {
            if dimension == Dim::Two {
                return Err(c.err("container.diameter_m", "a cylinder is 3D-only: with dimension = 2 give container.width_m (the 2D projection of the cylinder)"));
            }
            c.range("container.diameter_m", dia, oc(0.0, 1e4, "m"))?;
        }
        if let Some(w) = self.width_m {
            c.range("container.width_m", w, oc(0.0, 1e4, "m"))?;
        }
        Ok(())
    }

    /// The narrowest horizontal extent, m: the diameter of a cylinder, the width of a box (the
    /// smaller if both are given), infinite if neither is.
    pub fn narrowest_m(&self) -> f64 {
        self.diameter_m
            .unwrap_or(f64::INFINITY)
            .min(self.width_m.unwrap_or(f64::INFINITY))
    }
}
