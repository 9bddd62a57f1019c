//! What a scenario will cost before it runs: steps, bodies, time-series rows, memory, disk and
//! wall time, so that a run that would take days, more memory than the machine has or more disk
//! than a results folder should is refused up front with the estimate (the guard of
//! `settle run`; `--force` lifts the time limit and the soft memory and disk limits, never the
//! machine's physical memory). A run estimated to be long is announced on stderr before it
//! starts ([`Cost::is_long`], [`Cost::describe`]).

use super::schema::{Kind, Scenario};
use crate::error::BadInput;
use std::path::Path;

/// Wall time above which a run is refused without `--force`, s (24 h).
pub const MAX_WALL_S: f64 = 24.0 * 3600.0;

/// Memory above which a run is refused without `--force`, bytes (8 GB).
pub const MAX_MEMORY_BYTES: f64 = 8e9;

/// Disk above which a run is refused without `--force`, bytes (4 GB).
pub const MAX_DISK_BYTES: f64 = 4e9;

/// Wall time above which the estimate is printed before the run, s.
pub const ANNOUNCE_WALL_S: f64 = 30.0;

/// Memory or disk above which the estimate is printed before the run, bytes (1 GB).
pub const ANNOUNCE_BYTES: f64 = 1e9;

/// One row of `timeseries.csv` (free settling and drops): in memory (a time, a depth, a speed and
/// two optional analytic values, plus vector growth) and on disk (CSV text, measured on the
/// scenarios of `scenarios/`: 53–110 bytes), bytes.
const TIMESERIES_ROW_MEMORY_BYTES: f64 = 64.0;
const TIMESERIES_ROW_DISK_BYTES: f64 = 100.0;
/// Time-series rows per body without `record.every_s` (as the free-settling scene records).
const DEFAULT_ROWS_PER_BODY: f64 = 2000.0;
/// One grain in one sedimentation snapshot (a CSV row and a VTK point, ≈ 86 bytes each), and the
/// profiles, instruments and charts of a sedimentation run (≈ 20 MB whatever the grains), bytes.
const SNAPSHOT_GRAIN_DISK_BYTES: f64 = 180.0;
const SEDIMENTATION_FIXED_DISK_BYTES: f64 = 3e7;
/// Per-body files of the other kinds (summary rows, per-repeat census), bytes per body.
const BODY_DISK_BYTES: f64 = 200.0;

/// Cost of one body-step, s, by engine: measured by `settle bench` on the 2-core machine and
/// rounded up (exact free update ≈ 2–20 ns, Rapier ≈ 350–750 ns per body and step).
const FREE_BODY_STEP_S: f64 = 2e-8;
const RAPIER_BODY_STEP_S: f64 = 1e-6;
/// CPU time of the sedimentation cylinder per grain and step (N × steps, the steps counted at
/// `sample.max_step_s`), s, with full physics and no contacts: everything the run does (free
/// update, voidage grid, deposition, instruments, outputs) over N and the steps, the slowest of
/// the five samples of `scenarios/` at N = 10⁶ (sample 3: 75 s of CPU for 10⁶ × 8640, 8.7 ns;
/// sample 2: 18.5 s), rounded up. Measured on the 2-core machine, issue 17 (stop 21).
const SEDIMENTATION_FULL_GRAIN_STEP_S: f64 = 1e-8;
/// The same with `physics = "ideal-stokes"` (sample 5 at N = 10⁵: 0.36 s of CPU for
/// 10⁵ × 8640, 0.42 ns), rounded up.
const SEDIMENTATION_IDEAL_GRAIN_STEP_S: f64 = 1e-9;
/// CPU time of the contact stage (`sample.contacts = true`) per step, s, as
/// C N² (N/N₀)^½ (A₀/A) for N ≥ N₀, C N² (A₀/A) below: close pairs of representative grains
/// meet at a rate proportional to their number density N/A in the projected area A = B H, and
/// there are N of them (the close pairs grow as N^2.0–2.1, `docs/validation/performance.md`);
/// each pair costs 86–120 µs of CPU at N₀ = 10⁵, more as clusters grow. C is sample 2's (the
/// costliest of the measured samples): 331.8 s of CPU at N = 10⁵ over 8640 steps; with the
/// factor (N/N₀)^½ the model gives 5 170 s at 3·10⁵ against 5 016 s measured (sample 4: 1 927
/// s, the model is conservative for it).
const SEDIMENTATION_CONTACT_C_S: f64 = 3.84e-12;
const SEDIMENTATION_CONTACT_N0: f64 = 1e5;
/// The projected area A₀ of the cylinder those contact costs were measured in (B × H of
/// `scenarios/sedimentation_sample*.toml`), m².
const SEDIMENTATION_CONTACT_AREA_M2: f64 = 0.0635 * 0.457;
/// Memory per grain of the sedimentation cylinder, bytes: peak RSS 187 MB at N = 10⁶ for every
/// sample without contacts, 255 MB with contacts (sample 4), rounded up.
const SEDIMENTATION_GRAIN_BYTES: f64 = 300.0;
const RAPIER_BODY_BYTES: f64 = 2048.0;

