//! The bad-input suite of issue 26 (acceptance): every command on the command line and its
//! output folder, table-driven from `bad_input_cases.txt` (the format is at its top). Each case
//! runs in a fresh folder holding the fixtures (its working directory), and is classified:
//!
//! - **clear**: the exit code expected, a message with every expected word (the file, key or
//!   option, and the allowed range or the fix), no programmer's words (type names, parser
//!   jargon, `os error`, float noise such as `0.004300000000000004`), nothing written;
//! - **unclear**: refused, but with another exit code, a message missing a word or holding
//!   jargon, or something written;
//! - **silent**: exit 0 (the bad input accepted);
//! - **data loss**: a file that was there before changed or disappeared;
//! - **hang**: still running after [`HANG`] (killed).
//!
//! The test prints the counts and fails unless every case is clear. With `SETTLE_BIN` set to
//! another binary (e.g. the one before issue 26) it prints that binary's counts.
//! Lab files (readings, spheres, fluids, measurements with bad content) are
//! `bad_lab_inputs.rs`'s; bad scenario files are `tests/bad_scenarios/`'s.

use crate::common::{settle, tmp, HANG};
use std::collections::BTreeMap;
use std::path::Path;
use std::process::Stdio;
use std::time::Instant;

const CASES: &str = include_str!("bad_input_cases.txt");

/// A folder nothing can be written in, even by root (sysfs refuses new entries).
const READ_ONLY: &str = "/sys/settle-bad-input";

/// Words no message may hold: Rust's type names and parser errors, clap's reading of a negative
/// number as an option.
const JARGON: &[&str] = &[
    "expected f64",
    "expected u",
    "invalid digit",
    "invalid float literal",
    "os error",
    "parsefloat",
    "parseint",
    "some(",
    "err(",
    "panicked",
    "backtrace",
    "too large to fit",
    "cannot parse integer",
    "invalid type:",
    "unit variant",
];

/// One line of the cases file.
struct Case<'a> {
    exit: i32,
    setup: Vec<&'a str>,
    args: Vec<&'a str>,
    words: Vec<&'a str>,
}

fn cases() -> Vec<Case<'static>> {
    CASES
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
        .map(|l| {
            let f: Vec<&str> = l.split(" | ").map(str::trim).collect();
            assert_eq!(f.len(), 4, "bad case line: {l}");
            Case {
                exit: f[0].parse().expect("exit code"),
                setup: f[1].split_whitespace().filter(|s| *s != "-").collect(),
                args: f[2].split_whitespace().collect(),
                words: f[3].split(" ; ").collect(),
            }
        })
        .collect()
}

/// The fixtures every case finds in its folder.
fn fixtures(dir: &Path) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let copy = |from: &str, to: &str| {
        std::fs::copy(root.join(from), dir.join(to)).unwrap_or_else(|e| panic!("{from}: {e}"));
    };
    copy("scenarios/stokes_single.toml", "s.toml");
    copy("tests/data/lab/utf8/soil_b3.csv", "r.csv");
    copy("data/valentik_whitmore_1965_spheres.csv", "sp.csv");
    copy("data/valentik_whitmore_1965_suspensions.csv", "fl.csv");
    std::fs::write(
        dir.join("m.csv"),
        "file,column,row,value,sigma\nsummary.csv,v_simulated_m_s,0,0.005,1e-4\n",
    )
    .unwrap();
    std::fs::write(dir.join("f"), "a file\n").unwrap();
    std::fs::create_dir(dir.join("d")).unwrap();
    std::fs::write(dir.join("d/x.txt"), "x").unwrap();
}

/// What a case's SETUP token puts in `dir`.
fn setup(dir: &Path, token: &str) {
    let (kind, rest) = token.split_once(':').expect("KIND:ARGS");
    match kind {
        "user" => {
            std::fs::create_dir_all(dir.join(rest)).unwrap();
            std::fs::write(dir.join(rest).join("notes.txt"), "mine").unwrap();
        }
        "userfile" => {
            let p = dir.join(rest);
            std::fs::create_dir_all(p.parent().unwrap()).unwrap();
            std::fs::write(p, "mine").unwrap();
        }
        "owned" => {
            let mut f = rest.splitn(3, ':');
            let (folder, command, input) =
                (f.next().unwrap(), f.next().unwrap(), f.next().unwrap());
            let p = dir.join(folder);
            std::fs::create_dir_all(&p).unwrap();
            std::fs::write(
                p.join(".settle-run"),
                format!(
                    "# written by settle\n# command = {command}\n# input = {}\nresult.csv\n",
                    input.replace('+', " ")
                ),
            )
            .unwrap();
            std::fs::write(p.join("result.csv"), "a\n1\n").unwrap();
        }
        _ => panic!("unknown setup `{token}`"),
    }
}

