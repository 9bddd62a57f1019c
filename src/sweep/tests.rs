//! Time-step sweeps (f-EDEM Figs. 5, 9, 10): sharded sweeps merge to the unsharded one, the
//! explicit scheme is reported unstable where theory says, and the stable integrator meets the
//! accuracy targets at large steps.

use crate::dynamics::Integrator;
use crate::run::prepare;
use crate::sweep::{finish, grid, run_cases, shard, summarise, Row, Status};
use std::path::Path;

fn strip_wall(rows: &[Row]) -> Vec<Row> {
    rows.iter()
        .cloned()
        .map(|mut r| {
            r.wall_time_s = 0.0;
            r
        })
        .collect()
}

fn same(a: &[Row], b: &[Row]) -> bool {
    // NaN-aware equality (unstable rows carry NaN values).
    a.len() == b.len()
        && a.iter().zip(b).all(|(x, y)| {
            let f = |p: f64, q: f64| p == q || (p.is_nan() && q.is_nan());
            x.integrator == y.integrator
                && f(x.dt_s, y.dt_s)
                && x.status == y.status
                && x.reason == y.reason
                && x.steps == y.steps
                && x.body == y.body
                && x.quantity == y.quantity
                && f(x.value, y.value)
                && f(x.reference, y.reference)
                && f(x.error_vs_reference, y.error_vs_reference)
                && f(x.error_vs_finest, y.error_vs_finest)
        })
}

#[test]
fn merged_shards_equal_the_unsharded_sweep_row_for_row() {
    let p = prepare(Path::new("scenarios/stokes_single.toml"), None, &[]).unwrap();
    let cases = grid(&Integrator::ALL, &[1e-2, 3e-3, 1e-3, 1e-4, 1e-5]);
    let mut whole = run_cases(&p, &cases).unwrap();
    finish(&mut whole);
    let dir = tempfile::tempdir().unwrap();
    for i in 1..=4 {
        let part = run_cases(&p, &shard(&cases, i, 4)).unwrap();
        crate::sweep::write_rows(&dir.path().join(format!("sweep_part_{i}_of_4.csv")), &part)
            .unwrap();
    }
    let mut merged = Vec::new();
    for i in 1..=4 {
        merged.extend(
            crate::sweep::read_rows(&dir.path().join(format!("sweep_part_{i}_of_4.csv"))).unwrap(),
        );
    }
    finish(&mut merged);
    // Values go through CSV: compare after the same round trip for the unsharded rows.
    crate::sweep::write_rows(&dir.path().join("whole.csv"), &whole).unwrap();
    let whole = crate::sweep::read_rows(&dir.path().join("whole.csv")).unwrap();
    assert!(same(&strip_wall(&whole), &strip_wall(&merged)));
    assert_eq!(whole.len(), 3 * 5 * 3);
}

/// τ = 1.5 ms: the explicit scheme is unstable at 3.5 ms and 1e-2 s, stable at 2.5 ms and below;
/// the exponential scheme is stable and exact everywhere.
#[test]
fn the_sweep_reports_explicit_instability_beyond_two_tau() {
    let p = prepare(Path::new("scenarios/stokes_single.toml"), None, &[]).unwrap();
    let cases = grid(
        &[Integrator::Explicit, Integrator::Exponential],
        &[1e-2, 3.5e-3, 2.5e-3, 1e-4],
    );
    let mut rows = run_cases(&p, &cases).unwrap();
    finish(&mut rows);
    for r in &rows {
        let expect_stable = r.integrator == Integrator::Exponential || r.dt_s < 3e-3;
        assert_eq!(
            r.status == Status::Stable,
            expect_stable,
            "{:?} dt {}",
            r.integrator,
            r.dt_s
        );
        if r.status == Status::Unstable {
            assert!(
                r.reason.contains("fedem-table1") && r.reason.contains("largest stable dt"),
                "{}",
                r.reason
            );
            assert!(r.value.is_nan());
        }
        if r.integrator == Integrator::Exponential {
            assert!(
                r.error_vs_reference.abs() < 1e-6,
                "{} at {}: {}",
                r.quantity,
                r.dt_s,
                r.error_vs_reference
            );
        }
    }
}