/// The estimate for one scenario.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cost {
    /// Steps of one world (for adaptive steps, the number at the largest step).
    pub steps: f64,
    /// Bodies over all worlds.
    pub bodies: f64,
    /// Rows of the time series (free settling and drops; 0 for the other kinds).
    pub rows: f64,
    /// Memory, bytes.
    pub memory_bytes: f64,
    /// Outputs on disk, bytes.
    pub disk_bytes: f64,
    /// Wall time on one core, s.
    pub wall_s: f64,
}

impl Cost {
    /// True if the run is worth announcing before it starts: at least [`ANNOUNCE_WALL_S`] of
    /// wall time, or [`ANNOUNCE_BYTES`] of memory or disk.
    pub fn is_long(&self) -> bool {
        self.wall_s >= ANNOUNCE_WALL_S
            || self.memory_bytes >= ANNOUNCE_BYTES
            || self.disk_bytes >= ANNOUNCE_BYTES
    }

    /// One line: bodies × steps, rows, memory, disk and wall time.
    pub fn describe(&self) -> String {
        format!(
            "estimate: {:.3e} bodies × {:.3e} steps, {:.3e} time-series rows, {:.2} GB of memory, \
             {:.2} GB on disk, {} of wall time on one core",
            self.bodies,
            self.steps,
            self.rows,
            self.memory_bytes / 1e9,
            self.disk_bytes / 1e9,
            hours(self.wall_s)
        )
    }
}

fn hours(s: f64) -> String {
    if s < 60.0 {
        format!("{s:.0} s")
    } else if s < 3600.0 {
        format!("{:.0} min", s / 60.0)
    } else {
        format!("{:.1} h", s / 3600.0)
    }
}

/// Time-series rows of one body of a free-settling or drop scenario, as the scene records them:
/// every `record.every_s`, or every step up to [`DEFAULT_ROWS_PER_BODY`] rows.
fn rows_per_body(s: &Scenario, steps: f64) -> f64 {
    if !s.record.timeseries {
        return 0.0;
    }
    let steps = steps.round().max(1.0);
    let every = match s.record.every_s {
        Some(e) => (e / s.time.dt_s).round().max(1.0),
        None => (steps / DEFAULT_ROWS_PER_BODY).floor().max(1.0),
    };
    (steps / every).floor() + 1.0
}

/// Whether `s` is a sedimentation run whose close grain pairs are resolved (`sample.contacts`
/// with full physics).
fn sedimentation_contacts(s: &Scenario) -> bool {
    s.kind == Kind::Sedimentation
        && s.physics == super::schema::Physics::Full
        && s.sample.as_ref().is_some_and(|m| m.contacts)
}

