//! The funnel pour of f-EDEM §4.2 (Figs. 17–22): balls held in a funnel above a cylinder of paste
//! are released together, fall through air, enter the paste and stop, held by its yield stress.
//! Repeated with different random initial placements (f-EDEM: 15 repeats) to give presence
//! probabilities on horizontal planes.
//!
//! # Scene (3D, z up, origin at the centre of the cylinder bottom)
//! - The table and the cylinder bottom: one half-space z ≥ 0 (nothing can pass through it).
//! - The cylinder wall, inner radius R = `container.diameter_m`/2, from z = 0 to
//!   `funnel.wall_above_surface_m` (default 0) above the paste surface z = H =
//!   `container.height_m` (f-EDEM's mould is as high as its paste): `funnel.facets` boxes
//!   of thickness `funnel.wall_thickness_m` whose inner faces make a regular polygon circumscribing
//!   the circle of radius R.
//! - The funnel, coaxial, its outlet `funnel.outlet_above_surface_m` above the paste surface: a
//!   cone frustum (`outlet_diameter_m` at the bottom, `top_diameter_m` at `cone_height_m` above)
//!   made of `facets` tilted boxes (a pyramid circumscribing the cone), and above it a vertical
//!   column of height `column_height_m` (boxes at the top radius) to make room for the balls.
//! - A plug: a box closing the outlet from below, removed at t = 0.
//! - Every collider has the `[contacts]` restitution and friction; every contact feels the
//!   rolling resistance `contacts.rolling_resistance` (torque −μ_r r Σ|F_n| ω̂, see
//!   [`crate::engine::dim3::World::set_rolling_resistance`]).
//! - The paste fills the cylinder below z = H: fluid forces (buoyancy, `drag.law`) act only there
//!   ([`crate::engine::dim3::World::set_free_surface`]), from the moment a ball's lowest point
//!   passes the surface (`fluid.submergence = "full"`, f-EDEM) or on the immersed cap
//!   (`"partial"`). A ball at rest in paste is held by the yield stress until pushed harder than
//!   its static resistance (see [`crate::engine::dim3::World::set_yield_hold`]).
//!
//! # Run of one repeat
//! Ball i (diameter and density of `[[spheres]]` entry i mod n) is placed at random (ChaCha8,
//! seed `repeats.seed` + repeat index) in the funnel and column, clear of the walls, the plug and
//! the other balls by 5 % of its diameter; the balls fall onto the plug and settle for
//! `funnel.fill_time_s`; the plug is removed at t = 0 and the run goes on to `time.end_s`, or
//! stops earlier once t ≥ `count_time_s` and every ball has been slower than
//! `funnel.rest_speed_m_s` for 0.05 s. Repeats run in parallel (rayon).
//!
//! # Where a ball is (centre position)
//! `paste`: within the cylinder radius, its lowest point below the paste surface (z − r ≤ H: the
//! fluid forces act on it with full submergence). `funnel`: above the outlet minus one radius,
//! within the funnel's top radius. `falling`: between the two, within the funnel's top radius.
//! `outside`: anywhere else in the domain (escaped over the rim, beside the cylinder). `away`: out
//! of the domain (the cylinder about the axis 0.1 m beyond the scene, z from −d to 0.1 m above
//! the column) after escaping over the rim. `lost`: passed through a wall, the funnel or the
//! floor (its centre crossed the cylinder's radius more than d/4 below the rim, or got beyond a
//! funnel wall's outer face, or below z = 0), or non-finite. Checked every step.

use crate::dynamics::Unstable;
use crate::engine::{dim3, EngineSettings};
use crate::output::StagedDir;
use crate::run::{Prepared, RunContext, RunError, SceneReport};
use crate::scenario::{Contacts, FunnelSpec, Repeats, Scenario};
use crate::scenes::sphere_drag;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rapier3d_f64::math::{Pose, Rotation, Vector as RVector};
use rapier3d_f64::prelude::{ColliderBuilder, ColliderHandle};
use std::time::Instant;

