//! Validation case of issue 16: ten Cate et al. (2002), a 15 mm nylon sphere settling onto the
//! bottom of a 100 × 100 × 160 mm box of silicone oil (`scenarios/ten_cate_e1.toml` … `e4`),
//! against the measured v(t) and gap of their Fig. 5 (digitised, `data/ten_cate_2002/`, with
//! their source) and the measured peak speeds u_max = (u_max/u∞) u∞ of their Table II.
//!
//! u∞ (Table I: 0.038, 0.060, 0.091, 0.128 m/s) is *not* a measurement: it is the terminal speed
//! in an unbounded fluid from Abraham's (1970) drag correlation (their eq. 1). The box slows the
//! sphere to u_max/u∞ = 0.947, 0.953, 0.959, 0.955 (Table II, as quoted in third-party benchmark
//! notes; data/ten_cate_2002/README.md). Errors of v(t) are RMS over the measured points up to
//! the time the measured gap reaches one diameter, divided by u∞ (the paper's velocity scale);
//! the simulated v is interpolated linearly in its 5 ms records; release from rest at t = 0 in
//! both (no time shift).

use crate::common::{read_csv_records, settle, tmp};

/// Table I: u∞ in an unbounded fluid (Abraham's correlation), m/s.
const U_INF: [f64; 4] = [0.038, 0.060, 0.091, 0.128];
/// Table II: measured u_max/u∞.
const PEAK_RATIO: [f64; 4] = [0.947, 0.953, 0.959, 0.955];

/// (t, v, gap) of one run, s, m/s, m.
type Series = Vec<(f64, f64, f64)>;

/// The four experiments run with `set`.
fn series(set: &[&str]) -> Vec<Series> {
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
                .map(|r| {
                    let f = |k: &str| r[k].parse::<f64>().unwrap();
                    (f("time_s"), f("velocity_m_s"), f("gap_to_bottom_m"))
                })
                .collect()
        })
        .collect()
}

/// Columns `a`, `b` of `data/ten_cate_2002/ten_cate_e{e}_{what}.csv`.
fn measured(e: usize, what: &str, a: &str, b: &str) -> Vec<(f64, f64)> {
    let path = format!("data/ten_cate_2002/ten_cate_e{e}_{what}.csv");
    read_csv_records(std::path::Path::new(&path))
        .iter()
        .map(|r| (r[a].parse().unwrap(), r[b].parse().unwrap()))
        .collect()
}

fn interp(xy: &[(f64, f64)], x: f64) -> f64 {
    if x <= xy[0].0 {
        return xy[0].1;
    }
    for w in xy.windows(2) {
        if x <= w[1].0 {
            return w[0].1 + (x - w[0].0) / (w[1].0 - w[0].0) * (w[1].1 - w[0].1);
        }
    }
    xy[xy.len() - 1].1
}

/// Time at which the measured gap reaches one diameter, s (linear between digitised points).
fn cut_time(e: usize) -> f64 {
    let g = measured(e, "gap", "time_s", "gap_over_diameter");
    let i = g.iter().position(|p| p.1 <= 1.0).expect("reaches 1 d");
    let (a, b) = (g[i - 1], g[i]);
    a.0 + (a.1 - 1.0) / (a.1 - b.1) * (b.0 - a.0)
}

/// RMS of v_sim − v_measured over the measured points before the gap reaches one diameter,
/// divided by u∞, for each experiment.
fn rms(sim: &[Series]) -> Vec<f64> {
    (1..=4)
        .map(|e| {
            let v: Vec<(f64, f64)> = sim[e - 1].iter().map(|p| (p.0, p.1)).collect();
            let tc = cut_time(e);
            let pts: Vec<(f64, f64)> = measured(e, "velocity", "time_s", "velocity_m_s")
                .into_iter()
                .filter(|p| p.0 <= tc)
                .collect();
            let ss: f64 = pts.iter().map(|p| (interp(&v, p.0) - p.1).powi(2)).sum();
            (ss / pts.len() as f64).sqrt() / U_INF[e - 1]
        })
        .collect()
}

