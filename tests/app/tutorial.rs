//! The README's first commands and its tutorial, run as a reader would.
//!
//! The tutorial is the part of `README.md` between `<!-- tutorial -->` and `<!-- /tutorial -->`.
//! Each ```` ```toml ```` block is written to the file the prose line before it names
//! (`` Save this as `ball.toml`: ``); each line of a ```` ```sh ```` block is a `settle` command,
//! run with this build's binary in an empty temporary folder, in order; every output file the
//! prose names in backticks (`` `out/steel_ball/summary.csv` ``) must exist afterwards. The
//! figures the tutorial states are checked against what the runs wrote.

use crate::common::{read_csv, settle, tmp};
use std::path::Path;

const README: &str = include_str!("../../README.md");
const CI: &str = include_str!("../../.ci/run");

/// What the tutorial asks the reader to do.
struct Tutorial {
    /// Files to write: name and text.
    files: Vec<(String, String)>,
    /// `settle` commands: the arguments after `settle`.
    commands: Vec<Vec<String>>,
    /// Output files the prose names, relative to the working folder.
    outputs: Vec<String>,
}

/// The arguments of a tutorial command line, after `settle` (or `cargo run --release --`).
fn settle_args(line: &str) -> Vec<String> {
    let rest = line
        .strip_prefix("settle ")
        .or_else(|| line.strip_prefix("cargo run --release -- "))
        .unwrap_or_else(|| panic!("a tutorial command must start with `settle`: {line}"));
    assert!(
        !rest.contains(['\'', '"', '$', '|', '>', '<']),
        "tutorial commands are plain words (no quoting or shell syntax): {line}"
    );
    rest.split_whitespace().map(str::to_string).collect()
}

/// Reads the tutorial out of the README.
fn tutorial() -> Tutorial {
    let start = README
        .find("<!-- tutorial -->")
        .expect("<!-- tutorial --> in README.md");
    let end = README
        .find("<!-- /tutorial -->")
        .expect("<!-- /tutorial --> in README.md");
    let text = &README[start..end];
    let mut t = Tutorial {
        files: Vec::new(),
        commands: Vec::new(),
        outputs: Vec::new(),
    };
    let mut prose = String::new();
    let mut last_prose_line = "";
    let mut lines = text.lines();
    while let Some(line) = lines.next() {
        let Some(info) = line.strip_prefix("```") else {
            prose.push_str(line);
            prose.push('\n');
            if !line.trim().is_empty() {
                last_prose_line = line;
            }
            continue;
        };
        let block: Vec<&str> = lines
            .by_ref()
            .take_while(|l| !l.starts_with("```"))
            .collect();
        match info {
            "toml" => {
                let name = last_prose_line
                    .split('`')
                    .rev()
                    .find(|w| w.ends_with(".toml"))
                    .unwrap_or_else(|| {
                        panic!("no file name before a toml block: {last_prose_line}")
                    });
                t.files.push((name.to_string(), block.join("\n") + "\n"));
            }
            "sh" => t.commands.extend(
                block
                    .iter()
                    .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
                    .map(|l| settle_args(l)),
            ),
            other => panic!("a tutorial block is ```toml or ```sh, not ```{other}"),
        }
    }
    // The output folders: `out` (the default) and every `--out`.
    let mut roots = vec!["out".to_string()];
    for c in &t.commands {
        if let Some(i) = c.iter().position(|a| a == "--out") {
            roots.push(c[i + 1].clone());
        }
    }
    for w in prose.split('`').skip(1).step_by(2) {
        let first = w.split('/').next().unwrap_or("");
        let last = w.rsplit('/').next().unwrap_or("");
        if w.contains('/')
            && last.contains('.')
            && !w.contains(' ')
            && roots.iter().any(|r| r == first)
        {
            t.outputs.push(w.to_string());
        }
    }
    t
}

/// Whether the README says `words` (line breaks and runs of spaces read as one space).
fn readme_says(words: &str) -> bool {
    let flat = README.split_whitespace().collect::<Vec<_>>().join(" ");
    flat.contains(words)
}

/// The column `col` of the first row of a CSV the tutorial's runs wrote.
fn first_row(path: &Path, col: &str) -> String {
    let (header, rows) = read_csv(path);
    let i = header
        .iter()
        .position(|h| h == col)
        .unwrap_or_else(|| panic!("no {col} in {}", path.display()));
    rows[0][i].clone()
}