/// Time over which every ball must stay slower than `rest_speed_m_s` before a run stops early, s.
pub const REST_WINDOW_S: f64 = 0.05;
/// Clearance of the random initial placement, as a fraction of the ball's diameter.
pub const PLACEMENT_GAP: f64 = 0.05;
/// Margin of the domain beyond the scene's bounding box, m.
pub const DOMAIN_MARGIN_M: f64 = 0.1;
/// Default interval of the time series when `record.every_s` is not set, s.
pub const DEFAULT_RECORD_EVERY_S: f64 = 0.01;

/// Geometry of the scene, SI units, derived from the scenario (see the module doc).
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
    /// The geometry of a validated `funnel_pour` scenario.
    pub fn of(s: &Scenario) -> Self {
        let f = funnel(s);
        let c = s
            .container
            .as_ref()
            .expect("validated: funnel_pour has a container");
        let h = c.height_m;
        let outlet_z = h + f.outlet_above_surface_m;
        let (r_out, r_top) = (0.5 * f.outlet_diameter_m, 0.5 * f.top_diameter_m);
        Self {
            cylinder_radius_m: 0.5 * c.diameter_m.expect("validated: cylinder"),
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

/// Where a ball is (see the module doc).
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
pub enum Place {
    /// In the paste (centre in the cylinder, below the surface).
    Paste,
    /// Between the funnel and the paste.
    Falling,
    /// Still in the funnel.
    Funnel,
    /// Beside the cylinder, in the domain (escaped over the rim).
    Outside,
    /// Out of the domain, after escaping over the rim.
    Away,
    /// Through a wall, the funnel or the floor, or non-finite.
    Lost,
}

impl Place {
    /// CSV label.
    pub fn label(self) -> &'static str {
        match self {
            Self::Paste => "paste",
            Self::Falling => "falling",
            Self::Funnel => "funnel",
            Self::Outside => "outside",
            Self::Away => "away",
            Self::Lost => "lost",
        }
    }
}

/// Numbers of balls in each place.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Census {
    /// In the paste.
    pub paste: usize,
    /// Falling between funnel and paste.
    pub falling: usize,
    /// In the funnel.
    pub funnel: usize,
    /// Beside the cylinder.
    pub outside: usize,
    /// Out of the domain (over the rim).
    pub away: usize,
    /// Through a wall or non-finite.
    pub lost: usize,
}

impl Census {
    /// Counts the places of the balls.
    pub fn of(places: impl IntoIterator<Item = Place>) -> Self {
        let mut c = Self::default();
        for p in places {
            match p {
                Place::Paste => c.paste += 1,
                Place::Falling => c.falling += 1,
                Place::Funnel => c.funnel += 1,
                Place::Outside => c.outside += 1,
                Place::Away => c.away += 1,
                Place::Lost => c.lost += 1,
            }
        }
        c
    }

    /// Balls in the domain (all but the away and lost ones).
    pub fn in_domain(&self) -> usize {
        self.paste + self.falling + self.funnel + self.outside
    }
}

/// One row of a repeat's time series.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Sample {
    /// Time since the outlet opened, s (negative while the balls settle in the funnel).
    pub time_s: f64,
    /// Where the balls are.
    pub census: Census,
    /// Largest ball speed, m/s.
    pub max_speed_m_s: f64,
}

/// One ball at the end of a repeat.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Ball {
    /// Diameter, m.
    pub diameter_m: f64,
    /// Centre (x, y, z), m; z above the cylinder bottom.
    pub position_m: [f64; 3],
    /// Speed, m/s.
    pub speed_m_s: f64,
    /// Where it is.
    pub place: Place,
}

