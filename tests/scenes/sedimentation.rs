//! Validation case: the sedimentation cylinder of seed 000 in its `ideal-stokes` reference
//! (scenarios/sedimentation_sample*.toml). Every grain falls at its Stokes velocity, so the solid
//! concentration at depth y and time t is c0·F(d*), d* = √(18 μ y / ((ρ_p − ρ_f) g t)), with F the
//! mass fraction finer than d* (seed eq. 16 and the ASTM D422 analysis). Tolerance: 4 standard
//! deviations of the representative-grain count in the band (σ/c = 1/√n), plus one size class.

use crate::common::{number_after, settle, tmp};
use settle::fluid::sphere_volume_m3;
use settle::run::prepare;
use settle::scenes::sedimentation::{limiting_diameter_m, setup, simulate, OnRecord, State};
use std::path::Path;

const H: f64 = 0.457;

struct Snap {
    t: f64,
    heights: Vec<(f64, f64, bool)>, // (y, solid volume, settled)
}

fn run(sample: u32, extra: &[&str]) -> (Vec<Snap>, settle::scenes::sedimentation::Setup, f64) {
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
    let su = setup(&p.scenario, &p.path).unwrap();
    let mut snaps = Vec::new();
    let rec = |st: &State| {
        snaps.push(Snap {
            t: st.time_s,
            heights: st
                .grains
                .iter()
                .zip(&st.settled)
                .map(|(g, s)| (g.y_m, g.weight * sphere_volume_m3(g.diameter_m), *s))
                .collect(),
        })
    };
    simulate(
        &p.scenario,
        &su,
        State::initial(&su),
        &[],
        &mut OnRecord(rec),
    );
    let c0 = su.model_mass_kg / 2500.0 / (su.width_m * su.height_m * su.thickness_m);
    (snaps, su, c0)
}

/// Mass fraction of the discretised sample finer than or equal to `d`.
fn finer(su: &settle::scenes::sedimentation::Setup, d: f64) -> f64 {
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

/// Regression: the explicit integrator at the cylinder's steps (1–10 s, against a response time
/// of µs for a 5 µm grain) sent every grain through the floor in the first step; the floor
/// absorbed them into the bed and the run "succeeded" with every instrument 85–100 % off. The run
/// must stop instead, naming the grain, the time, the speed against its physical bound (twice the
/// largest grain's Stokes terminal speed) and the explicit scheme's stable dt (2τ = ρ d²/(9μ)
/// for that grain, to the 4 digits printed), and write nothing.
#[test]
fn an_explicit_blow_up_stops_the_run_instead_of_filling_the_bed() {
    let dir = tmp();
    let out = settle()
        .args([
            "run",
            "scenarios/sedimentation_sample5.toml",
            "--set",
            "physics=ideal-stokes",
            "--set",
            "time.integrator=explicit",
            "--set",
            "sample.particles=1000",
            "--quiet",
            "--out",
        ])
        .arg(dir.path())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(3));
    let e = String::from_utf8_lossy(&out.stderr);
    assert!(e.contains("grain ") && e.contains("speed (bound"), "{e}");
    assert!(e.contains("step 1)"), "{e}");
    // The grain's diameter and the stable dt it prints: 2τ = ρ_p d²/(9 μ).
    let (d, stable) = (number_after(&e, "(d = "), number_after(&e, "use dt < "));
    let two_tau = 2500.0 * d * d / (9.0 * 1e-3);
    assert!(
        (stable / two_tau - 1.0).abs() < 1e-3,
        "{stable} vs 2τ = {two_tau}"
    ); // 4 digits printed
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        0,
        "nothing written"
    );
}

/// ideal-Stokes with the exponential integrator makes the steps between two events at once,
/// grain by grain (`Stepper::ideal_interval`); it must give the state of the step loop (free
/// update, deposition, clock after every step) bit for bit: every height, speed and settled flag,
/// the time and the step count.
#[test]
fn ideal_stokes_intervals_give_the_step_loop_bit_for_bit() {
    use settle::scenes::sedimentation::schedule::Schedule;
    use settle::scenes::sedimentation::step::{advance_clock, Stepper};
    use settle::scenes::sedimentation::voidage::VoidageGrid;
    let ov: Vec<String> = vec![
        "physics=ideal-stokes".into(),
        "sample.particles=3000".into(),
        "time.end_s=7200.0".into(),
        "sample.snapshot_times_s=[]".into(),
    ];
    let p = prepare(Path::new("scenarios/sedimentation_sample2.toml"), None, &ov).unwrap();
    let su = setup(&p.scenario, &p.path).unwrap();
    let fast = simulate(&p.scenario, &su, State::initial(&su), &[], &mut ());
    // The step loop, stage by stage.
    let s = &p.scenario;
    let sm = &su.spec.sample;
    let mut st = State::initial(&su);
    let stepper = Stepper::new(s, sm, &su, &st);
    let grid = VoidageGrid::new(&su, sm.voidage_cell_m, true, stepper.fluid_density_kg_m3);
    let schedule = Schedule::new(s, sm, &[]);
    let every: Vec<usize> = (0..st.grains.len()).collect();
    while schedule.running(&st) {
        let next = schedule.next_event_s(&st);
        let dt = stepper.step_size_s(&st, next, &[]);
        let (_, suspect) = stepper
            .free_update(&mut st, &su, &grid, dt, &every)
            .unwrap();
        assert!(!suspect);
        stepper.deposit(&mut st, &every);
        advance_clock(&mut st, dt, next);
        schedule.dispatch(&mut st, &mut ());
    }
    assert_eq!((fast.time_s, fast.steps), (st.time_s, st.steps));
    assert!(st.settled.iter().any(|&x| x) && st.settled.iter().any(|&x| !x));
    for (i, (a, b)) in fast.grains.iter().zip(&st.grains).enumerate() {
        assert_eq!(a.y_m.to_bits(), b.y_m.to_bits(), "grain {i}: height");
        assert_eq!(
            fast.velocity_m_s[i].to_bits(),
            st.velocity_m_s[i].to_bits(),
            "grain {i}: speed"
        );
        assert_eq!(fast.settled[i], st.settled[i], "grain {i}: settled");
    }
}

