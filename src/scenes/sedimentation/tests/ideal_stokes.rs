//! Validation case: the sedimentation cylinder of seed 000 in its `ideal-stokes` reference
//! (scenarios/sedimentation_sample*.toml). Every grain falls at its Stokes velocity, so the solid
//! concentration at depth y and time t is c0·F(d*), d* = √(18 μ y / ((ρ_p − ρ_f) g t)), with F the
//! mass fraction finer than d* (seed eq. 16 and the ASTM D422 analysis). Tolerance: 4 standard
//! deviations of the representative-grain count in the band (σ/c = 1/√n), plus one size class.

use super::prepare;
use crate::fluid::sphere_volume_m3;
use crate::scenes::sedimentation::{limiting_diameter_m, setup, simulate, OnRecord, State};
use std::path::Path;

const H: f64 = 0.457;

struct Snap {
    t: f64,
    heights: Vec<(f64, f64, bool)>, // (y, solid volume, settled)
}

fn run(sample: u32, extra: &[&str]) -> (Vec<Snap>, crate::scenes::sedimentation::Setup, f64) {
    let path = format!("scenarios/sedimentation_sample{sample}.toml");
    let mut ov: Vec<String> = vec![
        "physics=ideal-stokes".into(),
        "sample.particles=60000".into(),
        "sample.max_step_s=1e5".into(),
        "sample.record_times_s=[60.0, 300.0, 900.0, 3600.0, 14400.0, 86400.0]".into(),
        "sample.snapshot_times_s=[]".into(),
    ];
    ov.extend(extra.iter().map(|s| s.to_string()));
    let p = prepare(Path::new(&path), None, &ov).unwrap();
    let su = setup(&p).unwrap();
    let mut snaps = Vec::new();
    let rec = |st: &State| {
        snaps.push(Snap {
            t: st.time_s,
            heights: (0..st.len())
                .map(|i| st.grain(&su.grains, i))
                .zip(&st.settled)
                .map(|(g, s)| (g.y_m, g.weight * sphere_volume_m3(g.diameter_m), *s))
                .collect(),
        })
    };
    simulate(&su, State::initial(&su), &[], &mut OnRecord(rec));
    let c0 = su.model_mass_kg / 2500.0 / (su.width_m * su.height_m * su.thickness_m);
    (snaps, su, c0)
}

/// Mass fraction of the discretised sample finer than or equal to `d`.
fn finer(su: &crate::scenes::sedimentation::Setup, d: f64) -> f64 {
    su.classes
        .iter()
        .filter(|c| c.diameter_m <= d)
        .map(|c| c.mass_fraction)
        .sum()
}

#[test]
fn ideal_stokes_concentration_matches_the_analytic_solution() {
    for sample in [1u32, 4, 5] {
        let (snaps, su, c0) = run(sample, &[]);
        assert_eq!(snaps.len(), 6);
        let band = 0.005;
        let n_total = su.grains.len() as f64;
        for s in &snaps {
            for y in [0.3 * H, 0.15] {
                // Simulated: solid volume of suspended grains with centre depth in [y − band, y + band].
                let (lo, hi) = (H - y - band, H - y + band);
                let (mut vol, mut n) = (0.0, 0usize);
                for &(h, v, settled) in &s.heights {
                    if !settled && h >= lo && h < hi {
                        vol += v;
                        n += 1;
                    }
                }
                let c_sim = vol / (su.width_m * 2.0 * band * su.thickness_m);
                // Analytic, averaged over the band.
                let k = 50;
                let mut f_avg = 0.0;
                let mut f_lo: f64 = 1.0;
                let mut f_hi: f64 = 0.0;
                for i in 0..k {
                    let depth = y - band + (i as f64 + 0.5) * 2.0 * band / k as f64;
                    let f = finer(
                        &su,
                        limiting_diameter_m(depth, s.t, 1e-3, 2500.0, 1000.0, 9.81),
                    );
                    f_avg += f / k as f64;
                    f_lo = f_lo.min(f);
                    f_hi = f_hi.max(f);
                }
                let c_an = c0 * f_avg;
                let n_exp = n_total * 2.0 * band / H * f_avg;
                let sigma = if n_exp > 0.0 {
                    c_an / n_exp.sqrt()
                } else {
                    0.0
                };
                // One size class of slack at the edge of d*: the largest class fraction present.
                let class_slack = c0
                    * su.classes
                        .iter()
                        .map(|c| c.mass_fraction)
                        .fold(0.0, f64::max);
                let tol = 4.0 * sigma + class_slack;
                assert!(
                    (c_sim - c_an).abs() <= tol,
                    "sample {sample}, t = {} s, y = {y} m: c_sim {c_sim:.4e} vs c_an {c_an:.4e} (tol {tol:.2e}, n = {n}, F {f_lo:.3}–{f_hi:.3})",
                    s.t
                );
            }
        }
    }
}

