//! What a scenario will cost before it runs: steps, bodies, time-series rows, memory, disk and
//! wall time, so that a run that would take days, more memory than the machine has or more disk
//! than a results folder should is refused up front with the estimate (the guard of
//! `settle run`; `--force` lifts the time limit and the soft memory and disk limits, never the
//! machine's physical memory). A run estimated to be long is announced on stderr before it
//! starts ([`Cost::is_long`], [`Cost::describe`]).

use crate::error::BadInput;
use crate::scenario::Common;

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

/// Per-body files of the other kinds (summary rows, per-repeat census), bytes per body.
pub const BODY_DISK_BYTES: f64 = 200.0;

/// Cost of one body-step, s, by engine: measured by `settle bench` on the 2-core machine and
/// rounded up (exact free update ≈ 2–20 ns, Rapier ≈ 350–750 ns per body and step).
pub const FREE_BODY_STEP_S: f64 = 2e-8;
pub const RAPIER_BODY_STEP_S: f64 = 1e-6;
/// Memory of one body in a Rapier world (or of one free sphere), bytes.
pub const RAPIER_BODY_BYTES: f64 = 2048.0;

/// What one kind's scene says of a scenario's load, from which [`estimate`] derives the cost
/// (each kind's `cost.rs`, dispatched by [`super::load`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Load {
    /// Steps of one world.
    pub steps: f64,
    /// Bodies over all worlds.
    pub bodies: f64,
    /// CPU time of one body-step, s.
    pub body_step_s: f64,
    /// Memory of one body, bytes.
    pub body_bytes: f64,
    /// Rows of the time series.
    pub rows: f64,
    /// Memory of one time-series row, bytes.
    pub row_bytes: f64,
    /// Outputs on disk, bytes.
    pub disk_bytes: f64,
    /// The key named when the memory or disk estimate is refused.
    pub key: &'static str,
    /// What lowers the memory, named when its estimate is refused ([`LOWER_IT`] where the key
    /// alone drives it).
    pub memory_hint: &'static str,
    /// The key and the hint named when the wall-time estimate is refused.
    pub wall: (&'static str, &'static str),
}

/// The memory hint of a load driven by its key alone ([`Load::memory_hint`]).
pub const LOWER_IT: &str = "lower it";

/// The hint of a wall time over the limit, for a run whose cost is its steps.
pub const STEP_HINT: &str = "raise the step, shorten time.end_s, or run with --force";

/// A run of `bodies` Rapier bodies over `time.end_s / time.dt_s` steps, writing a summary row
/// per body: the load of the contact kinds.
pub fn rapier_load(c: &Common, bodies: f64, key: &'static str) -> Load {
    Load {
        steps: c.time.end_s / c.time.dt_s,
        bodies,
        body_step_s: RAPIER_BODY_STEP_S,
        body_bytes: RAPIER_BODY_BYTES,
        rows: 0.0,
        row_bytes: 0.0,
        disk_bytes: bodies * BODY_DISK_BYTES,
        key,
        memory_hint: LOWER_IT,
        wall: ("time.dt_s", STEP_HINT),
    }
}

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

/// Estimates the cost of a prepared scenario (see the module doc).
pub fn estimate(p: &super::Prepared) -> Cost {
    of(&super::load(p))
}

/// The cost of a load.
fn of(l: &Load) -> Cost {
    Cost {
        steps: l.steps,
        bodies: l.bodies,
        rows: l.rows,
        memory_bytes: l.bodies * l.body_bytes + l.rows * l.row_bytes,
        disk_bytes: l.disk_bytes,
        wall_s: l.steps * l.bodies * l.body_step_s,
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
/// the scenario file, the key that drives the cost and the estimate.
pub fn check(p: &super::Prepared, force: bool) -> Result<Cost, BadInput> {
    let file = p.path.as_path();
    let load = super::load(p);
    let c = of(&load);
    let key = load.key;
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
                    "{memory}, more than this machine's {:.1} GB: not runnable, even with \
                     --force ({})",
                    ram / 1e9,
                    load.memory_hint
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
                "{memory} (limit {:.0} GB): {}, or run with --force",
                MAX_MEMORY_BYTES / 1e9,
                load.memory_hint
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
        let (key, hint) = load.wall;
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