/// Result of one repeat.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RepeatResult {
    /// Repeat index (0-based).
    pub index: usize,
    /// Seed of the initial placement.
    pub seed: u64,
    /// The balls at the end.
    pub balls: Vec<Ball>,
    /// Where the balls were at `count_time_s` (None if the run ended before).
    pub census_at_count: Option<Census>,
    /// Largest ball speed when the outlet opened, m/s (how well they had settled).
    pub max_speed_at_opening_m_s: f64,
    /// Time since opening at which the run ended, s.
    pub end_time_s: f64,
    /// Steps taken (fill included).
    pub steps: u64,
    /// Wall time of this repeat, s.
    pub wall_time_s: f64,
    /// Time series (every `record.every_s`, default 0.01 s).
    pub samples: Vec<Sample>,
}

impl RepeatResult {
    /// Where the balls are at the end.
    pub fn census(&self) -> Census {
        Census::of(self.balls.iter().map(|b| b.place))
    }

    /// Lowest and highest centre height of the balls in the paste, m (None if none is).
    pub fn z_range_m(&self) -> Option<(f64, f64)> {
        z_range(self.balls.iter())
    }
}

/// Lowest and highest centre height of the balls in the paste among `balls`, m.
pub fn z_range<'a>(balls: impl Iterator<Item = &'a Ball>) -> Option<(f64, f64)> {
    balls
        .filter(|b| b.place == Place::Paste)
        .map(|b| b.position_m[2])
        .fold(None, |acc, z| match acc {
            None => Some((z, z)),
            Some((lo, hi)) => Some((lo.min(z), hi.max(z))),
        })
}

fn funnel(s: &Scenario) -> &FunnelSpec {
    s.funnel
        .as_ref()
        .expect("validated: funnel_pour has a [funnel] table")
}

fn contacts(s: &Scenario) -> &Contacts {
    s.contacts
        .as_ref()
        .expect("validated: funnel_pour has a [contacts] table")
}

/// The repeats of a scenario (default: one, seed 0).
pub fn repeats(s: &Scenario) -> Repeats {
    s.repeats.clone().unwrap_or(Repeats { count: 1, seed: 0 })
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

/// Random initial centres of the balls of diameters `diameters` in the funnel and column, clear
/// of the walls, the plug and each other by [`PLACEMENT_GAP`] × d. Errors if a ball cannot be
/// placed in 100 000 tries.
pub fn place_balls(geo: &Geometry, diameters: &[f64], seed: u64) -> Result<Vec<[f64; 3]>, String> {
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
        let x = ok.ok_or_else(|| {
            format!(
                "cannot place ball {i} of {} (d = {d} m) in the funnel at random: raise funnel.column_height_m or top_diameter_m",
                diameters.len()
            )
        })?;
        placed.push((x, d));
    }
    Ok(placed.into_iter().map(|(x, _)| x).collect())
}

/// Everything a repeat needs to continue from where it is: saved in its checkpoint (part
/// `repeat<i>`, see [`crate::checkpoint`]).
#[derive(serde::Serialize, serde::Deserialize)]
struct RepeatState {
    world: dim3::World,
    ids: Vec<crate::engine::BodyId>,
    diameters: Vec<f64>,
    plug: ColliderHandle,
    /// Positions at the end of the last step (for the wall-breach test).
    prev: Vec<[f64; 3]>,
    /// Balls that went through a wall.
    breached: Vec<bool>,
    samples: Vec<Sample>,
    census_at_count: Option<Census>,
    max_speed_at_opening: f64,
    /// Step since which every ball in play is slower than the rest speed.
    rest_since: Option<u64>,
    /// Steps taken.
    k: u64,
    /// Wall time spent before the last resumption, s.
    wall_before_s: f64,
}

/// How a repeat ended.
pub enum RepeatOutcome {
    /// It ran to its end.
    Done(RepeatResult),
    /// Ctrl-C/SIGTERM stopped it (its state is in the checkpoint, if checkpoints are on).
    Interrupted,
}

/// Runs repeat `index` (seed `seed`) of a funnel pour from its start.
pub fn run_repeat(p: &Prepared, index: usize, seed: u64) -> Result<RepeatResult, RunError> {
    match run_repeat_with(p, index, seed, &RunContext::default())? {
        RepeatOutcome::Done(r) => Ok(r),
        RepeatOutcome::Interrupted => Err(RunError::Interrupted(p.path.clone())),
    }
}

