//! One drop of the restitution scene: the ball falls from rest onto the plate in a Rapier 3D
//! [`World`] and is followed to the apex of its first bounce (see the [module doc](super)).

use super::setup::Setup;
use crate::engine::dim3::{up, FluidBody, World};
use crate::engine::{EngineSettings, Unstable};
use crate::scenario::Common;

/// Result of one drop.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DropOutcome {
    /// Drop height of the ball's lowest point above the plate, m.
    pub drop_height_m: f64,
    /// Apex of the lowest point above the plate after the first bounce, m.
    pub rebound_height_m: f64,
    /// Speed of the ball when it reaches the plate, m/s.
    pub impact_speed_m_s: f64,
    /// Upward speed of the ball when it leaves the plate, m/s.
    pub lift_off_speed_m_s: f64,
    /// Lift-off speed / impact speed: the restitution the contact achieved.
    pub restitution_effective: f64,
    /// Steps taken.
    pub steps: u64,
}

/// Drops the ball of `setup` from `drop_height_m` (lowest point above the plate) in the
/// scenario's fluid with the setup's restitution law, the scenario's added mass (`[transient]`)
/// and the scenario's time step and integrator, and returns the first rebound. Errors with the
/// engine's [`Unstable`], or with a message when no apex is reached within `time.end_s`.
pub fn simulate_drop(
    s: &Common,
    setup: &Setup,
    drop_height_m: f64,
    settings: EngineSettings,
) -> Result<DropOutcome, DropError> {
    let g = s.gravity_m_s2;
    let dt = s.time.dt_s;
    let ball = setup.ball;
    let d = ball.diameter_m;
    let r = 0.5 * d;
    let restitution = setup.law;
    let mut world = World::new(settings, g);
    world.add_floor(0.0);
    let id = world.add_sphere(FluidBody::at_rest(
        up() * (drop_height_m + r),
        d,
        ball.density_kg_m3,
        s.sphere_drag(d),
        g,
    ));
    world.set_restitution_law(restitution);
    world.set_added_mass_coefficient(s.added_mass_coefficient());

    let max_steps = (s.time.end_s / dt).ceil() as u64;
    let mut steps = 0u64;
    // Falling: the fastest descent seen (at the start of the impact step) and the height of the
    // lowest point then. Rising: the fastest ascent seen (at the end of the step that releases
    // the ball) and its height, then the last state still rising.
    let mut fall = (0.0f64, drop_height_m);
    let mut lift_off: Option<(f64, f64)> = None;
    let mut last_rising = (0.0f64, 0.0f64);
    let mut landed = false;
    while steps < max_steps {
        // Ctrl-C within about a second: a check every 4096 steps (a few ms of Rapier).
        if steps.is_multiple_of(4096) && crate::interrupt::requested() {
            return Err(DropError::Interrupted);
        }
        let (z0, vz0) = (world.position_m(id)[2] - r, world.velocity_m_s(id)[2]);
        world.step(dt, s.time.integrator)?;
        steps += 1;
        let (z, vz) = (world.position_m(id)[2] - r, world.velocity_m_s(id)[2]);
        match lift_off {
            None => {
                landed |= world.in_contact(id) && z < 0.01 * d;
                if -vz0 > fall.0 {
                    fall = (-vz0, z0.max(0.0));
                }
                if vz > 0.0 {
                    lift_off = Some((vz, z.max(0.0)));
                    last_rising = (vz, z);
                }
            }
            Some((v_out, _)) if vz > 0.0 => {
                if vz > v_out {
                    lift_off = Some((vz, z.max(0.0)));
                }
                last_rising = (vz, z);
            }
            Some((v_out, gap_out)) => {
                // Apex passed during this step: continue the last rising state ballistically
                // (the drag changes it by ~F_d dt/m, far below the step's own resolution).
                let (v, z_last) = last_rising;
                let apex = z_last + v * v / (2.0 * g);
                // Carry both speeds to the plate surface (free fall over the small gaps).
                let (v_in, gap_in) = fall;
                let impact_speed = (v_in * v_in + 2.0 * g * gap_in).sqrt();
                let lift_off_speed = (v_out * v_out + 2.0 * g * gap_out).sqrt();
                return Ok(DropOutcome {
                    drop_height_m,
                    rebound_height_m: apex.max(z).max(0.0),
                    impact_speed_m_s: impact_speed,
                    lift_off_speed_m_s: lift_off_speed,
                    restitution_effective: lift_off_speed / impact_speed,
                    steps,
                });
            }
        }
    }
    if landed && lift_off.is_none() {
        // No rebound at all (e = 0): the ball lies on the plate.
        let (v_in, gap_in) = fall;
        return Ok(DropOutcome {
            drop_height_m,
            rebound_height_m: 0.0,
            impact_speed_m_s: (v_in * v_in + 2.0 * g * gap_in).sqrt(),
            lift_off_speed_m_s: 0.0,
            restitution_effective: 0.0,
            steps,
        });
    }
    Err(DropError::NoApex {
        drop_height_m,
        end_s: s.time.end_s,
    })
}

/// Why a drop did not give a rebound.
#[derive(Debug)]
pub enum DropError {
    /// The engine went unstable.
    Unstable(Unstable),
    /// No apex after the bounce within `time.end_s` (too short), or the ball never reached the
    /// plate. A ball that lands and stays (e = 0) gives a rebound of 0, not this error.
    NoApex {
        /// The drop height, m.
        drop_height_m: f64,
        /// The scenario's `time.end_s`, s.
        end_s: f64,
    },
    /// Ctrl-C or SIGTERM ([`crate::interrupt::requested`]) during the drop: no result.
    Interrupted,
}

impl From<Unstable> for DropError {
    fn from(u: Unstable) -> Self {
        Self::Unstable(u)
    }
}

impl std::fmt::Display for DropError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Unstable(u) => write!(f, "{u}"),
            Self::NoApex {
                drop_height_m,
                end_s,
            } => write!(
                f,
                "the ball dropped from {drop_height_m} m reached no rebound apex within \
                 time.end_s = {end_s} s: raise time.end_s"
            ),
            Self::Interrupted => write!(f, "interrupted"),
        }
    }
}
