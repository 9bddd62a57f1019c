//! Validation case of issue 16: ten Cate et al. (2002), a 15 mm nylon sphere settling onto the
//! bottom of a 100 × 100 × 160 mm box of silicone oil (`scenarios/ten_cate_e1.toml` … `e4`),
//! against the measured terminal velocities 0.038, 0.060, 0.091, 0.128 m/s (their Table 1).
//! The simulated terminal velocity is the peak speed before the bottom slows the sphere.

use crate::common::{read_csv_records, settle, tmp};

const MEASURED: [f64; 4] = [0.038, 0.060, 0.091, 0.128];

/// Peak downward speed of each experiment, run with `set` (m/s).
fn peaks(set: &[&str]) -> Vec<f64> {
    let out = tmp();
    let mut cmd = settle();
    cmd.arg("run").arg("-q").arg("--out").arg(out.path());
    for e in 1..=4 {
        cmd.arg(format!("scenarios/ten_cate_e{e}.toml"));
    }
    for s in set {
        cmd.arg("--set").arg(s);
    }
    let o = cmd.output().expect("settle runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    (1..=4)
        .map(|e| {
            let path = out.path().join(format!("ten_cate_e{e}/timeseries.csv"));
            read_csv_records(&path)
                .iter()
                .map(|r| r["velocity_m_s"].parse::<f64>().unwrap())
                .fold(0.0, f64::max)
        })
        .collect()
}

/// With added mass and Brenner's bottom correction (the scenarios as written), E1 and E2
/// (Re 1.5, 4.1) are within 3 % of the measured terminal velocity; E3 and E4 (Re 12, 32), where
/// Brenner's creeping-flow factor overstates the wall's reach, within 7 % (low). The quasi-steady
/// model without any wall overshoots E1 by 7.5 %: the side walls, not modelled, slow E1 and E2.
#[test]
fn terminal_velocities_against_the_measured_ones() {
    let sim = peaks(&[]);
    let err: Vec<f64> = sim.iter().zip(MEASURED).map(|(s, m)| s / m - 1.0).collect();
    eprintln!("added mass + Brenner: relative errors {err:?}");
    assert!(err[0].abs() <= 0.03 && err[1].abs() <= 0.03, "{err:?}");
    assert!(err[2].abs() <= 0.07 && err[3].abs() <= 0.07, "{err:?}");
    let qs = peaks(&["transient.added_mass=false", "transient.wall=off"]);
    let err_qs: Vec<f64> = qs.iter().zip(MEASURED).map(|(s, m)| s / m - 1.0).collect();
    eprintln!("quasi-steady, no wall: relative errors {err_qs:?}");
    assert!(err_qs[0] > 0.05 && err_qs[3].abs() < 0.02, "{err_qs:?}");
}

/// The time series gives the gap to the bottom, like the paper's figures: 120 mm at release
/// (centre 127.5 mm up, radius 7.5 mm), shrinking to under a millimetre by the end.
#[test]
fn the_gap_to_the_bottom_is_written() {
    let out = tmp();
    let o = settle()
        .args(["run", "-q", "--out"])
        .arg(out.path())
        .arg("scenarios/ten_cate_e4.toml")
        .output()
        .expect("settle runs");
    assert!(o.status.success());
    let rows = read_csv_records(&out.path().join("ten_cate_e4/timeseries.csv"));
    let gap = |r: &std::collections::HashMap<String, String>| {
        r["gap_to_bottom_m"].parse::<f64>().unwrap()
    };
    assert!((gap(&rows[0]) - 0.12).abs() < 1e-12);
    let last = gap(rows.last().unwrap());
    assert!(last > 0.0 && last < 1e-3, "{last}");
}

/// With the Basset kernel the memory is overstated at these Re: at E4 (Re 32) the sphere is
/// still well short of u_inf when the bottom stops it.
#[test]
fn the_basset_kernel_overstates_the_memory_at_finite_re() {
    let sim = peaks(&["transient.history=basset", "transient.wall=off"]);
    assert!(sim[3] < 0.9 * MEASURED[3], "{sim:?}");
}
