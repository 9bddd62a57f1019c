//! The random initial placement of the balls in the funnel and its column.

use super::setup::Geometry;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Clearance of the random initial placement, as a fraction of the ball's diameter.
pub const PLACEMENT_GAP: f64 = 0.05;

/// A ball that found no free place in the funnel and column in 100 000 random tries.
#[derive(Clone, Debug, PartialEq)]
pub struct Unplaceable {
    /// Index of the ball (0-based).
    pub index: usize,
    /// Number of balls to place.
    pub count: usize,
    /// Its diameter, m.
    pub diameter_m: f64,
}

impl std::fmt::Display for Unplaceable {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "cannot place ball {} of {} (d = {} m) in the funnel at random: raise funnel.column_height_m or top_diameter_m",
            self.index, self.count, self.diameter_m
        )
    }
}

/// Random initial centres of the balls of diameters `diameters` in the funnel and column, clear
/// of the walls, the plug and each other by [`PLACEMENT_GAP`] × d; [`Unplaceable`] if a ball
/// cannot be placed in 100 000 tries.
pub fn place_balls(
    geo: &Geometry,
    diameters: &[f64],
    seed: u64,
) -> Result<Vec<[f64; 3]>, Unplaceable> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut placed: Vec<([f64; 3], f64)> = Vec::with_capacity(diameters.len());
    let cos_a = geo.half_angle_rad.cos();
    for (i, &d) in diameters.iter().enumerate() {
        let r = 0.5 * d;
        let gap = PLACEMENT_GAP * d;
        let z_lo = geo.outlet_z_m + r + gap;
        let z_hi = geo.column_top_z_m - r - gap;
        let mut ok = None;
        for _ in 0..100_000 {
            if z_hi < z_lo {
                break;
            }
            let z = rng.random_range(z_lo..=z_hi);
            let rho_max = geo.top_radius_m;
            let rho = rho_max * rng.random::<f64>().sqrt();
            let phi = rng.random_range(0.0..std::f64::consts::TAU);
            let wall = geo.funnel_radius_m(z).unwrap_or(0.0);
            // Distance to the cone along its normal: (R(z) − ρ) cos a; to the column: R − ρ.
            let clear = if z < geo.cone_top_z_m {
                (wall - rho) * cos_a
            } else {
                wall - rho
            };
            if clear < r + gap {
                continue;
            }
            let x = [rho * phi.cos(), rho * phi.sin(), z];
            let free = placed.iter().all(|(y, dy)| {
                let dist =
                    ((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2) + (x[2] - y[2]).powi(2)).sqrt();
                dist >= 0.5 * (d + dy) + gap
            });
            if free {
                ok = Some(x);
                break;
            }
        }
        let x = ok.ok_or(Unplaceable {
            index: i,
            count: diameters.len(),
            diameter_m: d,
        })?;
        placed.push((x, d));
    }
    Ok(placed.into_iter().map(|(x, _)| x).collect())
}