/// Every tutorial command exits 0, and every file the
/// tutorial names appears; the figures its prose states are those the runs wrote.
#[test]
fn the_tutorial_runs_and_writes_the_files_it_names() {
    let t = tutorial();
    assert!(
        !t.files.is_empty() && t.commands.len() >= 3,
        "tutorial found"
    );
    let dir = tmp();
    for (name, text) in &t.files {
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    let mut ran = 0;
    for args in &t.commands {
        let line = args.join(" ");
        let out = settle()
            .args(args)
            .arg("--quiet")
            .current_dir(dir.path())
            .output()
            .expect("spawn settle");
        assert!(
            out.status.success(),
            "settle {line}: {:?}\n{}",
            out.status.code(),
            String::from_utf8_lossy(&out.stderr)
        );
        ran += 1;
    }
    assert!(ran >= 5, "{ran} commands ran");
    assert!(
        t.outputs.len() >= 6,
        "the tutorial names its files: {:?}",
        t.outputs
    );
    for f in &t.outputs {
        let meta = std::fs::metadata(dir.path().join(f))
            .unwrap_or_else(|e| panic!("the tutorial names `{f}`: {e}"));
        assert!(meta.len() > 0, "`{f}` is empty");
    }
    // Step 2: "the simulated terminal velocity (0.2067 m/s) … Re′ = 2.36".
    let summary = dir.path().join("out/steel_ball/summary.csv");
    let v: f64 = first_row(&summary, "v_simulated_m_s").parse().unwrap();
    let re: f64 = first_row(&summary, "re_bingham").parse().unwrap();
    assert!(
        readme_says("terminal velocity (0.2067 m/s)") && (v - 0.2067).abs() < 5e-5,
        "v = {v}"
    );
    assert!(
        readme_says("Re′ = 2.36") && (re - 2.36).abs() < 5e-3,
        "Re′ = {re}"
    );
    assert_eq!(first_row(&summary, "regime"), "1<=re<=150");
    let vs_balance: f64 = first_row(&summary, "rel_error_vs_force_balance")
        .parse()
        .unwrap();
    assert!(
        readme_says("(the same within 3e-7)") && vs_balance.abs() < 3e-7,
        "{vs_balance}"
    );
    // Step 4: "1e-2 s for the default `exponential` integrator, 1e-4 s (the finest tried, so
    // marked unverified) for `explicit`".
    assert!(readme_says("1e-2 s for the default `exponential` integrator, 1e-4 s (the finest tried, so marked unverified) for `explicit`"));
    let (header, rows) = read_csv(&dir.path().join("out/steel_ball_sweep/recommended_dt.csv"));
    let col = |name: &str| header.iter().position(|h| h == name).expect(name);
    let rec = |integ: &str| {
        let r = rows
            .iter()
            .find(|r| r[col("integrator")] == integ)
            .expect(integ);
        (
            r[col("recommended_dt_s")].parse::<f64>().unwrap(),
            r[col("verified")].clone(),
        )
    };
    assert_eq!(rec("exponential"), (1e-2, "true".to_string()));
    assert_eq!(rec("explicit"), (1e-4, "false".to_string()));
    // Step 3: at 30 Pa the ball never moves.
    let held = dir.path().join("out30/steel_ball/summary.csv");
    assert_eq!(first_row(&held, "regime"), "static");
    assert_eq!(first_row(&held, "v_simulated_m_s"), "0");
}

/// Step 5 says the ball moves up to 27.5 Pa (at 0.00906 m/s) and is held from 30 Pa (the grid
/// 10:40:13), and step 3 that the threshold is 27.9 Pa: checked with `--vary` and `--set`.
#[test]
fn the_yield_stress_that_holds_the_tutorial_ball() {
    let t = tutorial();
    let dir = tmp();
    for (name, text) in &t.files {
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    assert!(readme_says(
        "the ball moves up to 27.5 Pa (0.00906 m/s) and is held from 30 Pa"
    ));
    let out = settle()
        .args(["sweep", "ball.toml", "--quiet", "--vary"])
        .arg("fluid.yield_stress_pa=27.5,30")
        .current_dir(dir.path())
        .output()
        .expect("spawn settle");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (h, rows) = read_csv(&dir.path().join("out/steel_ball_vary/vary.csv"));
    let c = |n: &str| h.iter().position(|x| x == n).expect(n);
    let v = |i: usize| rows[i][c("terminal_velocity_m_s")].parse::<f64>().unwrap();
    assert_eq!(rows[0][c("fluid.yield_stress_pa")], "27.5");
    assert!((v(0) / 0.00906 - 1.0).abs() < 5e-4, "{}", v(0));
    assert_eq!(v(1), 0.0);
    assert!(readme_says("exceeds its net weight from τ_y = 27.9 Pa"));
    for (tau, regime_static) in [("27.5", false), ("27.8", false), ("27.9", true)] {
        let out_dir = format!("o{tau}");
        let out = settle()
            .args(["run", "ball.toml", "--quiet", "--out", &out_dir])
            .arg(format!("--set=fluid.yield_stress_pa={tau}"))
            .current_dir(dir.path())
            .output()
            .expect("spawn settle");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let regime = first_row(
            &dir.path().join(out_dir).join("steel_ball/summary.csv"),
            "regime",
        );
        assert_eq!(
            regime == "static",
            regime_static,
            "τ_y = {tau} Pa: {regime}"
        );
    }
}

/// The README opens with the two commands a newcomer needs: the main job, and exactly the test
/// command `.ci/run` runs last, which runs every test, Rust and Python.
#[test]
fn the_readme_opens_with_the_main_job_and_the_ci_test_command() {
    let blocks: Vec<&str> = README.split("```").skip(1).step_by(2).take(2).collect();
    assert_eq!(
        blocks[0].trim(),
        "cargo run --release -- run scenarios/valentik_susp1.toml"
    );
    let ci_last = CI.lines().rev().find(|l| !l.trim().is_empty()).unwrap();
    assert_eq!(blocks[1].trim(), ci_last.trim());
    assert_eq!(ci_last, "scripts/test.sh");
    let script = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scripts/test.sh"))
        .expect("scripts/test.sh");
    for step in ["cargo test --release", "scripts/test_python.sh"] {
        assert!(
            script.lines().any(|l| l.trim() == step),
            "scripts/test.sh runs `{step}` (every test: Rust and Python)"
        );
    }
    assert!(
        README.find("```").unwrap() < README.find("<!-- tutorial -->").unwrap(),
        "the commands come before the tutorial"
    );
}