#[test]
fn every_grain_is_accounted_for_and_stays_in_the_cylinder() {
    let (snaps, su, _) = run(
        2,
        &[
            "physics=full",
            "sample.particles=20000",
            "sample.max_step_s=10.0",
        ],
    );
    let total: f64 = su
        .grains
        .to_vec()
        .iter()
        .map(|g| g.weight * sphere_volume_m3(g.diameter_m))
        .sum();
    for s in &snaps {
        assert_eq!(s.heights.len(), su.grains.len());
        let sum: f64 = s.heights.iter().map(|h| h.1).sum();
        assert!((sum / total - 1.0).abs() < 1e-12, "t = {}", s.t);
        for &(y, _, _) in &s.heights {
            assert!((0.0..=H).contains(&y), "t = {}: grain at y = {y}", s.t);
        }
    }
    // Sample 2 is 95 % coarse (50–70 µm): after 900 s nearly everything is in the bed.
    let late = snaps.iter().find(|s| s.t == 900.0).unwrap();
    let bed: f64 = late.heights.iter().filter(|h| h.2).map(|h| h.1).sum();
    assert!(bed / total > 0.9, "bed fraction {}", bed / total);
}

/// The final state of a run of sample 2 (`overrides`, 3 000 grains, 2 h, no snapshots) with the
/// grains visited by `step_loop`, and what each of its records read: the time, the height of
/// every grain (bits) and the settled count.
#[allow(clippy::type_complexity)]
fn sample2_on(
    step_loop: crate::scenes::sedimentation::simulate::StepLoop,
    overrides: &[&str],
) -> (State, Vec<(f64, Vec<u64>, usize)>) {
    use crate::scenes::sedimentation::simulate::simulate_on;
    let mut ov: Vec<String> = vec![
        "sample.particles=3000".into(),
        "time.end_s=7200.0".into(),
        "sample.snapshot_times_s=[]".into(),
    ];
    ov.extend(overrides.iter().map(|s| s.to_string()));
    let p = prepare(Path::new("scenarios/sedimentation_sample2.toml"), None, &ov).unwrap();
    let su = setup(&p).unwrap();
    let mut records = Vec::new();
    let seen = |st: &State| {
        records.push((
            st.time_s,
            st.y_m.iter().map(|y| y.to_bits()).collect(),
            st.settled.iter().filter(|&&x| x).count(),
        ))
    };
    let st = simulate_on(
        step_loop,
        &su,
        State::initial(&su),
        &[],
        &mut OnRecord(seen),
    );
    (st, records)
}

/// The loop a run's modes choose (the packed suspension of full physics without contacts, the
/// ideal-Stokes intervals) and the per-grain loop over the state call the same free update
/// (`step::kernel`) on the same grains in the same order, so they must agree bit for bit:
/// every height, speed and settled flag, the bed, the time and step count, and what every
/// record reads. Checked in ideal Stokes with the exponential integrator (intervals, Stokes
/// factors once per step size, against the cell's drag through `dynamics::advance`), and in
/// full physics without contacts with the exponential step from the tables (16 lanes at once
/// against one grain at a time) and with the implicit integrator (each cell's drag).
#[test]
fn the_chosen_loops_agree_with_the_per_grain_loop_bit_for_bit() {
    use crate::scenes::sedimentation::simulate::StepLoop;
    for ov in [
        &["physics=ideal-stokes"][..],
        &["physics=full"],
        &["physics=full", "time.integrator=\"implicit\""],
    ] {
        let (chosen, chosen_records) = sample2_on(StepLoop::Chosen, ov);
        let (per_grain, loop_records) = sample2_on(StepLoop::PerGrain, ov);
        assert!(
            chosen.fault.is_none() && per_grain.fault.is_none(),
            "{ov:?}"
        );
        assert_eq!(
            (chosen.time_s, chosen.steps, chosen.bed_height_m.to_bits()),
            (
                per_grain.time_s,
                per_grain.steps,
                per_grain.bed_height_m.to_bits()
            ),
            "{ov:?}"
        );
        let settled = &per_grain.settled;
        assert!(
            settled.iter().any(|&x| x) && settled.iter().any(|&x| !x),
            "{ov:?}"
        );
        assert_eq!(chosen.len(), per_grain.len());
        for (i, (a, b)) in chosen.y_m.iter().zip(&per_grain.y_m).enumerate() {
            assert_eq!(a.to_bits(), b.to_bits(), "{ov:?} grain {i}: height");
            assert_eq!(
                chosen.velocity_m_s[i].to_bits(),
                per_grain.velocity_m_s[i].to_bits(),
                "{ov:?} grain {i}: speed"
            );
            assert_eq!(chosen.settled[i], settled[i], "{ov:?} grain {i}: settled");
        }
        assert!(loop_records.len() > 3, "{ov:?}: {}", loop_records.len());
        assert!(chosen_records == loop_records, "{ov:?}: the records differ");
    }
}