/// f-EDEM found the Valentik terminal velocity stable for dt ≤ 0.1 s but v(0.01 s) only for
/// dt ≤ 1e-4 s. Ours: terminal velocity within 0.5 % of the converged value at dt = 0.1 s and
/// v(0.01 s) within 1 % at dt = 1e-3 s (suspension 1, all 27 spheres).
#[test]
fn valentik_accuracy_at_large_steps() {
    let p = prepare(Path::new("scenarios/valentik_susp1.toml"), None, &[]).unwrap();
    let cases = grid(&[Integrator::Exponential], &[1e-1, 1e-3, 1e-4]);
    let mut rows = run_cases(&p, &cases).unwrap();
    finish(&mut rows);
    let sums = summarise(&rows);
    let at = |dt: f64| sums.iter().find(|s| s.dt_s == dt).unwrap();
    assert!(at(1e-1).stable && at(1e-3).stable);
    let term = at(1e-1).errors["terminal_velocity_m_s"].0;
    assert!(term < 0.005, "terminal velocity at dt = 0.1 s: {term}");
    let v01 = at(1e-3).errors["velocity_at_0.01s_m_s"].0;
    assert!(v01 < 0.01, "v(0.01 s) at dt = 1e-3 s: {v01}");
}

/// The 68-ball pour in a sweep (f-EDEM Fig. 20: balls counted at t = 0.5 s; f-EDEM's count is of
/// balls generated, all 68 only for dt ≤ 1.04e-5 s). A reduced pour (10 balls) at two large steps: every case stable, no
/// ball lost, all balls in the domain.
#[test]
fn funnel_pour_sweep_counts_balls_and_loses_none() {
    let p = prepare(
        Path::new("scenarios/paste_68_balls.toml"),
        None,
        &["funnel.count=10".into()],
    )
    .unwrap();
    let cases = grid(&[Integrator::Exponential], &[1e-3, 5e-4]);
    let mut rows = run_cases(&p, &cases).unwrap();
    finish(&mut rows);
    assert_eq!(rows.len(), 2 * 5);
    for r in &rows {
        assert_eq!(r.status, Status::Stable, "{}: {}", r.dt_s, r.reason);
        match r.quantity.as_str() {
            "balls_lost" => assert_eq!(r.value, 0.0),
            "balls_in_domain_at_count" => assert_eq!(r.value, 10.0),
            _ => assert!(r.value.is_finite()),
        }
    }
}

/// `--dt-range 1e-3:1e-1 --per-decade 2`: 1e-1, 10^-1.5, 1e-2, 10^-2.5, 1e-3, round numbers
/// printed round.
#[test]
fn dt_range_is_log_spaced_from_hi_down_to_lo() {
    let v = crate::sweep::dt_range(1e-3, 1e-1, 2);
    assert_eq!(v.len(), 5);
    assert_eq!((v[0], v[2], v[4]), (1e-1, 1e-2, 1e-3));
    assert!((v[1] - 10f64.powf(-1.5)).abs() < 1e-12);
}

/// The shards of a grid are disjoint and together are the grid.
#[test]
fn shards_partition_the_grid() {
    let cases = grid(&Integrator::ALL, &[1e-3, 1e-2, 1e-1, 1e-2]);
    assert_eq!(cases.len(), 3 * 3, "duplicate dt removed");
    let mut all: Vec<_> = (1..=4).flat_map(|i| shard(&cases, i, 4)).collect();
    assert_eq!(all.len(), cases.len());
    all.sort_by(|a, b| {
        format!("{:?}", a.integrator)
            .cmp(&format!("{:?}", b.integrator))
            .then(a.dt_s.total_cmp(&b.dt_s))
    });
    all.dedup();
    assert_eq!(all.len(), cases.len());
}

