//! What a scenario will cost before it runs: steps, bodies, memory and wall time, so that a run
//! that would take days or more memory than the machine has is refused up front with the
//! estimate (the guard of `settle run`; `--force` lifts the time limit and the soft memory
//! limit, never the machine's physical memory).

use super::load::ScenarioError;
use super::schema::{Kind, Scenario};
use std::path::Path;

/// Wall time above which a run is refused without `--force`, s (24 h).
pub const MAX_WALL_S: f64 = 24.0 * 3600.0;

/// Memory above which a run is refused without `--force`, bytes (8 GB).
pub const MAX_MEMORY_BYTES: f64 = 8e9;

/// Cost of one body-step, s, by engine: measured by `settle bench` on the 2-core machine and
/// rounded up (exact free update ≈ 2–20 ns, Rapier ≈ 350–750 ns per body and step).
const FREE_BODY_STEP_S: f64 = 2e-8;
const RAPIER_BODY_STEP_S: f64 = 1e-6;
/// State per body, bytes (grain, velocity, flags, recorded profiles amortised; Rapier body).
const FREE_BODY_BYTES: f64 = 64.0;
const RAPIER_BODY_BYTES: f64 = 2048.0;

/// The estimate for one scenario.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cost {
    /// Steps of one world (for adaptive steps, the number at the largest step).
    pub steps: f64,
    /// Bodies over all worlds.
    pub bodies: f64,
    /// Memory, bytes.
    pub memory_bytes: f64,
    /// Wall time on one core, s.
    pub wall_s: f64,
}

/// Estimates the cost of a scenario (see the module doc).
pub fn estimate(s: &Scenario) -> Cost {
    let (steps, bodies, per_step, per_body) = match s.kind {
        Kind::Sedimentation => {
            let sm = s.sample.as_ref();
            let n = sm.map_or(1.0, |m| m.particles as f64);
            let max_step = sm.map_or(s.time.dt_s, |m| m.max_step_s);
            (
                s.time.end_s / max_step,
                n,
                FREE_BODY_STEP_S,
                FREE_BODY_BYTES,
            )
        }
        Kind::FunnelPour => {
            let balls = s.funnel.as_ref().map_or(1, |f| f.count) as f64;
            let reps = s.repeats.as_ref().map_or(1, |r| r.count) as f64;
            (
                s.time.end_s / s.time.dt_s,
                balls * reps,
                RAPIER_BODY_STEP_S,
                RAPIER_BODY_BYTES,
            )
        }
        Kind::RestitutionDrop | Kind::TiltFriction => (
            s.time.end_s / s.time.dt_s,
            1.0,
            RAPIER_BODY_STEP_S,
            RAPIER_BODY_BYTES,
        ),
        Kind::FreeSettling | Kind::Drop => (
            s.time.end_s / s.time.dt_s,
            s.spheres.len().max(1) as f64,
            if s.engine() == super::schema::Engine::Rapier {
                RAPIER_BODY_STEP_S
            } else {
                FREE_BODY_STEP_S
            },
            RAPIER_BODY_BYTES,
        ),
    };
    Cost {
        steps,
        bodies,
        memory_bytes: bodies * per_body,
        wall_s: steps * bodies * per_step,
    }
}

/// Physical memory of this machine, bytes (Linux `/proc/meminfo`; None elsewhere).
pub fn physical_memory_bytes() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024.0)
}

/// Refuses a scenario whose estimate exceeds the limits: [`MAX_WALL_S`] and
/// [`MAX_MEMORY_BYTES`] unless `force`, and the machine's physical memory always. The error names
/// the file, the key that drives the cost and the estimate.
pub fn check(s: &Scenario, file: &Path, force: bool) -> Result<Cost, ScenarioError> {
    let c = estimate(s);
    let key = match s.kind {
        Kind::Sedimentation => "sample.particles",
        Kind::FunnelPour => "repeats.count",
        _ => "time.dt_s",
    };
    let memory = format!(
        "about {:.3e} bodies × {:.3e} steps: {:.1} GB of state",
        c.bodies,
        c.steps,
        c.memory_bytes / 1e9
    );
    if let Some(ram) = physical_memory_bytes() {
        if c.memory_bytes > ram {
            return Err(ScenarioError::new(
                file,
                Some(key),
                format!(
                    "{memory}, more than this machine's {:.1} GB: not runnable, even with --force",
                    ram / 1e9
                ),
            ));
        }
    }
    if force {
        return Ok(c);
    }
    if c.memory_bytes > MAX_MEMORY_BYTES {
        return Err(ScenarioError::new(
            file,
            Some(key),
            format!(
                "{memory} (limit {:.0} GB): lower it, or run with --force",
                MAX_MEMORY_BYTES / 1e9
            ),
        ));
    }
    if c.wall_s > MAX_WALL_S {
        let key = if s.kind == Kind::Sedimentation {
            "sample.max_step_s"
        } else {
            "time.dt_s"
        };
        return Err(ScenarioError::new(
            file,
            Some(key),
            format!(
                "{:.3e} steps × {:.3e} bodies would take about {:.0} h of wall time on one core \
                 (limit {:.0} h): raise the step, shorten time.end_s, or run with --force",
                c.steps,
                c.bodies,
                c.wall_s / 3600.0,
                MAX_WALL_S / 3600.0
            ),
        ));
    }
    Ok(c)
}