/// What a checkpoint reads of a state: step, heights and speeds (bits), settled flags.
type Saved = (u64, Vec<u64>, Vec<u64>, Vec<bool>);

/// An observer that wants the grains every `k`-th step (as a checkpoint does) and keeps what
/// the state holds then ([`Saved`]).
struct EveryKth {
    k: u64,
    calls: u64,
    due: bool,
    seen: Vec<Saved>,
}

impl crate::scenes::sedimentation::Observer for EveryKth {
    fn wants_grains(&mut self) -> bool {
        self.calls += 1;
        self.due = self.calls.is_multiple_of(self.k);
        self.due
    }

    fn step(&mut self, st: &State) {
        if self.due {
            let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect();
            let seen = (
                st.steps,
                bits(&st.y_m),
                bits(&st.velocity_m_s),
                st.settled.clone(),
            );
            self.seen.push(seen);
        }
    }
}

/// The packed suspension keeps the suspended grains' speeds apart and gives the state every
/// speed only when the observer wants the grains (a checkpoint) and at the end: there the
/// state must be that of the per-grain loop, bit for bit (heights, speeds, settled flags; full
/// physics without contacts, sample 2, 3 000 grains, every 40th step), and at the end every
/// grain has a speed.
#[test]
fn the_packed_loop_gives_checkpoints_every_speed() {
    use crate::scenes::sedimentation::simulate::{simulate_on, StepLoop};
    let ov: Vec<String> = ["sample.particles=3000", "time.end_s=7200.0", "physics=full"]
        .map(String::from)
        .to_vec();
    let p = prepare(Path::new("scenarios/sedimentation_sample2.toml"), None, &ov).unwrap();
    let su = setup(&p).unwrap();
    let on = |step_loop| {
        let mut obs = EveryKth {
            k: 40,
            calls: 0,
            due: false,
            seen: Vec::new(),
        };
        let st = simulate_on(step_loop, &su, State::initial(&su), &[], &mut obs);
        (st, obs.seen)
    };
    let (packed, packed_seen) = on(StepLoop::Chosen);
    let (per_grain, per_grain_seen) = on(StepLoop::PerGrain);
    assert!(packed_seen.len() >= 3, "{} checkpoints", packed_seen.len());
    assert!(packed_seen
        .iter()
        .all(|s| s.2.len() == su.grains.len() && s.3.iter().any(|&x| !x)));
    assert!(
        packed_seen == per_grain_seen,
        "the checkpoints' states differ"
    );
    assert_eq!(packed.velocity_m_s.len(), su.grains.len());
    let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&packed.velocity_m_s), bits(&per_grain.velocity_m_s));
}