#[test]
fn option_parsers_accept_the_documented_forms_only() {
    use crate::sweep::{parse_dt, parse_dt_range, parse_shard, parse_tol, DtRange, Shard};
    assert_eq!(parse_shard("2/8"), Ok(Shard { index: 2, count: 8 }));
    for bad in ["0/2", "3/2", "1/0", "2", "a/b", "-1/2"] {
        assert!(parse_shard(bad).is_err(), "{bad}");
    }
    assert_eq!(
        parse_dt_range("1e-8:1e-1"),
        Ok(DtRange {
            lo_s: 1e-8,
            hi_s: 1e-1
        })
    );
    for bad in ["1e-1:1e-8", "0:1", "-1:1", "1e-3", "1e-3:inf", "1e-3:1e-3"] {
        assert!(parse_dt_range(bad).is_err(), "{bad}");
    }
    assert_eq!(parse_tol("1"), Ok(1.0));
    assert_eq!(parse_tol("0.01"), Ok(0.01));
    for bad in ["0", "-1", "5", "1.0000001", "NaN", "x"] {
        assert!(parse_tol(bad).is_err(), "{bad}");
    }
    assert_eq!(parse_dt("1e-3"), Ok(1e-3));
    for bad in ["0", "-1e-3", "inf", "NaN"] {
        assert!(parse_dt(bad).is_err(), "{bad}");
    }
}

/// Typed rows survive the CSV round trip, NaN values and unstable reasons with quotes included.
#[test]
fn rows_round_trip_through_csv() {
    let row = |integrator, dt_s, status, reason: &str, value| Row {
        integrator,
        dt_s,
        status,
        reason: reason.to_string(),
        wall_time_s: 0.25,
        steps: 12,
        body: "b1".into(),
        quantity: "terminal_velocity_m_s".into(),
        value,
        reference: f64::NAN,
        error_vs_reference: f64::NAN,
        error_vs_finest: f64::NAN,
    };
    let rows = vec![
        row(
            Integrator::Explicit,
            1e-2,
            Status::Unstable,
            "use \"exponential\", dt < 3e-3",
            f64::NAN,
        ),
        row(Integrator::Exponential, 1e-5, Status::Stable, "", 1.25e-3),
    ];
    let text = crate::sweep::to_csv(&rows).unwrap();
    let s = String::from_utf8(text.clone()).unwrap();
    assert!(s.starts_with(&crate::sweep::HEADER.join(",")), "{s}");
    assert!(s.contains("explicit,0.01,unstable,"), "{s}");
    assert!(s.contains("exponential,1e-5,stable,,0.25,12,b1"), "{s}");
    let back = crate::sweep::from_csv(text.as_slice()).unwrap();
    assert!(same(&rows, &back));
    assert!(crate::sweep::from_csv(&b"integrator,dt_s\nrk4,1\n"[..]).is_err());
}

/// `finish` takes the finest stable dt as the reference of each integrator, body and quantity.
#[test]
fn error_vs_finest_skips_unstable_cases() {
    let p = prepare(Path::new("scenarios/stokes_single.toml"), None, &[]).unwrap();
    let mut rows = run_cases(&p, &grid(&[Integrator::Explicit], &[1e-2, 1e-3, 1e-4])).unwrap();
    finish(&mut rows);
    for r in &rows {
        match r.status {
            Status::Unstable => assert!(r.error_vs_finest.is_nan()),
            Status::Stable if r.dt_s == 1e-4 => assert_eq!(r.error_vs_finest, 0.0),
            Status::Stable => assert!(r.error_vs_finest.is_finite()),
        }
    }
}