/// Every file (with its bytes) and folder under `dir`.
fn snapshot(dir: &Path) -> BTreeMap<String, Option<Vec<u8>>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            let rel = p.strip_prefix(dir).unwrap().display().to_string();
            if p.is_dir() {
                out.insert(rel, None);
                stack.push(p);
            } else {
                out.insert(rel, Some(std::fs::read(&p).unwrap()));
            }
        }
    }
    out
}

/// Whether `text` holds a number printed with float noise (`0.004300000000000004`).
fn float_noise(text: &str) -> bool {
    let b = text.as_bytes();
    (0..b.len()).any(|i| {
        b[i] == b'.'
            && i > 0
            && b[i - 1].is_ascii_digit()
            && b[i + 1..].iter().take_while(|c| c.is_ascii_digit()).count() >= 12
    })
}

/// Runs one case; its class and, unless clear, why.
fn classify(case: &Case) -> (&'static str, String) {
    let dir = tmp();
    fixtures(dir.path());
    for s in &case.setup {
        setup(dir.path(), s);
    }
    let before = snapshot(dir.path());
    let args: Vec<&str> = case
        .args
        .iter()
        .map(|a| if *a == "RO" { READ_ONLY } else { a })
        .collect();
    let mut child = settle()
        .args(&args)
        .current_dir(dir.path())
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn settle");
    let start = Instant::now();
    while child.try_wait().expect("wait").is_none() {
        if start.elapsed() > HANG {
            let _ = child.kill();
            let _ = child.wait();
            return ("hang", String::new());
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let o = child.wait_with_output().expect("output");
    let after = snapshot(dir.path());
    let lost: Vec<&String> = before
        .iter()
        .filter(|(k, v)| after.get(*k) != Some(v))
        .map(|(k, _)| k)
        .collect();
    if !lost.is_empty() {
        return ("data loss", format!("{lost:?}"));
    }
    let code = o.status.code().unwrap_or(-1);
    if code == 0 {
        return ("silent", String::new());
    }
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stderr),
        String::from_utf8_lossy(&o.stdout)
    );
    let lower = text.to_lowercase();
    let mut why = Vec::new();
    if code != case.exit {
        why.push(format!("exit {code}, not {}", case.exit));
    }
    let missing: Vec<&&str> = case
        .words
        .iter()
        .filter(|w| !lower.contains(&w.to_lowercase()))
        .collect();
    if !missing.is_empty() {
        why.push(format!("missing {missing:?}"));
    }
    let jargon: Vec<&&str> = JARGON.iter().filter(|j| lower.contains(*j)).collect();
    if !jargon.is_empty() {
        why.push(format!("jargon {jargon:?}"));
    }
    if lower.contains("unexpected argument '-") && lower.contains(" -") {
        let negative = args.iter().any(|a| {
            a.starts_with('-') && a[1..].starts_with(|c: char| c.is_ascii_digit() || c == 'i')
        });
        if negative {
            why.push("a negative number read as an option".into());
        }
    }
    if float_noise(&text) {
        why.push("float noise".into());
    }
    let written: Vec<&String> = after.keys().filter(|k| !before.contains_key(*k)).collect();
    if !written.is_empty() {
        why.push(format!("wrote {written:?}"));
    }
    if why.is_empty() {
        ("clear", String::new())
    } else {
        ("unclear", format!("{}: {}", why.join("; "), text.trim()))
    }
}

/// At least 150 command-line and output-folder cases over every command, all clear.
#[test]
fn every_bad_command_line_is_refused_clearly_and_nothing_is_lost() {
    let cases = cases();
    assert!(cases.len() >= 150, "{} cases", cases.len());
    for command in ["run", "sweep", "fit", "reduce", "invert", "laws", "bench"] {
        assert!(
            cases.iter().filter(|c| c.args[0] == command).count() >= 5,
            "too few cases of {command}"
        );
    }
    let mut counts: BTreeMap<&str, usize> = BTreeMap::new();
    let mut report = Vec::new();
    for c in &cases {
        let (class, why) = classify(c);
        *counts.entry(class).or_default() += 1;
        if class != "clear" {
            report.push(format!("[{class}] settle {}\n    {why}", c.args.join(" ")));
        }
    }
    println!("{}", report.join("\n"));
    println!("bad-input suite: {} cases: {counts:?}", cases.len());
    assert_eq!(
        counts.get("clear"),
        Some(&cases.len()),
        "{counts:?}\n{}",
        report.join("\n")
    );
}

/// The suite's own judge: float noise is caught, a rounded number is not.
#[test]
fn float_noise_is_told_from_rounded_numbers() {
    assert!(float_noise("allowed ≥ 0.004300000000000004 m"));
    assert!(!float_noise("allowed ≥ 0.0043 m, 1e-3 s, 12345678901234"));
}