/// In ideal Stokes every grain obeys m v̇ = −(m − m_f) g − 3π μ d v from rest, whose solution is
/// v(t) = −u (1 − e^(−t/τ)), y(t) = y₀ − u (t − τ (1 − e^(−t/τ))) with u = (ρ_p − ρ_f) g d²/(18 μ)
/// and τ = ρ_p d²/(18 μ), until its bottom reaches the floor (the bed does not rise in ideal
/// Stokes). The free update (exponential integrator, exact for linear drag) must follow it to
/// rounding, through the interval loop and the per-grain loop alike: every record's heights
/// within 0.1 µm (against falls of up to the cylinder's 0.457 m) and speeds within 1e-9 of u,
/// and every grain whose analytic bottom is below the floor settled on it.
#[test]
fn ideal_stokes_free_update_follows_the_analytic_stokes_solution() {
    use crate::scenes::sedimentation::simulate::{simulate_on, StepLoop};
    let ov: Vec<String> = vec![
        "physics=ideal-stokes".into(),
        "sample.particles=3000".into(),
        "time.end_s=3600.0".into(),
        "sample.record_times_s=[60.0, 600.0, 3600.0]".into(),
        "sample.snapshot_times_s=[]".into(),
    ];
    let p = prepare(Path::new("scenarios/sedimentation_sample2.toml"), None, &ov).unwrap();
    let su = setup(&p).unwrap();
    let (g, mu) = (p.common.gravity_m_s2, su.viscosity_pa_s);
    let (rho_p, rho_f) = (su.spec.sample.density_kg_m3, p.common.fluid_density_kg_m3);
    let start = State::initial(&su);
    for step_loop in [StepLoop::Chosen, StepLoop::PerGrain] {
        let (mut checked, mut landed) = (0, 0);
        let check = |st: &State| {
            let t = st.time_s;
            for i in 0..st.len() {
                let (gr, g0) = (st.grain(&su.grains, i), start.grain(&su.grains, i));
                let d = gr.diameter_m;
                let u = (rho_p - rho_f) * g * d * d / (18.0 * mu);
                let tau = rho_p * d * d / (18.0 * mu);
                let y = g0.y_m - u * (t - tau * -(-t / tau).exp_m1());
                if y - 0.5 * d > 1e-7 {
                    let v = -u * -(-t / tau).exp_m1();
                    assert!(!st.settled[i], "{step_loop:?} t {t}: grain {i} settled");
                    assert!(
                        (gr.y_m - y).abs() < 1e-7,
                        "{step_loop:?} t {t}: grain {i} at {} not {y}",
                        gr.y_m
                    );
                    let dv = (st.velocity_m_s[i] - v).abs();
                    assert!(
                        dv < 1e-9 * u,
                        "{step_loop:?} t {t}: grain {i} speed {dv:e} off"
                    );
                    checked += 1;
                } else if y - 0.5 * d < -1e-7 {
                    assert!(
                        st.settled[i],
                        "{step_loop:?} t {t}: grain {i} still suspended"
                    );
                    assert_eq!(
                        gr.y_m,
                        0.5 * d,
                        "{step_loop:?} t {t}: grain {i} on the floor"
                    );
                    landed += 1;
                }
            }
        };
        simulate_on(step_loop, &su, start.clone(), &[], &mut OnRecord(check));
        assert!(
            checked > 1000 && landed > 1000,
            "{step_loop:?}: {checked} {landed}"
        );
    }
}

/// The packed free update finds a grain's new voidage cell from its old one
/// (`VoidageGrid::cell_after`: two comparisons against the cell's exact bounds); it must be the
/// cell `VoidageGrid::cell_of` computes, at every row boundary to the last unit in the last
/// place, from the cell below, the cell itself and the cell above, and outside the cylinder.
#[test]
fn cell_after_is_cell_of_at_every_row_boundary() {
    use crate::scenes::sedimentation::voidage::VoidageGrid;
    let p = prepare(Path::new("scenarios/sedimentation_sample2.toml"), None, &[]).unwrap();
    let su = setup(&p).unwrap();
    let cell_m = su.spec.sample.voidage_cell_m;
    let grid = VoidageGrid::new(&su, cell_m, false, 1000.0);
    let rows = (su.height_m / cell_m).ceil() as usize;
    let mut checked = 0;
    for x in [0.0, 0.37 * su.width_m, su.width_m] {
        for r in 0..=rows {
            let nominal = r as f64 * su.height_m / rows as f64;
            let mut ys = vec![-1.0, su.height_m * 2.0, f64::INFINITY];
            let mut y = nominal;
            for _ in 0..4 {
                y = f64::from_bits(y.to_bits().saturating_sub(1));
            }
            for _ in 0..9 {
                ys.push(y);
                y = f64::from_bits(y.to_bits() + 1);
            }
            for y in ys {
                let want = grid.cell_of(x, y);
                for from_y in [nominal - cell_m, nominal, nominal + 0.5 * cell_m] {
                    let from = grid.cell_of(x, from_y);
                    assert_eq!(
                        grid.cell_after(from, y),
                        want,
                        "x {x}, y {y:e}, from {from}"
                    );
                    checked += 1;
                }
            }
        }
    }
    assert!(checked > 1000, "{checked}");
}
