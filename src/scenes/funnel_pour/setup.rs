//! The scene's geometry (see the [module doc](super)): the cylinder, the funnel and its column,
//! where a ball is, and the colliders that make the walls.

use super::census::Place;
use crate::engine::dim3;
use crate::scenario::FunnelPourSpec;
use rapier3d_f64::math::{Pose, Rotation, Vector as RVector};
use rapier3d_f64::prelude::{ColliderBuilder, ColliderHandle};

/// Margin of the domain beyond the scene's bounding box, m.
pub const DOMAIN_MARGIN_M: f64 = 0.1;

/// Geometry of the scene, SI units, derived from the scenario (see the [module doc](super)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Geometry {
    /// Inner radius of the cylinder R, m.
    pub cylinder_radius_m: f64,
    /// Height of the paste surface above the bottom H, m.
    pub paste_height_m: f64,
    /// Height of the top of the cylinder wall above the bottom, m.
    pub wall_top_z_m: f64,
    /// Height of the outlet above the bottom, m.
    pub outlet_z_m: f64,
    /// Inner radius of the outlet, m.
    pub outlet_radius_m: f64,
    /// Inner radius of the funnel at the top of the cone (and of the column), m.
    pub top_radius_m: f64,
    /// Height of the top of the cone above the bottom, m.
    pub cone_top_z_m: f64,
    /// Height of the top of the column above the bottom, m.
    pub column_top_z_m: f64,
    /// Half-angle of the cone from the vertical, rad.
    pub half_angle_rad: f64,
    /// Wall thickness, m.
    pub wall_thickness_m: f64,
    /// Number of faces per circle.
    pub facets: usize,
}

impl Geometry {
    /// The geometry of a `funnel_pour` scenario: its `[funnel]` table and its cylinder.
    pub fn of(spec: &FunnelPourSpec) -> Self {
        let f = &spec.funnel;
        let h = spec.height_m;
        let outlet_z = h + f.outlet_above_surface_m;
        let (r_out, r_top) = (0.5 * f.outlet_diameter_m, 0.5 * f.top_diameter_m);
        Self {
            cylinder_radius_m: spec.cylinder_radius_m,
            paste_height_m: h,
            wall_top_z_m: h + f.wall_above_surface_m,
            outlet_z_m: outlet_z,
            outlet_radius_m: r_out,
            top_radius_m: r_top,
            cone_top_z_m: outlet_z + f.cone_height_m,
            column_top_z_m: outlet_z + f.cone_height_m + f.column_height_m,
            half_angle_rad: ((r_top - r_out) / f.cone_height_m).atan(),
            wall_thickness_m: f.wall_thickness_m,
            facets: f.facets,
        }
    }

    /// Inner radius of the funnel (cone or column) at height `z_m`, m (the circle, not the
    /// polygon; None below the outlet or above the column).
    pub fn funnel_radius_m(&self, z_m: f64) -> Option<f64> {
        if z_m < self.outlet_z_m || z_m > self.column_top_z_m {
            None
        } else if z_m >= self.cone_top_z_m {
            Some(self.top_radius_m)
        } else {
            Some(self.outlet_radius_m + (z_m - self.outlet_z_m) * self.half_angle_rad.tan())
        }
    }

    /// Radius of the domain about the axis, m.
    pub fn domain_radius_m(&self) -> f64 {
        self.cylinder_radius_m.max(self.top_radius_m) + self.wall_thickness_m + DOMAIN_MARGIN_M
    }

    /// True if a ball of diameter `d_m` moving from `from` to `to` passed through a wall: its
    /// centre crossed the cylinder's radius more than d/4 below the rim, or is beyond the outer
    /// face of a funnel wall, or below the floor.
    pub fn breached(&self, from: &[f64; 3], to: &[f64; 3], d_m: f64) -> bool {
        let (r0, r1) = (from[0].hypot(from[1]), to[0].hypot(to[1]));
        let r = self.cylinder_radius_m;
        let below_rim = to[2].max(from[2]) < self.wall_top_z_m - 0.25 * d_m;
        let crossed = (r0 <= r) != (r1 <= r);
        let beyond_funnel = self
            .funnel_radius_m(to[2])
            .is_some_and(|rf| r1 > rf + self.wall_thickness_m + 0.5 * d_m);
        (crossed && below_rim) || beyond_funnel || to[2] < 0.0
    }

