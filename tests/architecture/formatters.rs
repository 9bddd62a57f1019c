//! One number formatter (issue 24, item 4): every rule that turns an `f64` into text lives in
//! `src/io/fmt.rs`. A function named like one of its functions (`sig`, `sig_trim`, `clean`,
//! `num`, …) that takes a number (`f64` in its signature line) defined anywhere else in `src/`
//! is a second formatter and fails this test; a method (taking `self`) or a function of text
//! (`scenario::check::short`, the last segment of a key) is something else and is allowed.

use super::sources;
use std::path::Path;

/// The file that holds every number format.
const FORMATTERS: &str = "io/fmt.rs";

/// Names that must be defined in [`FORMATTERS`] (so that this test never passes vacuously).
const REQUIRED: [&str; 7] = [
    "sig",
    "sig_trim",
    "clean",
    "num",
    "sig_plain",
    "sig_shortest",
    "g",
];

/// The names of the free functions of a number (not methods: no `self` parameter; `f64` in
/// the line that names them) that `text` defines, with their 1-based lines.
fn free_functions(text: &str) -> Vec<(String, usize)> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let code = line.split("//").next().unwrap_or("");
        let Some(at) = code.find("fn ") else {
            continue;
        };
        // `fn` as a word: at the start of the line's code, or after `pub `, `pub(crate) `, …
        if at > 0 && !code[..at].ends_with(' ') {
            continue;
        }
        let rest = &code[at + 3..];
        let name: String = rest
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        if name.is_empty() {
            continue;
        }
        let params = rest[name.len()..].trim_start();
        let params = params.trim_start_matches(|c| c != '(');
        let first = params.trim_start_matches('(').trim_start();
        let method = first.starts_with("self")
            || first.starts_with("&self")
            || first.starts_with("&mut self");
        if !method && code.contains("f64") {
            out.push((name, i + 1));
        }
    }
    out
}

/// `file:line fn name` of every function in `files` (other than [`FORMATTERS`]) named like one
/// of `names`.
fn second_formatters(files: &[(std::path::PathBuf, String)], names: &[String]) -> Vec<String> {
    let mut found = Vec::new();
    for (path, text) in files {
        if path == Path::new(FORMATTERS) {
            continue;
        }
        for (name, line) in free_functions(text) {
            if names.contains(&name) {
                found.push(format!("src/{}:{line} fn {name}", path.display()));
            }
        }
    }
    found
}

#[test]
fn every_number_format_is_defined_in_io_fmt_only() {
    let files = sources();
    assert!(files.len() > 100, "only {} source files found", files.len());
    let fmt = &files
        .iter()
        .find(|(p, _)| p == Path::new(FORMATTERS))
        .expect("src/io/fmt.rs")
        .1;
    let names: Vec<String> = free_functions(fmt)
        .into_iter()
        .map(|(n, _)| n)
        .filter(|n| !n.starts_with("test") && n != "tests")
        .collect();
    for r in REQUIRED {
        assert!(
            names.iter().any(|n| n == r),
            "io/fmt.rs lost `fn {r}`: {names:?}"
        );
    }
    let found = second_formatters(&files, &names);
    assert!(
        found.is_empty(),
        "number formats defined outside src/io/fmt.rs (move them there, under a name that \
         says their rule):\n{}",
        found.join("\n")
    );
}

/// The check finds a formatter defined elsewhere, also nested or private, and not a method.
#[test]
fn a_second_formatter_is_found() {
    let names: Vec<String> = ["sig", "clean", "num"].map(String::from).to_vec();
    let fixture = "pub fn sig(x: f64, n: usize) -> String {}\n\
                   fn helper() {\n    fn clean(x: f64) -> String { num(x) }\n}\n\
                   impl Level {\n    pub fn num(&self) -> Option<f64> {}\n}\n\
                   pub(crate) fn sig_else(x: f64) {}\n// fn num(x: f64)\n\
                   fn num(key: &str) -> &str {}\n";
    let files = vec![
        ("a/b.rs".into(), fixture.to_string()),
        (FORMATTERS.into(), "pub fn sig(x: f64) {}".to_string()),
    ];
    assert_eq!(
        second_formatters(&files, &names),
        ["src/a/b.rs:1 fn sig", "src/a/b.rs:3 fn clean"]
    );
}