fn peaks(sim: &[Series]) -> Vec<f64> {
    sim.iter()
        .map(|s| s.iter().map(|p| p.1).fold(0.0, f64::max))
        .collect()
}

fn pct(x: &[f64]) -> String {
    x.iter()
        .map(|v| format!("{:+.1} %", 100.0 * v))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The two digitised curves of each experiment agree: the distance the velocity curve integrates
/// to (from rest at t = 0) until the gap curve reaches one diameter is the 7 d = 0.105 m the gap
/// curve falls, within 10 % (+8.4, +5.4, +2.4, +4.5 %: the E1 and E2 velocity curves run high,
/// as their peaks against Table II show); the digitised peaks are Table II's u_max within 5 %.
#[test]
fn the_measured_curves_agree_with_each_other_and_with_table_ii() {
    for e in 1..=4 {
        let tc = cut_time(e);
        let mut pts = vec![(0.0, 0.0)];
        pts.extend(measured(e, "velocity", "time_s", "velocity_m_s"));
        let mut dist = 0.0;
        for w in pts.windows(2) {
            let (a, b) = (w[0], w[1]);
            let t1 = b.0.min(tc);
            let v1 = a.1 + (t1 - a.0) / (b.0 - a.0) * (b.1 - a.1);
            dist += 0.5 * (a.1 + v1) * (t1 - a.0);
            if b.0 >= tc {
                break;
            }
        }
        let err = dist / (7.0 * 0.015) - 1.0;
        assert!(err.abs() < 0.10, "E{e}: distance {dist} m ({err:+})");
        let peak = measured(e, "velocity", "time_s", "velocity_m_s")
            .iter()
            .map(|p| p.1)
            .fold(0.0, f64::max);
        let table = PEAK_RATIO[e - 1] * U_INF[e - 1];
        assert!((peak / table - 1.0).abs() < 0.05, "E{e}: {peak} vs {table}");
    }
}

/// v(t) against the measured curves (RMS / u∞ up to a gap of one diameter):
///
/// | model | E1 | E2 | E3 | E4 |
/// |---|---|---|---|---|
/// | quasi-steady, no wall | 27.0 % | 25.5 % | 26.8 % | 26.3 % |
/// | added mass + Brenner (the scenarios) | 22.3 % | 21.7 % | 17.9 % | 16.1 % |
/// | added mass + Basset, no wall | 6.0 % | 7.7 % | 7.9 % | 9.1 % |
/// | added mass + Mei–Adrian + Brenner | 10.8 % | 11.3 % | 7.3 % | 5.2 % |
/// | the same, kernel at the current Re | 8.2 % | 9.0 % | 5.0 % | 3.9 % |
///
/// The quasi-steady sphere reaches its terminal speed in ~0.1 s, the measured one in 0.5–1 s:
/// the history force is what the start needs. Basset's kernel is best at Re 1.5–4 and too slow
/// at Re 12–32; Mei & Adrian's is best there, with its Re following the body's (the memory
/// then fades only as the sphere speeds up): within 5 % of u∞ at E3 and E4. Not at E1–E2:
/// without the side walls (d/W = 0.15, not modelled) the plateaus are off by 1–6 %.
#[test]
fn v_of_t_against_the_measured_curves() {
    let qs = rms(&series(&[
        "transient.added_mass=false",
        "transient.wall=off",
    ]));
    let scen = rms(&series(&[]));
    let basset = rms(&series(&["transient.wall=off", "transient.history=basset"]));
    let mei = rms(&series(&["transient.history=mei-adrian"]));
    let cur = rms(&series(&[
        "transient.history=mei-adrian",
        "transient.history_reynolds=current",
    ]));
    eprintln!(
        "RMS/u∞ quasi-steady [{}], added mass + Brenner [{}], + Basset no wall [{}], \
         + Mei–Adrian + Brenner [{}], the same at the current Re [{}]",
        pct(&qs),
        pct(&scen),
        pct(&basset),
        pct(&mei),
        pct(&cur)
    );
    assert!(cur[2] < 0.051 && cur[3] < 0.045, "{cur:?}");
    assert!(cur.iter().zip(&mei).all(|(c, m)| c < m), "{cur:?} {mei:?}");
    for e in 0..4 {
        assert!(qs[e] > 0.2, "quasi-steady E{}: {}", e + 1, qs[e]);
        assert!(scen[e] > 0.12, "added mass alone E{}: {}", e + 1, scen[e]);
        assert!(basset[e] < 0.10, "Basset E{}: {}", e + 1, basset[e]);
        // The best transient model is at least 2.5× closer than the quasi-steady one.
        assert!(basset[e].min(mei[e]) < qs[e] / 2.5, "E{}", e + 1);
    }
    assert!(basset[0] < 0.07 && basset[1] < 0.085, "{basset:?}");
    assert!(mei[2] < 0.08 && mei[3] < 0.06, "{mei:?}");
    assert!(
        mei[3] < basset[3] && mei[2] < basset[2],
        "{mei:?} {basset:?}"
    );
    assert!(
        basset[0] < mei[0] && basset[1] < mei[1],
        "{mei:?} {basset:?}"
    );
}

/// Peak speed against the measured u_max of Table II. With added mass and Brenner's bottom
/// correction (the scenarios as written): E3 +0.5 %, E4 −2.0 % (within 3 %); E1 +6.3 %, E2
/// +4.0 % too fast (the side walls, not modelled, slow the sphere most at low Re, where the
/// Oseen length ν/u is longest: 10 mm at E1, 0.5 mm at E4). Against the digitised curves'
/// peaks: +4.2, −0.4, +1.1, −2.1 %. The quasi-steady model without any wall is 5–14 % fast.
#[test]
fn peak_velocities_against_the_measured_ones() {
    let umax: Vec<f64> = (0..4).map(|e| PEAK_RATIO[e] * U_INF[e]).collect();
    let sim = peaks(&series(&[]));
    let err: Vec<f64> = sim.iter().zip(&umax).map(|(s, m)| s / m - 1.0).collect();
    eprintln!(
        "added mass + Brenner against Table II u_max: [{}]",
        pct(&err)
    );
    assert!(err[2].abs() <= 0.03 && err[3].abs() <= 0.03, "{err:?}");
    assert!(err[0] > 0.03 && err[0] < 0.08, "{err:?}");
    assert!(err[1] > 0.02 && err[1] < 0.06, "{err:?}");
    let curve: Vec<f64> = (1..=4)
        .map(|e| {
            measured(e, "velocity", "time_s", "velocity_m_s")
                .iter()
                .map(|p| p.1)
                .fold(0.0, f64::max)
        })
        .collect();
    let err_c: Vec<f64> = sim.iter().zip(&curve).map(|(s, m)| s / m - 1.0).collect();
    eprintln!("against the digitised peaks: [{}]", pct(&err_c));
    assert!(err_c[1..].iter().all(|e| e.abs() <= 0.03), "{err_c:?}");
    let qs = peaks(&series(&[
        "transient.added_mass=false",
        "transient.wall=off",
    ]));
    let err_qs: Vec<f64> = qs.iter().zip(&umax).map(|(s, m)| s / m - 1.0).collect();
    eprintln!(
        "quasi-steady, no wall, against Table II: [{}]",
        pct(&err_qs)
    );
    assert!(err_qs.iter().all(|e| *e > 0.05), "{err_qs:?}");
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
/// still 9 % short of the measured u_max when the bottom stops it; Mei & Adrian's kernel, whose
/// memory fades as t^{−2} after t_c ≈ 0.07 s there, reaches the quasi-steady plateau.
#[test]
fn the_basset_kernel_overstates_the_memory_at_finite_re() {
    let umax = PEAK_RATIO[3] * U_INF[3];
    let basset = peaks(&series(&["transient.history=basset", "transient.wall=off"]));
    assert!(basset[3] < 0.93 * umax, "{basset:?}");
    let mei = peaks(&series(&[
        "transient.history=mei-adrian",
        "transient.wall=off",
    ]));
    let qs = peaks(&series(&["transient.wall=off"]));
    assert!((mei[3] / qs[3] - 1.0).abs() < 0.01, "{mei:?} vs {qs:?}");
}