    /// Where a ball of diameter `d_m` centred at `x` is (without the history: see
    /// [`Geometry::breached`] for `lost`).
    pub fn place(&self, x: &[f64; 3], d_m: f64) -> Place {
        if !x.iter().all(|c| c.is_finite()) {
            return Place::Lost;
        }
        let rho = x[0].hypot(x[1]);
        let z = x[2];
        if rho > self.domain_radius_m() || z < -d_m || z > self.column_top_z_m + DOMAIN_MARGIN_M {
            Place::Away
        } else if rho <= self.cylinder_radius_m && z - 0.5 * d_m <= self.paste_height_m {
            Place::Paste
        } else if rho <= self.top_radius_m + self.wall_thickness_m
            && z >= self.outlet_z_m - 0.5 * d_m
        {
            Place::Funnel
        } else if rho <= self.top_radius_m.max(self.cylinder_radius_m) && z > self.paste_height_m {
            Place::Falling
        } else {
            Place::Outside
        }
    }
}

/// Box faces of a vertical circle (cylinder wall or column) of inner radius `r`, from `z0` to
/// `z1`.
fn ring(geo: &Geometry, r: f64, z0: f64, z1: f64, e: f64, mu: f64) -> Vec<ColliderBuilder> {
    let n = geo.facets as f64;
    let t = geo.wall_thickness_m;
    let half_w = (r + t) * (std::f64::consts::PI / n).tan();
    (0..geo.facets)
        .map(|i| {
            let th = 2.0 * std::f64::consts::PI * i as f64 / n;
            let c = r + 0.5 * t;
            ColliderBuilder::cuboid(0.5 * t, half_w, 0.5 * (z1 - z0))
                .position(Pose::from_parts(
                    RVector::new(c * th.cos(), c * th.sin(), 0.5 * (z0 + z1)),
                    Rotation::from_rotation_z(th),
                ))
                .restitution(e)
                .friction(mu)
        })
        .collect()
}

/// Box faces of the cone: each box's inner face is tangent to the cone along a generatrix
/// (a pyramid circumscribing the cone; wider than the pyramid's faces, the boxes overlap behind
/// them).
fn cone(geo: &Geometry, e: f64, mu: f64) -> Vec<ColliderBuilder> {
    let n = geo.facets as f64;
    let t = geo.wall_thickness_m;
    let a = geo.half_angle_rad;
    let h = geo.cone_top_z_m - geo.outlet_z_m;
    let len = h / a.cos();
    let half_w = (geo.top_radius_m + t) * (std::f64::consts::PI / n).tan();
    let r_mid = 0.5 * (geo.outlet_radius_m + geo.top_radius_m);
    let z_mid = 0.5 * (geo.outlet_z_m + geo.cone_top_z_m);
    (0..geo.facets)
        .map(|i| {
            let th = 2.0 * std::f64::consts::PI * i as f64 / n;
            // Local x: outward normal of the cone (cos a, 0, −sin a) at azimuth 0; local z: the
            // generatrix (sin a, 0, cos a).
            let rot = Rotation::from_rotation_z(th) * Rotation::from_rotation_y(a);
            let normal = rot * RVector::X;
            let mid = RVector::new(r_mid * th.cos(), r_mid * th.sin(), z_mid);
            ColliderBuilder::cuboid(0.5 * t, half_w, 0.5 * len)
                .position(Pose::from_parts(mid + normal * (0.5 * t), rot))
                .restitution(e)
                .friction(mu)
        })
        .collect()
}

/// Adds the fixed walls of the scene to `world` (the cylinder wall, the cone, the column above it
/// when there is one, all with restitution `e` and friction `mu`) and the plug closing the
/// outlet from below; returns the plug's handle.
pub fn add_walls(world: &mut dim3::World, geo: &Geometry, e: f64, mu: f64) -> ColliderHandle {
    let mut faces = ring(geo, geo.cylinder_radius_m, 0.0, geo.wall_top_z_m, e, mu);
    faces.extend(cone(geo, e, mu));
    if geo.column_top_z_m > geo.cone_top_z_m {
        faces.extend(ring(
            geo,
            geo.top_radius_m,
            geo.cone_top_z_m,
            geo.column_top_z_m,
            e,
            mu,
        ));
    }
    for face in faces {
        world.add_fixed_collider(face);
    }
    let t = geo.wall_thickness_m;
    let plug_half = geo.outlet_radius_m + 2.0 * t;
    world.add_fixed_collider(
        ColliderBuilder::cuboid(plug_half, plug_half, 0.5 * t)
            .translation(RVector::new(0.0, 0.0, geo.outlet_z_m - 0.5 * t))
            .restitution(e)
            .friction(mu),
    )
}
