//! Random mutations of the good scenarios never make the loader panic (moved from
//! `tests/scenario/bad_input.rs`, whose cases go through `settle run`): `load_str` returns `Ok`
//! or `Err` (one line), never panics.

use proptest::prelude::*;
use proptest::test_runner::Config;
use std::path::Path;

const GOOD: [&str; 2] = [
    include_str!("../../../scenarios/stokes_single.toml"),
    include_str!("../../../scenarios/valentik_susp1.toml"),
];

const KEYS: &[&str] = &[
    "name",
    "kind",
    "dimension",
    "physics",
    "engine",
    "gravity_m_s2",
    "description",
    "fluid.density_kg_m3",
    "fluid.rheology",
    "fluid.viscosity_pa_s",
    "fluid.plastic_viscosity_pa_s",
    "fluid.yield_stress_pa",
    "drag.law",
    "drag.voidage",
    "time.dt_s",
    "time.end_s",
    "time.integrator",
    "container.height_m",
    "container.diameter_m",
    "container.width_m",
    "release.depth_m",
    "release.velocity_m_s",
    "spheres",
    "spheres_csv.path",
    "spheres_csv.suspension",
    "measure.section_top_depth_m",
    "measure.section_bottom_depth_m",
    "measure.terminal_window_m",
    "measure.velocity_at_s",
    "measure.steady_tolerance",
    "record.every_s",
    "record.timeseries",
    "sweep.dt_s",
    "sweep.tol",
    "sweep.integrators",
    "fluid",
    "time",
    "x",
    "\"we\\nird\"",
    "a.\"b\\nc\"",
    "diameter_m",
    "poisson_ratio",
    "dt_s",
];

const VALUES: &[&str] = &[
    "0",
    "-1",
    "1",
    "3",
    "2",
    "300",
    "-0.0",
    "0.5",
    "0.7",
    "1e308",
    "-1e308",
    "1e-308",
    "nan",
    "-nan",
    "inf",
    "-inf",
    "true",
    "\"\"",
    "\"../../etc\"",
    "\"bingham\"",
    "\"newtonian\"",
    "\"bingham-fedem\"",
    "\"rk4\"",
    "\"stokes\"",
    "\"é\\n\"",
    "[]",
    "[1, nan]",
    "[-1.0, 0.0]",
    "{}",
    "[{diameter_m = 1e-4, density_kg_m3 = 2000.0}]",
    "[{diameter_m = nan, density_kg_m3 = -1.0}]",
    "{ dt_s = 1, end_s = 1 }",
    "1979-05-27T07:32:00Z",
    "9223372036854775807",
    "-9223372036854775808",
];

const OVERRIDE_KEYS: &[&str] = &[
    "spheres[0].diameter_m",
    "spheres[9].diameter_m",
    "spheres[x].diameter_m",
    "spheres[0]",
    "spheres_csv.path.x",
    "a..b",
    ".",
    "",
    "name.x",
    "time.dt_s.x",
];

#[derive(Clone, Debug)]
enum Mutation {
    /// Replace the byte at this fraction of the text.
    Replace(usize, u8),
    /// Insert a byte.
    Insert(usize, u8),
    /// Delete a run of bytes.
    Delete(usize, usize),
    /// Insert the line `KEY = VALUE` before the line at this index.
    Line(usize, &'static str, &'static str),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    // Bytes biased towards TOML syntax.
    let byte = prop_oneof![
        3 => prop::sample::select(b"=[]{}\".,#'\n-+0123456789eE_ ".to_vec()),
        1 => any::<u8>(),
    ];
    prop_oneof![
        (any::<usize>(), byte.clone()).prop_map(|(i, b)| Mutation::Replace(i, b)),
        (any::<usize>(), byte).prop_map(|(i, b)| Mutation::Insert(i, b)),
        (any::<usize>(), 1usize..20).prop_map(|(i, n)| Mutation::Delete(i, n)),
        (
            any::<usize>(),
            prop::sample::select(KEYS),
            prop::sample::select(VALUES)
        )
            .prop_map(|(i, k, v)| Mutation::Line(i, k, v)),
    ]
}

fn apply(text: &str, muts: &[Mutation]) -> String {
    let mut bytes = text.as_bytes().to_vec();
    for m in muts {
        let n = bytes.len().max(1);
        match *m {
            Mutation::Replace(i, b) => {
                if !bytes.is_empty() {
                    bytes[i % n] = b;
                }
            }
            Mutation::Insert(i, b) => bytes.insert(i % (bytes.len() + 1), b),
            Mutation::Delete(i, len) => {
                let start = i % n;
                let end = (start + len).min(bytes.len());
                bytes.drain(start.min(end)..end);
            }
            Mutation::Line(i, k, v) => {
                let s = String::from_utf8_lossy(&bytes).into_owned();
                let mut lines: Vec<&str> = s.lines().collect();
                let line = format!("{k} = {v}");
                lines.insert(i % (lines.len() + 1), &line);
                bytes = lines.join("\n").into_bytes();
            }
        }
    }
    String::from_utf8_lossy(&bytes).into_owned()
}

fn override_strategy() -> impl Strategy<Value = Vec<String>> {
    let key = prop_oneof![
        prop::sample::select(KEYS),
        prop::sample::select(OVERRIDE_KEYS)
    ];
    let one = prop_oneof![
        4 => (key, prop::sample::select(VALUES)).prop_map(|(k, v)| format!("{k}={v}")),
        1 => "[a-z_.\\[\\]0-9=\"-]{0,12}",
    ];
    prop::collection::vec(one, 0..3)
}

proptest! {
    #![proptest_config(Config {
        cases: 200,
        // Keep regressions out of the source tree (tests/proptest-regressions/); a failure
        // prints the minimal input to add as a case instead.
        failure_persistence: None,
        ..Config::default()
    })]

    #[test]
    fn load_str_never_panics(
        which in 0usize..2,
        muts in prop::collection::vec(mutation(), 1..6),
        overrides in override_strategy(),
    ) {
        let text = apply(GOOD[which], &muts);
        // Ok or Err both fine; a panic fails the test. An error is one line.
        if let Err(e) = crate::scenario::load_str(&text, Path::new("fuzz.toml"), &overrides) {
            let line = e.to_string();
            prop_assert_eq!(line.lines().count(), 1, "error is not one line: {:?}", line);
            prop_assert!(line.starts_with("fuzz.toml: "), "error does not name the file: {}", line);
        }
    }
}