/// Full physics without contacts steps the suspended grains packed apart from the state
/// (`suspension::Suspension`: structure of arrays, several grains' terminal-state tables
/// evaluated together, settled grains dropped, heights written back only when read); it must
/// give the state of the step loop over the state itself (voidage grid, free update,
/// deposition, clock after every step) bit for bit, and hand the records current grains. Checked
/// with the exponential step from the tables (the default) and with the implicit integrator
/// (the drag of each cell, no tables).
#[test]
fn packed_suspension_gives_the_step_loop_bit_for_bit() {
    use settle::scenes::sedimentation::schedule::Schedule;
    use settle::scenes::sedimentation::step::{advance_clock, Stepper};
    use settle::scenes::sedimentation::voidage::VoidageGrid;
    for integrator in ["exponential", "implicit"] {
        let ov: Vec<String> = vec![
            "sample.particles=3000".into(),
            "time.end_s=7200.0".into(),
            "sample.snapshot_times_s=[]".into(),
            format!("time.integrator=\"{integrator}\""),
        ];
        let p = prepare(Path::new("scenarios/sedimentation_sample2.toml"), None, &ov).unwrap();
        let su = setup(&p.scenario, &p.path).unwrap();
        assert!(!su.spec.sample.contacts);
        // What a record reads: the heights of all grains and the settled count.
        let seen = |st: &State| {
            let heights: Vec<u64> = st.grains.iter().map(|g| g.y_m.to_bits()).collect();
            (
                st.time_s,
                heights,
                st.settled.iter().filter(|&&x| x).count(),
            )
        };
        let mut packed_records = Vec::new();
        let packed = simulate(
            &p.scenario,
            &su,
            State::initial(&su),
            &[],
            &mut OnRecord(|st: &State| packed_records.push(seen(st))),
        );
        // The step loop over the state, stage by stage, every grain visited at every step.
        let s = &p.scenario;
        let sm = &su.spec.sample;
        let mut st = State::initial(&su);
        let stepper = Stepper::new(s, sm, &su, &st);
        let mut grid = VoidageGrid::new(&su, sm.voidage_cell_m, false, stepper.fluid_density_kg_m3)
            .with_hindered(sm.hindered)
            .with_terminal_tables(&st, stepper.grain_density_kg_m3, stepper.gravity_m_s2);
        let speeds = stepper.stokes_speeds_m_s(&st);
        let volumes = grid.grain_volumes_m3(&st);
        let schedule = Schedule::new(s, sm, &[]);
        let every: Vec<usize> = (0..st.grains.len()).collect();
        let mut loop_records = Vec::new();
        while schedule.running(&st) {
            let next = schedule.next_event_s(&st);
            let dt = stepper.step_size_s(&st, next, &speeds);
            grid.fill(&st, &volumes, &every);
            let (_, suspect) = stepper
                .free_update(&mut st, &su, &grid, dt, &every)
                .unwrap();
            assert!(!suspect);
            stepper.deposit_vmax(&mut st, &speeds, &every);
            advance_clock(&mut st, dt, next);
            schedule.dispatch(
                &mut st,
                &mut OnRecord(|st: &State| loop_records.push(seen(st))),
            );
        }
        assert_eq!(
            (packed.time_s, packed.steps, packed.bed_height_m.to_bits()),
            (st.time_s, st.steps, st.bed_height_m.to_bits()),
            "{integrator}"
        );
        assert!(st.settled.iter().any(|&x| x) && st.settled.iter().any(|&x| !x));
        for (i, (a, b)) in packed.grains.iter().zip(&st.grains).enumerate() {
            assert_eq!(
                a.y_m.to_bits(),
                b.y_m.to_bits(),
                "{integrator} grain {i}: height"
            );
            assert_eq!(
                packed.velocity_m_s[i].to_bits(),
                st.velocity_m_s[i].to_bits(),
                "{integrator} grain {i}: speed"
            );
            assert_eq!(
                packed.settled[i], st.settled[i],
                "{integrator} grain {i}: settled"
            );
        }
        assert!(
            loop_records.len() > 3,
            "{integrator}: {}",
            loop_records.len()
        );
        assert!(
            packed_records == loop_records,
            "{integrator}: the records differ"
        );
    }
}

/// The packed free update finds a grain's new voidage cell from its old one
/// (`VoidageGrid::cell_after`: two comparisons against the cell's exact bounds); it must be the
/// cell `VoidageGrid::cell_of` computes, at every row boundary to the last unit in the last
/// place, from the cell below, the cell itself and the cell above, and outside the cylinder.
#[test]
fn cell_after_is_cell_of_at_every_row_boundary() {
    use settle::scenes::sedimentation::voidage::VoidageGrid;
    let p = prepare(Path::new("scenarios/sedimentation_sample2.toml"), None, &[]).unwrap();
    let su = setup(&p.scenario, &p.path).unwrap();
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
