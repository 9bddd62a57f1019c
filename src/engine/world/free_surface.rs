//! The free surface: where the fluid is, for scenes where bodies travel through air before
//! they enter it.

use crate::fluid::Submergence;

/// The fluid's extent, for scenes where bodies travel through air before they enter the fluid
/// (see [`super::World::set_free_surface`]). SI units.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FreeSurface {
    /// Height of the free surface on the last axis, m: the fluid lies below it.
    pub height_m: f64,
    /// Radius of the fluid column about the vertical axis through the origin, m (a cylindrical
    /// container); None: the fluid extends sideways without bound.
    pub radius_m: Option<f64>,
    /// How the fluid forces act on a sphere crossing the surface (f-EDEM: full).
    pub submergence: Submergence,
}
