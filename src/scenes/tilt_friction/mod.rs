//! Tilt test (kind `tilt_friction`, f-EDEM App. III): a block on a tilted plate, to calibrate the
//! sliding friction coefficient.
//!
//! # Scene
//!
//! A cuboid block rests on a fixed horizontal plate (a half-space) and gravity is tilted by the
//! angle θ about the y axis, `g (sin θ, 0, −cos θ)`: in the plate's frame this is the tilted plate
//! of the test. This scene uses a bare Rapier 3D world (our [`World`] holds spheres only); its
//! integration parameters are set from [`EngineSettings`] as [`World::new`] does. The block has no
//! fluid forces: buoyancy scales the normal and tangential loads alike and drag acts only once the
//! block moves, so neither shifts the threshold.
//!
//! # Equations
//!
//! After `duration_s` the displacement along the slope decides: the block slides if it moved more
//! than `slide_distance_m` ([`simulate_tilt`]). A block on a plane tilted by θ sticks while
//! tan θ ≤ μ (Coulomb), so the sticking threshold is `atan(contacts.friction)`. The angles given
//! bracket the threshold; it is then bisected to `bisection_tolerance_deg` ([`tilt_threshold`]).
//!
//! # Limits
//!
//! Rapier has a single Coulomb friction coefficient per collider (static = dynamic): the test
//! measures that one coefficient, not a static and a dynamic one.
//!
//! # Files
//!
//! `summary.csv` (one row per angle run, the given angles and the bisection's), `threshold.csv`
//! and `tilt_displacement.svg` (see [`output`]).

pub mod cost;
pub mod output;
pub mod search;
pub mod setup;
pub mod simulate;

pub use search::{tilt_threshold, TiltSearch};
pub use setup::TiltSetup;
pub use simulate::{simulate_tilt, TiltError, TiltOutcome};

#[cfg(doc)]
use crate::engine::dim3::World;
#[cfg(doc)]
use crate::engine::EngineSettings;
use crate::error::Error;
use crate::io::fmt::{g, short};
use crate::io::Outputs;
use crate::scenario::TiltFrictionSpec;
use crate::scenes::{Prepared, SceneReport};

/// [`g`] with a `+` on positive values.
fn signed(x: f64) -> String {
    let s = g(x);
    if x > 0.0 && s != "0" {
        format!("+{s}")
    } else {
        s
    }
}

/// Console lines: one per given angle, then the threshold against atan(μ) = `expected_deg`.
fn lines(
    runs: &[TiltOutcome],
    bracket: Option<(f64, f64)>,
    friction: f64,
    expected_deg: f64,
) -> Vec<String> {
    let mut lines: Vec<String> = runs
        .iter()
        .filter(|r| !r.bisection)
        .map(|r| {
            format!(
                "θ = {}°: displacement {} m, {}",
                short(r.angle_deg),
                g(r.displacement_m),
                if r.slides { "slides" } else { "sticks" }
            )
        })
        .collect();
    lines.push(match bracket {
        Some((lo, hi)) => format!(
            "threshold {}° (sticks at {}°, slides at {}°); atan(μ = {}) = {}°, \
             error {}° (Rapier: one friction coefficient, static = dynamic)",
            g(0.5 * (lo + hi)),
            g(lo),
            g(hi),
            short(friction),
            g(expected_deg),
            signed(0.5 * (lo + hi) - expected_deg)
        ),
        None => format!(
            "threshold not bracketed by the angles given (need a sticking angle below a sliding \
             one); atan(μ = {}) = {}°",
            short(friction),
            g(expected_deg)
        ),
    });
    lines
}

/// Tilt friction (kind `tilt_friction`): runs the threshold search and adds `summary.csv`,
/// `threshold.csv` and `tilt_displacement.svg` to `out`.
pub fn run(p: &Prepared, tf: &TiltFrictionSpec, out: &mut Outputs) -> Result<SceneReport, Error> {
    let s = &p.common;
    let spec = &tf.tilt;
    let setup = TiltSetup::new(s, tf);
    let search = tilt_threshold(&setup, &spec.angles_deg, spec.bisection_tolerance_deg).map_err(
        |e| match e {
            TiltError::Unstable(u) => Error::Unstable(p.path.clone(), u),
            TiltError::Interrupted => Error::InterruptedUnwritten(p.path.clone()),
        },
    )?;
    let found = search.threshold_deg();
    let TiltSearch { runs, bracket } = search;
    let expected = setup.friction.atan().to_degrees();

    out.table(output::summary_table(&runs));
    out.table(output::threshold_table(
        setup.friction,
        expected,
        found,
        bracket,
    ));
    let title = format!(
        "{}: displacement down the slope after {} s",
        s.name, spec.duration_s
    );
    out.chart(
        "tilt_displacement.svg",
        &output::chart(&title, &runs, expected),
    )
    .map_err(|e| Error::Io(p.path.clone(), e))?;

    Ok(SceneReport {
        warnings: Vec::new(),
        steps: runs.len() as u64 * setup.steps(),
        bodies: runs.len(),
        engine_settings: Some(setup.settings),
        lines: lines(&runs, bracket, setup.friction, expected),
        interrupted: false,
        reached_s: None,
    })
}

#[cfg(test)]
mod tests;