/// The state of repeat `index` (seed `seed`) at t = 0: the world built, the balls placed.
fn initial_repeat(p: &Prepared, seed: u64) -> Result<RepeatState, RunError> {
    let s = &p.scenario;
    let f = funnel(s);
    let ct = contacts(s);
    let geo = Geometry::of(s);
    let g = s.gravity_m_s2;
    let n = f.count;
    let specs: Vec<_> = (0..n)
        .map(|i| &p.spheres[i % p.spheres.len()].spec)
        .collect();
    let diameters: Vec<f64> = specs.iter().map(|sp| sp.diameter_m).collect();
    let d_min = diameters.iter().copied().fold(f64::INFINITY, f64::min);
    let centres = place_balls(&geo, &diameters, seed)
        .map_err(|m| RunError::Other(format!("{}: {m}", p.path.display())))?;

    // Free fall from the top of the column to the bottom bounds every speed of the scene.
    let v_max = (2.0 * g * geo.column_top_z_m).sqrt();
    let mut settings = EngineSettings::for_scene(d_min, v_max);
    settings.friction = ct.friction;
    let mut world = dim3::World::new(settings, g);
    world.add_floor(0.0);
    let (e, mu) = (ct.restitution, ct.friction);
    let mut faces = ring(&geo, geo.cylinder_radius_m, 0.0, geo.wall_top_z_m, e, mu);
    faces.extend(cone(&geo, e, mu));
    if geo.column_top_z_m > geo.cone_top_z_m {
        faces.extend(ring(
            &geo,
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
    let plug = world.add_fixed_collider(
        ColliderBuilder::cuboid(plug_half, plug_half, 0.5 * t)
            .translation(RVector::new(0.0, 0.0, geo.outlet_z_m - 0.5 * t))
            .restitution(e)
            .friction(mu),
    );
    let ids: Vec<_> = specs
        .iter()
        .zip(&centres)
        .map(|(sp, x)| {
            world.add_sphere(dim3::FluidBody::at_rest(
                dim3::Vector::new(x[0], x[1], x[2]),
                sp.diameter_m,
                sp.density_kg_m3,
                sphere_drag(s, sp.diameter_m),
                g,
            ))
        })
        .collect();
    world.set_restitution_law(ct.restitution_law());
    world.set_rolling_resistance(ct.rolling_resistance);
    world.set_free_surface(dim3::FreeSurface {
        height_m: geo.paste_height_m,
        radius_m: Some(geo.cylinder_radius_m),
        submergence: s.fluid.submergence,
    });

    let position = |id| -> [f64; 3] {
        let x = world.position_m(id);
        [x[0], x[1], x[2]]
    };
    let prev: Vec<[f64; 3]> = ids.iter().map(|&id| position(id)).collect();
    Ok(RepeatState {
        breached: vec![false; n],
        prev,
        world,
        ids,
        diameters,
        plug,
        samples: Vec::new(),
        census_at_count: None,
        max_speed_at_opening: 0.0,
        rest_since: None,
        k: 0,
        wall_before_s: 0.0,
    })
}

/// [`run_repeat`] with checkpoints and resumption as `ctx` says: continues from the repeat's
/// checkpoint when resuming, saves its state every checkpoint period and when interrupted, and
/// saves its result (part `repeat<i>.done`) once finished, so that a resumed run does not redo
/// it.
pub fn run_repeat_with(
    p: &Prepared,
    index: usize,
    seed: u64,
    ctx: &RunContext,
) -> Result<RepeatOutcome, RunError> {
    let wall = Instant::now();
    let s = &p.scenario;
    let part = format!("repeat{index}");
    let done_part = format!("repeat{index}.done");
    let saved = match (&ctx.checkpoints, ctx.resume) {
        (Some(c), true) => {
            if let Some(r) = c
                .load::<RepeatResult>(&s.name, &done_part)
                .map_err(RunError::Other)?
            {
                return Ok(RepeatOutcome::Done(r));
            }
            c.load::<RepeatState>(&s.name, &part)
                .map_err(RunError::Other)?
        }
        _ => None,
    };
    let mut state = match saved {
        Some(st) => st,
        None => initial_repeat(p, seed)?,
    };
    let save = |state: &mut RepeatState| -> Result<(), RunError> {
        if let Some(c) = &ctx.checkpoints {
            let before = state.wall_before_s;
            state.wall_before_s += wall.elapsed().as_secs_f64();
            let r = c.save(&s.name, &part, &*state);
            state.wall_before_s = before;
            r.map_err(|e| RunError::Io(p.path.clone(), e))?;
        }
        Ok(())
    };
    let mut timer = ctx.checkpoints.as_ref().map(|c| c.timer());
    let f = funnel(s);
    let geo = Geometry::of(s);
    let dt = s.time.dt_s;
    let n_fill = (f.fill_time_s / dt).round() as u64;
    let n_run = (s.time.end_s / dt).round().max(1.0) as u64;
    let count_step = f.count_time_s.map(|tc| n_fill + (tc / dt).round() as u64);
    let every = ((s.record.every_s.unwrap_or(DEFAULT_RECORD_EVERY_S) / dt).round() as u64).max(1);
    let rest_steps = (REST_WINDOW_S / dt).round() as u64;
    let position = |world: &dim3::World, id| -> [f64; 3] {
        let x = world.position_m(id);
        [x[0], x[1], x[2]]
    };
    let ids = state.ids.clone();
    let diameters = state.diameters.clone();
    // Places of the balls and the largest speed of those still in play (in the paste, falling or
    // in the funnel: balls that escaped over the rim do not hold the run).
    let observe = |world: &dim3::World, breached: &[bool]| -> (Vec<Place>, f64) {
        let mut vmax: f64 = 0.0;
        let places = ids
            .iter()
            .zip(&diameters)
            .zip(breached)
            .map(|((&id, &d), &lost)| {
                let place = if lost {
                    Place::Lost
                } else {
                    geo.place(&position(world, id), d)
                };
                if matches!(place, Place::Paste | Place::Falling | Place::Funnel) {
                    vmax = vmax.max(world.velocity_m_s(id).norm());
                }
                place
            })
            .collect();
        (places, vmax)
    };
    let time_of = |k: u64| (k as f64 - n_fill as f64) * dt;
    let tag = |u: Unstable| {
        let mut u = u;
        u.body = format!("repeat {index} (seed {seed}) {}", u.body);
        RunError::Unstable(p.path.clone(), u)
    };
    while state.k < n_fill + n_run {
        if crate::interrupt::requested() {
            save(&mut state)?;
            return Ok(RepeatOutcome::Interrupted);
        }
        if timer.as_mut().is_some_and(|t| t.due()) {
            save(&mut state)?;
        }
        let RepeatState {
            world,
            breached,
            prev,
            k,
            max_speed_at_opening,
            plug,
            samples,
            census_at_count,
            rest_since,
            ..
        } = &mut state;
        if *k == n_fill {
            *max_speed_at_opening = observe(world, breached).1;
            world.remove_fixed_collider(*plug);
        }
        world.step(dt, s.time.integrator).map_err(tag)?;
        *k += 1;
        let k = *k;
        for ((&id, &d), (from, lost)) in ids
            .iter()
            .zip(&diameters)
            .zip(prev.iter_mut().zip(breached.iter_mut()))
        {
            let to = position(world, id);
            *lost = *lost || geo.breached(from, &to, d) || !to.iter().all(|c| c.is_finite());
            *from = to;
        }
        let sample_now = k.is_multiple_of(every);
        let count_now = count_step == Some(k);
        let after_count = count_step.is_none_or(|c| k >= c) && k > n_fill;
        if !(sample_now || count_now || after_count) {
            continue;
        }
        let (places, vmax) = observe(world, breached);
        let census = Census::of(places.iter().copied());
        if sample_now {
            samples.push(Sample {
                time_s: time_of(k),
                census,
                max_speed_m_s: vmax,
            });
        }
        if count_now {
            *census_at_count = Some(census);
        }
        if after_count {
            if vmax < f.rest_speed_m_s {
                let since = *rest_since.get_or_insert(k);
                if k - since >= rest_steps {
                    break;
                }
            } else {
                *rest_since = None;
            }
        }
    }
    let world = &state.world;
    let places = observe(world, &state.breached).0;
    let balls = ids
        .iter()
        .zip(&diameters)
        .zip(places)
        .map(|((&id, &d), place)| Ball {
            diameter_m: d,
            position_m: position(world, id),
            speed_m_s: world.velocity_m_s(id).norm(),
            place,
        })
        .collect();
    let result = RepeatResult {
        index,
        seed,
        balls,
        census_at_count: state.census_at_count,
        max_speed_at_opening_m_s: state.max_speed_at_opening,
        end_time_s: time_of(state.k),
        steps: state.k,
        wall_time_s: state.wall_before_s + wall.elapsed().as_secs_f64(),
        samples: std::mem::take(&mut state.samples),
    };
    if let Some(c) = &ctx.checkpoints {
        c.save(&s.name, &done_part, &result)
            .map_err(|e| RunError::Io(p.path.clone(), e))?;
    }
    Ok(RepeatOutcome::Done(result))
}

/// Runs every repeat of a funnel pour in parallel (rayon); results in repeat order.
pub fn simulate(p: &Prepared) -> Result<Vec<RepeatResult>, RunError> {
    let (results, interrupted) = simulate_with(p, &RunContext::default())?;
    if interrupted {
        return Err(RunError::Interrupted(p.path.clone()));
    }
    Ok(results)
}

/// [`simulate`] with checkpoints, resumption and progress as `ctx` says. Returns the finished
/// repeats in repeat order, and whether Ctrl-C/SIGTERM stopped some (they are then missing).
pub fn simulate_with(
    p: &Prepared,
    ctx: &RunContext,
) -> Result<(Vec<RepeatResult>, bool), RunError> {
    use rayon::prelude::*;
    let r = repeats(&p.scenario);
    let bar = crate::progress::bar(r.count as u64, &p.scenario.name, "repeats,", ctx.quiet);
    let outcomes: Vec<RepeatOutcome> = (0..r.count)
        .into_par_iter()
        .map(|i| {
            let o = run_repeat_with(p, i, r.seed.wrapping_add(i as u64), ctx);
            bar.inc(1);
            o
        })
        .collect::<Result<_, _>>()?;
    bar.finish_and_clear();
    let mut interrupted = false;
    let mut results = Vec::new();
    for o in outcomes {
        match o {
            RepeatOutcome::Done(r) => results.push(r),
            RepeatOutcome::Interrupted => interrupted = true,
        }
    }
    Ok((results, interrupted))
}

/// Funnel pour (kind `funnel_pour`): runs the repeats, writes `balls.csv`, `counts.csv`,
/// `timeseries.csv`, `z_distribution.csv` + `.svg` and `presence.csv` + `.svg` (see
/// [`crate::output::funnel`]). Interrupted, it writes the repeats that finished.
pub fn run(p: &Prepared, stage: &StagedDir, ctx: &RunContext) -> Result<SceneReport, RunError> {
    let s = &p.scenario;
    let t0 = Instant::now();
    let (results, interrupted) = simulate_with(p, ctx)?;
    if results.is_empty() {
        return Ok(SceneReport {
            interrupted,
            lines: vec!["interrupted before any repeat finished".into()],
            ..SceneReport::default()
        });
    }
    let wall = t0.elapsed().as_secs_f64();
    crate::output::funnel::write_all(p, &results, stage)?;
    let geo = Geometry::of(s);
    let f = funnel(s);
    let n = f.count;
    let reps = results.len();
    let d_min = p
        .spheres
        .iter()
        .map(|c| c.spec.diameter_m)
        .fold(f64::INFINITY, f64::min);
    let v_max = (2.0 * s.gravity_m_s2 * geo.column_top_z_m).sqrt();
    let mut settings = EngineSettings::for_scene(d_min, v_max);
    settings.friction = contacts(s).friction;

    let mut lines = Vec::new();
    let per_repeat: Vec<f64> = results.iter().map(|r| r.wall_time_s).collect();
    let mean_wall = per_repeat.iter().sum::<f64>() / reps as f64;
    lines.push(format!(
        "funnel pour: {reps} repeat(s) × {n} balls, dt = {:e} s, {} submergence; wall time {wall:.1} s ({mean_wall:.1} s per repeat, {} threads)",
        s.time.dt_s,
        match s.fluid.submergence {
            crate::scenario::Submergence::Full => "full",
            crate::scenario::Submergence::Partial => "partial",
        },
        rayon::current_num_threads()
    ));
    if let Some(tc) = f.count_time_s {
        let counted: Vec<Census> = results.iter().filter_map(|r| r.census_at_count).collect();
        if !counted.is_empty() {
            let rng = |f: &dyn Fn(&Census) -> usize| {
                let lo = counted.iter().map(f).min().unwrap_or(0);
                let hi = counted.iter().map(f).max().unwrap_or(0);
                if lo == hi {
                    format!("{lo}")
                } else {
                    format!("{lo}–{hi}")
                }
            };
            lines.push(format!(
                "at t = {tc} s: {} of {n} balls in the paste, {} in the domain (f-EDEM Fig. 20: N = 68 for dt ≤ 1.04e-5 s)",
                rng(&|c| c.paste),
                rng(&|c| c.in_domain())
            ));
        }
    }
    let finals: Vec<Census> = results.iter().map(|r| r.census()).collect();
    let sum = |f: &dyn Fn(&Census) -> usize| finals.iter().map(f).sum::<usize>();
    lines.push(format!(
        "at the end: {} of {} balls in the paste; {} still in the funnel, {} falling, {} escaped over the rim ({} beside the cylinder, {} out of the domain), {} lost through a wall",
        sum(&|c| c.paste),
        n * reps,
        sum(&|c| c.funnel),
        sum(&|c| c.falling),
        sum(&|c| c.outside + c.away),
        sum(&|c| c.outside),
        sum(&|c| c.away),
        sum(&|c| c.lost)
    ));
    let mut zs: Vec<f64> = results
        .iter()
        .flat_map(|r| r.balls.iter())
        .filter(|b| b.place == Place::Paste)
        .map(|b| b.position_m[2])
        .collect();
    zs.sort_by(f64::total_cmp);
    if !zs.is_empty() {
        let q = |f: f64| zs[((zs.len() - 1) as f64 * f).round() as usize] * 100.0;
        lines.push(format!(
            "ball centres in the paste at Z = {:.2}–{:.2} cm above the bottom (5–95 %: {:.2}–{:.2} cm, median {:.2} cm; f-EDEM Fig. 21: 8.5–13.5 cm)",
            q(0.0),
            q(1.0),
            q(0.05),
            q(0.95),
            q(0.5)
        ));
    }
    let slowest_fill = results
        .iter()
        .map(|r| r.max_speed_at_opening_m_s)
        .fold(0.0, f64::max);
    lines.push(format!(
        "largest ball speed when the outlet opened: {slowest_fill:.2e} m/s; runs ended at t = {:.3}–{:.3} s",
        results.iter().map(|r| r.end_time_s).fold(f64::INFINITY, f64::min),
        results.iter().map(|r| r.end_time_s).fold(0.0, f64::max)
    ));
    Ok(SceneReport {
        steps: results.iter().map(|r| r.steps).sum(),
        bodies: n * reps,
        engine_settings: Some(settings),
        lines,
        interrupted,
    })
}
