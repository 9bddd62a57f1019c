//! The cost of a sedimentation run ([`crate::scenes::cost`]): N grains over the steps at
//! `sample.max_step_s`, measured per grain and step, plus the close pairs of the contact solve;
//! snapshots on disk.

use crate::scenario::{Common, Physics, SedimentationSpec};
use crate::scenes::cost::{Load, STEP_HINT};

/// One grain in one sedimentation snapshot (a CSV row and a VTK point, ≈ 86 bytes each), and the
/// profiles, instruments and charts of a sedimentation run (≈ 20 MB whatever the grains), bytes.
const SNAPSHOT_GRAIN_DISK_BYTES: f64 = 180.0;
const SEDIMENTATION_FIXED_DISK_BYTES: f64 = 3e7;
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
/// Memory per grain of the sedimentation cylinder without contacts, bytes, snapshots apart: peak
/// RSS 58.9 B per grain at N = 10⁶ (sample 5, `settle bench`, 6 December 2026; the grains held
/// once: 12 B of constants, 9 B of state, 28 B of packed suspension, 8 B more on a checkpoint's
/// step), rounded up.
const SEDIMENTATION_GRAIN_BYTES: f64 = 64.0;
/// The same with contacts (`sample.contacts = true`): 255 MB at N = 10⁶ (sample 4), rounded up.
const SEDIMENTATION_CONTACT_GRAIN_BYTES: f64 = 300.0;
/// Memory per grain and snapshot, bytes: the grains' state kept for the snapshot until the end
/// of the run (height and settled flag, 9 B; the horizontal position too with contacts), and
/// its table and files at the end (typed columns, the VTK file written from them): 326 MB at
/// N = 10⁶ with three snapshots against 134 MB without (sample 5, 6 December 2026), 64 B per
/// grain and snapshot, rounded up.
const SNAPSHOT_GRAIN_MEMORY_BYTES: f64 = 70.0;

/// The load of a sedimentation scenario.
pub fn load(c: &Common, spec: &SedimentationSpec) -> Load {
    let sm = &spec.sample;
    let n = sm.particles as f64;
    let snaps = sm.snapshot_times_s.len() as f64;
    Load {
        steps: c.time.end_s / sm.max_step_s,
        bodies: n,
        body_step_s: grain_step_s(c, spec, n),
        body_bytes: if contacts(c, spec) {
            SEDIMENTATION_CONTACT_GRAIN_BYTES
        } else {
            SEDIMENTATION_GRAIN_BYTES
        } + snaps * SNAPSHOT_GRAIN_MEMORY_BYTES,
        rows: 0.0,
        row_bytes: 0.0,
        disk_bytes: snaps * n * SNAPSHOT_GRAIN_DISK_BYTES + SEDIMENTATION_FIXED_DISK_BYTES,
        key: "sample.particles",
        memory_hint: "fewer grains, or fewer sample.snapshot_times_s (each holds every grain)",
        wall: if contacts(c, spec) {
            (
                "sample.particles",
                "fewer grains (the contacts' cost grows as N^2.5), sample.contacts = false, \
                 or run with --force",
            )
        } else {
            ("sample.max_step_s", STEP_HINT)
        },
    }
}

/// Whether the close grain pairs are resolved (`sample.contacts` with full physics).
fn contacts(c: &Common, spec: &SedimentationSpec) -> bool {
    c.physics == Physics::Full && spec.sample.contacts
}

/// CPU time of the sedimentation cylinder per grain and step, s, for `n` grains: the per-grain
/// cost of its physics, plus with contacts the cost of the close pairs of one step
/// ([`SEDIMENTATION_CONTACT_C_S`]) shared over the grains.
fn grain_step_s(c: &Common, spec: &SedimentationSpec, n: f64) -> f64 {
    let per_grain = match c.physics {
        Physics::Full => SEDIMENTATION_FULL_GRAIN_STEP_S,
        Physics::IdealStokes => SEDIMENTATION_IDEAL_GRAIN_STEP_S,
    };
    if !contacts(c, spec) {
        return per_grain;
    }
    let area_m2 = spec.height_m * spec.width_m;
    let growth = (n / SEDIMENTATION_CONTACT_N0).max(1.0).sqrt();
    let pairs_s =
        SEDIMENTATION_CONTACT_C_S * n * n * growth * SEDIMENTATION_CONTACT_AREA_M2 / area_m2;
    per_grain + pairs_s / n
}