/// CPU time of the sedimentation cylinder per grain and step, s, for `n` grains: the per-grain
/// cost of its physics, plus with contacts the cost of the close pairs of one step
/// ([`SEDIMENTATION_CONTACT_C_S`]) shared over the grains.
fn sedimentation_grain_step_s(s: &Scenario, n: f64) -> f64 {
    let per_grain = match s.physics {
        super::schema::Physics::Full => SEDIMENTATION_FULL_GRAIN_STEP_S,
        super::schema::Physics::IdealStokes => SEDIMENTATION_IDEAL_GRAIN_STEP_S,
    };
    if !sedimentation_contacts(s) {
        return per_grain;
    }
    let area_m2 = s
        .container
        .as_ref()
        .and_then(|c| Some(c.height_m * c.width_m.or(c.diameter_m)?))
        .unwrap_or(SEDIMENTATION_CONTACT_AREA_M2);
    let growth = (n / SEDIMENTATION_CONTACT_N0).max(1.0).sqrt();
    let pairs_s =
        SEDIMENTATION_CONTACT_C_S * n * n * growth * SEDIMENTATION_CONTACT_AREA_M2 / area_m2;
    per_grain + pairs_s / n
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
                sedimentation_grain_step_s(s, n),
                SEDIMENTATION_GRAIN_BYTES,
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
    let (rows, disk_bytes) = match s.kind {
        Kind::FreeSettling | Kind::Drop => {
            let rows = bodies * rows_per_body(s, steps);
            (
                rows,
                rows * TIMESERIES_ROW_DISK_BYTES + bodies * BODY_DISK_BYTES,
            )
        }
        Kind::Sedimentation => {
            let snaps = s.sample.as_ref().map_or(0, |m| m.snapshot_times_s.len()) as f64;
            (
                0.0,
                snaps * bodies * SNAPSHOT_GRAIN_DISK_BYTES + SEDIMENTATION_FIXED_DISK_BYTES,
            )
        }
        _ => (0.0, bodies * BODY_DISK_BYTES),
    };
    Cost {
        steps,
        bodies,
        rows,
        memory_bytes: bodies * per_body + rows * TIMESERIES_ROW_MEMORY_BYTES,
        disk_bytes,
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
pub fn check(s: &Scenario, file: &Path, force: bool) -> Result<Cost, BadInput> {
    let c = estimate(s);
    let key = match s.kind {
        Kind::Sedimentation => "sample.particles",
        Kind::FunnelPour => "repeats.count",
        _ => "time.dt_s",
    };
    let key = match s.kind {
        Kind::FreeSettling | Kind::Drop if c.rows > 0.0 => {
            if s.spheres.len() > 1 {
                "spheres"
            } else {
                "record.every_s"
            }
        }
        _ => key,
    };
    let memory = format!(
        "about {:.3e} bodies × {:.3e} steps and {:.3e} time-series rows: {:.1} GB of memory",
        c.bodies,
        c.steps,
        c.rows,
        c.memory_bytes / 1e9
    );
    if let Some(ram) = physical_memory_bytes() {
        if c.memory_bytes > ram {
            return Err(BadInput::new(
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
        return Err(BadInput::new(
            file,
            Some(key),
            format!(
                "{memory} (limit {:.0} GB): lower it, or run with --force",
                MAX_MEMORY_BYTES / 1e9
            ),
        ));
    }
    if c.disk_bytes > MAX_DISK_BYTES {
        return Err(BadInput::new(
            file,
            Some(key),
            format!(
                "about {:.3e} bodies and {:.3e} time-series rows would write {:.1} GB of outputs \
                 (limit {:.0} GB): fewer bodies, a longer record.every_s, record.timeseries = \
                 false, fewer snapshots, or run with --force",
                c.bodies,
                c.rows,
                c.disk_bytes / 1e9,
                MAX_DISK_BYTES / 1e9
            ),
        ));
    }
    if c.wall_s > MAX_WALL_S {
        let (key, hint) = if sedimentation_contacts(s) {
            (
                "sample.particles",
                "fewer grains (the contacts' cost grows as N^2.5), sample.contacts = false, \
                 or run with --force",
            )
        } else {
            let key = if s.kind == Kind::Sedimentation {
                "sample.max_step_s"
            } else {
                "time.dt_s"
            };
            (
                key,
                "raise the step, shorten time.end_s, or run with --force",
            )
        };
        return Err(BadInput::new(
            file,
            Some(key),
            format!(
                "{:.3e} steps × {:.3e} bodies would take about {:.0} h of wall time on one core \
                 (limit {:.0} h): {hint}",
                c.steps,
                c.bodies,
                c.wall_s / 3600.0,
                MAX_WALL_S / 3600.0
            ),
        ));
    }
    Ok(c)
}
