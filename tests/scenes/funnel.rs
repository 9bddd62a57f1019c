//! The funnel pour (f-EDEM §4.2) as `settle run` writes it, through the library API; the
//! scene's and its engine features' own tests are unit tests (`src/scenes/funnel_pour/tests/`).

use crate::common::tmp;

const SCENARIO: &str = "scenarios/paste_68_balls.toml";

/// The overrides of a small pour (8 balls, 0.5 s, two repeats).
const SMALL: [&str; 7] = [
    "funnel.count=8",
    "funnel.fill_time_s=0.15",
    "funnel.count_time_s=0.4",
    "time.end_s=0.5",
    "time.dt_s=2e-5",
    "repeats.count=2",
    "repeats.seed=7",
];

#[test]
fn settle_run_writes_the_funnel_outputs() {
    let mut s = settle::load(SCENARIO).expect("scenario");
    for set in SMALL.iter().chain(&["funnel.count=4", "repeats.count=2"]) {
        let (key, value) = set.split_once('=').unwrap();
        s = s.set(key, value).expect("override");
    }
    let report = s.run().expect("runs");
    let dir = tmp();
    let out = &report.write(dir.path()).expect("writes");
    for f in [
        "balls.csv",
        "counts.csv",
        "timeseries.csv",
        "z_distribution.csv",
        "z_distribution.svg",
        "presence.csv",
        "presence.svg",
        "run.toml",
    ] {
        assert!(out.join(f).exists(), "{f} missing");
    }
    let balls = std::fs::read_to_string(out.join("balls.csv")).unwrap();
    assert_eq!(balls.lines().count(), 1 + 4 * 2);
    assert!(balls.starts_with("repeat,seed,ball,diameter_m,x_m,y_m,z_m,speed_m_s,place"));
    let presence = std::fs::read_to_string(out.join("presence.csv")).unwrap();
    let mut planes = std::collections::BTreeSet::new();
    for line in presence.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        assert!((0.0..=1.0).contains(&v[3]));
        planes.insert((v[0] * 1e4).round() as i64);
    }
    assert_eq!(planes.len(), 6, "Z = 13.5 … 8.5 cm");
    assert!(report.lines().iter().any(|l| l.contains("8.5–13.5 cm")));
}