/// Kinds without sweep quantities are refused by the library too, not swept into no rows.
#[test]
fn run_cases_refuses_kinds_it_cannot_sweep() {
    for f in [
        "scenarios/sedimentation_sample1.toml",
        "scenarios/tilt_friction.toml",
        "scenarios/restitution_drop.toml",
    ] {
        let p = prepare(Path::new(f), None, &[]).unwrap();
        let e = run_cases(&p, &grid(&[Integrator::Exponential], &[1e-3])).unwrap_err();
        assert!(matches!(e, crate::error::Error::BadInput(_)), "{f}: {e}");
        assert_eq!(e.exit_code(), 2);
    }
}

/// The command line's arguments and the library's options build the same plan: the options of
/// `--dt-range 1e-5:1e-3 --per-decade 2 --integrator implicit --tol 0.05` as typed values, and
/// the scenario's `[sweep]` table when none is given.
#[test]
fn the_library_options_build_the_command_lines_plan() {
    use crate::sweep::{Args, DtRange, Plan, Shard, SweepOptions};
    let p = prepare(Path::new("scenarios/valentik_susp1.toml"), None, &[]).unwrap();
    let args = Args {
        dt_range: Some(DtRange {
            lo_s: 1e-5,
            hi_s: 1e-3,
        }),
        per_decade: 2,
        integrator: vec![Integrator::Implicit],
        tol: Some(0.05),
        shard: Some(Shard { index: 1, count: 2 }),
        ..Args::default()
    };
    let opts = SweepOptions {
        dt_range: Some((1e-5, 1e-3)),
        per_decade: Some(2),
        integrators: vec!["implicit".into()],
        tol: Some(0.05),
        ..SweepOptions::default()
    };
    let cli = Plan::resolve(&args, &p).unwrap();
    let lib = Plan::new(&opts, &p, args.shard).unwrap();
    assert_eq!(cli, lib);
    assert_eq!(lib.dts_s.len(), 5);
    assert_eq!(lib.integrators, [Integrator::Implicit]);
    // Nothing given: the scenario's [sweep] table (10 dts, all three integrators, tol 0.01).
    let defaults = Plan::new(&SweepOptions::default(), &p, None).unwrap();
    assert_eq!(
        defaults,
        Plan::resolve(
            &Args {
                per_decade: 3,
                ..Args::default()
            },
            &p
        )
        .unwrap()
    );
    assert_eq!(defaults.dts_s.len(), 10);
    assert_eq!(defaults.integrators, Integrator::ALL);
    assert_eq!(defaults.tol, 0.01);
}

/// Each bad option is refused naming the option, as clap refuses it on the command line.
#[test]
fn bad_library_options_name_the_option() {
    use crate::sweep::{Plan, SweepOptions};
    let p = prepare(Path::new("scenarios/stokes_single.toml"), None, &[]).unwrap();
    let dts = vec![1e-3];
    for (opts, option) in [
        (
            SweepOptions {
                dts: vec![f64::NAN],
                ..Default::default()
            },
            "--dt",
        ),
        (
            SweepOptions {
                dts: vec![0.0],
                ..Default::default()
            },
            "--dt",
        ),
        (
            SweepOptions {
                dt_range: Some((1e-3, f64::INFINITY)),
                ..Default::default()
            },
            "--dt-range",
        ),
        (
            SweepOptions {
                dts: dts.clone(),
                dt_range: Some((1e-5, 1e-3)),
                ..Default::default()
            },
            "--dt-range",
        ),
        (
            SweepOptions {
                dt_range: Some((1e-5, 1e-3)),
                per_decade: Some(0),
                ..Default::default()
            },
            "--per-decade",
        ),
        (
            SweepOptions {
                dts: dts.clone(),
                tol: Some(0.0),
                ..Default::default()
            },
            "--tol",
        ),
        (
            SweepOptions {
                dts: dts.clone(),
                integrators: vec!["Explicit".into()],
                ..Default::default()
            },
            "--integrator",
        ),
    ] {
        match Plan::new(&opts, &p, None) {
            Err(crate::error::Error::BadInput(b)) => {
                assert_eq!(b.key.as_deref(), Some(option), "{opts:?}: {}", b.message)
            }
            other => panic!("{opts:?}: {other:?}"),
        }
    }
}
