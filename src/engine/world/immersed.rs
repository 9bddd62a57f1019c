//! The fluid forces a body feels at the start of a step: drag, body force and spin drag scaled
//! by its immersed fractions below the free surface ([`super::FreeSurface`],
//! [`crate::fluid::immersion::immersion`]).

use super::{to_na, Body, FreeSurface, Vector, World, DIM};
use crate::fluid::{immersion, SphereDrag};

impl World {
    /// Restricts the fluid to the region below a free surface (and within a cylinder), for scenes
    /// where bodies fall through air into the fluid (f-EDEM §4.2 funnel pour). Each step, a body's
    /// drag (and its rotational drag) is scaled by the immersed fraction of its projected area and
    /// its body force (`FluidBody::body_force_n`, the buoyancy) by the immersed fraction of its
    /// volume, both from [`crate::fluid::immersion::immersion`] at the start of the step:
    /// with `full` submergence both are 1 as soon as the sphere's lowest point is below the
    /// surface, 0 above; with `partial`, the spherical cap below it. Outside `radius_m` (measured
    /// from the vertical axis through the origin, at the sphere's centre) there is no fluid. Entry
    /// is not located within the step (a body enters up to one step late: |v| dt).
    pub fn set_free_surface(&mut self, surface: FreeSurface) {
        self.surface = Some(surface);
    }

    /// Fluid forces on a body at the start of a step: (drag, body force, spin-drag rate, immersed
    /// volume fraction), with the free surface's immersed fractions applied if one is set.
    pub(super) fn fluid_now(&self, body: &Body) -> (SphereDrag, Vector, f64, f64) {
        let Some(fs) = self.surface else {
            return (body.drag, body.body_force_n, body.spin_drag_rate_hz, 1.0);
        };
        let x = to_na(self.physics.bodies[body.handle].translation());
        let mut horizontal = x;
        horizontal[DIM - 1] = 0.0;
        let outside = fs.radius_m.is_some_and(|r| horizontal.norm() > r);
        let (fv, fa) = if outside {
            (0.0, 0.0)
        } else {
            immersion(
                fs.height_m - x[DIM - 1],
                body.drag.diameter_m,
                fs.submergence,
            )
        };
        (
            body.drag.scaled(fa),
            body.body_force_n * fv,
            body.spin_drag_rate_hz * fa,
            fv,
        )
    }
}
