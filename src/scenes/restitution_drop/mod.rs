//! Restitution drop (kind `restitution_drop`, f-EDEM App. II): a ball dropped on a steel plate,
//! its rebound compared with the measured one.
//!
//! # Scene
//!
//! The scenario's single ball is dropped from rest, its lowest point `H` above a fixed plate
//! (a half-space), in a [`crate::engine::dim3::World`]: Rapier 3D contacts, the fluid's forces
//! (buoyancy and drag of the scenario's fluid, air) applied by the engine. The contact's
//! restitution is the scenario's law ([`RestitutionLaw`], `contacts.restitution`,
//! `restitution_exponent`, `restitution_reference_speed_m_s`) through
//! [`World::set_restitution_law`]: a constant e is set on every collider (Rapier averages the two
//! colliders' coefficients, so the contact gets exactly e; a plate left at 0 would halve it); a
//! speed-dependent one is set per contact manifold from the impact speed by a Rapier
//! contact-modification hook. The run stops at the apex after the first bounce; the rebound
//! height is the apex of the lowest point above the plate ([`simulate_drop`]).
//!
//! # Equations
//!
//! Reported per height ([`Comparison`]): the rebound height, its error against the measurement,
//! the ideal rebound `e(v)² H` (no air, v = √(2 g H), f-EDEM eq. A4), and the effective
//! restitution of the contact, the ratio of the lift-off to the impact speed. Both speeds are read
//! at the ends of the step that resolves the impact and carried ballistically to the plate
//! surface, so that the ratio is Rapier's contact restitution alone (air drag and the gravity of
//! the impact step do not enter it). At the scenario's dt = 1e-5 s it equals the law at the impact
//! speed within 1e-4; air drag lowers the rebound below e²H by 0.13 % (95 mm) to 0.46 % (398 mm).
//! A ball that lands and stays (e = 0) gives a rebound of 0.
//!
//! With `transient.added_mass` the ball's inertia is m_p + C_m m_f in the fall, the rise and the
//! contact, gravity staying m_p g ([`World::set_added_mass_coefficient`]); in air it moves the
//! rebound heights by less than 1e-4 relative.
//!
//! # Limits
//!
//! A constant coefficient cannot meet the "within 3 %" at all five heights of f-EDEM's
//! Table A2: the measured ratios H_r/H_f scatter from 0.3607 (252 mm) to 0.3895 (95 mm), so the
//! best any constant e² can do is 2 r_min r_max/(r_min + r_max), missing both ends by
//! (r_max − r_min)/(r_max + r_min) = 3.8 % ([`ConstantFit`]). The measured e falls with the
//! impact speed, and the power law fitted by [`RestitutionLaw::minimax_fit`] reaches 2.3 %
//! (2.7 % simulated, in air). `fit.csv` lists every model with its fitted error and its
//! leave-one-out (predictive) error ([`restitution_fits`]).
//!
//! # Files
//!
//! `summary.csv` (one row per drop height), `fit.csv` (the restitution models calibrated on the
//! measurements, when given) and `rebound_height.svg` (see [`output`]).
//!
//! # Layout
//!
//! [`setup`] (the Rapier settings of the scene), [`simulate`] (one drop to its first apex),
//! [`output`] (the files); and for this kind [`fit`] (the measured against the simulated
//! rebounds).

pub mod cost;
pub mod fit;
pub mod output;
pub mod setup;
pub mod simulate;

pub use fit::{Comparison, Tally};
pub use setup::{drop_settings, Setup};
pub use simulate::{simulate_drop, DropError, DropOutcome};

#[cfg(doc)]
use crate::contact::ConstantFit;
#[cfg(doc)]
use crate::contact::RestitutionLaw;
use crate::contact::{restitution_fits, LawFit};
#[cfg(doc)]
use crate::engine::dim3::World;
use crate::engine::EngineSettings;
use crate::error::Error;
use crate::io::Outputs;
use crate::scenario::RestitutionSpec;
use crate::scenes::{Prepared, SceneReport};

/// Drops the ball from every height of the setup, in order.
fn simulate_all(
    p: &Prepared,
    setup: &Setup,
    settings: EngineSettings,
) -> Result<Vec<DropOutcome>, Error> {
    setup
        .spec
        .drop_heights_m
        .iter()
        .map(|&h| {
            simulate_drop(&p.common, setup, h, settings).map_err(|err| match err {
                DropError::Unstable(u) => Error::Unstable(p.path.clone(), u),
                DropError::Interrupted => Error::InterruptedUnwritten(p.path.clone()),
                other @ DropError::NoApex { .. } => {
                    Error::bad_input(&p.path, Some("time.end_s"), other.to_string())
                }
            })
        })
        .collect()
}

/// Console lines on the calibrated models: the simulated tally, then one line per model.
fn fit_lines(tally: &Tally, heights: usize, tolerance: f64, fits: &[LawFit]) -> Vec<String> {
    use crate::io::fmt::{g, short};
    let mut lines = vec![format!(
        "{}/{heights} heights within {} % of the measurements (worst {} %)",
        tally.within,
        short(tolerance * 1e2),
        g(tally.worst * 1e2),
    )];
    lines.extend(fits.iter().map(|f| {
        format!(
            "  {:<24} e_ref = {}, k = {}: worst {} % (vacuum){}",
            f.model,
            g(f.law.coefficient),
            g(f.law.exponent),
            g(f.max_rel_error * 1e2),
            f.leave_one_out_max_rel_error
                .map(|x| format!(", leave-one-out {} %", g(x * 1e2)))
                .unwrap_or_default(),
        )
    }));
    lines
}

/// Restitution drop (kind `restitution_drop`): drops the ball from every height and adds
/// `summary.csv`, `fit.csv` (when measurements are given) and `rebound_height.svg` to `out`.
pub fn run(p: &Prepared, rd: &RestitutionSpec, out: &mut Outputs) -> Result<SceneReport, Error> {
    let s = &p.common;
    let setup = Setup::of(rd);
    let spec = setup.spec;
    let g = s.gravity_m_s2;
    let settings = drop_settings(s, &setup, setup.max_drop_height_m());
    let outcomes = simulate_all(p, &setup, settings)?;
    let rows: Vec<Comparison> = outcomes
        .iter()
        .enumerate()
        .map(|(i, o)| {
            let measured = spec.measured_rebound_heights_m.get(i).copied();
            Comparison::of(o, &setup.law, g, measured)
        })
        .collect();
    out.table(output::summary_table(&outcomes, &rows));
    let mut lines: Vec<String> = outcomes.iter().zip(&rows).map(|(o, c)| c.line(o)).collect();

    let fits = restitution_fits(
        &spec.drop_heights_m,
        &spec.measured_rebound_heights_m,
        g,
        setup.law.reference_speed_m_s,
    );
    if !fits.is_empty() {
        let tally = Tally::of(&rows, spec.tolerance);
        out.table(output::fit_table(&setup, g, &tally, outcomes.len(), &fits));
        lines.extend(fit_lines(&tally, outcomes.len(), spec.tolerance, &fits));
    }
    out.chart(
        "rebound_height.svg",
        &output::chart(&s.name, &setup, g, &outcomes),
    )
    .map_err(|e| Error::Io(p.path.clone(), e))?;

    Ok(SceneReport {
        warnings: Vec::new(),
        steps: outcomes.iter().map(|o| o.steps).sum(),
        bodies: outcomes.len(),
        engine_settings: Some(settings),
        lines,
        interrupted: false,
        reached_s: None,
    })
}

#[cfg(test)]
mod tests;
