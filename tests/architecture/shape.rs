//! The shape of the code a newcomer reads: no file in `src/` longer than 700 lines and no
//! function longer than 120 (issue 12: 150; issue 24: 120), counted from the line of `fn` to its closing brace.
//! A function that is clearer whole goes into [`ALLOWED`] with the reason.

use super::sources;
use std::path::Path;

/// Longest file, lines.
const MAX_FILE_LINES: usize = 700;
/// Longest function, lines.
const MAX_FN_LINES: usize = 120;
/// `(file relative to src/, function)` pairs allowed beyond [`MAX_FN_LINES`], each with its reason.
const ALLOWED: &[(&str, &str, &str)] = &[];

/// Length in lines of every function in `text`, as `(name, first line (1-based), lines)`.
fn functions(text: &str) -> Vec<(String, usize, usize)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let Some(name) = fn_name(line) else {
            continue;
        };
        let mut depth = 0i64;
        let mut started = false;
        let mut end = i;
        for (j, l) in lines.iter().enumerate().skip(i) {
            let code = strip(l);
            for c in code.chars() {
                match c {
                    '{' => {
                        depth += 1;
                        started = true;
                    }
                    '}' => depth -= 1,
                    _ => {}
                }
            }
            end = j;
            if (started && depth <= 0) || (!started && code.trim_end().ends_with(';')) {
                break;
            }
        }
        out.push((name, i + 1, end - i + 1));
    }
    out
}

/// The name of the function a line declares, if it does.
fn fn_name(line: &str) -> Option<String> {
    let code = strip(line);
    let words: Vec<&str> = code.split_whitespace().collect();
    let k = words.iter().position(|w| *w == "fn")?;
    let before_ok = words[..k].iter().all(|w| {
        w.starts_with("pub") || matches!(*w, "const" | "async" | "unsafe" | "extern" | "\"C\"")
    });
    if !before_ok {
        return None;
    }
    let name: String = words
        .get(k + 1)?
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect();
    (!name.is_empty()).then_some(name)
}

/// A line without its string literals and `//` comment.
pub(super) fn strip(line: &str) -> String {
    let mut out = String::new();
    let mut in_str = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        if in_str {
            match c {
                '\\' => {
                    chars.next();
                }
                '"' => in_str = false,
                _ => {}
            }
        } else if c == '"' {
            in_str = true;
        } else if c == '\'' {
            // A char literal such as '{' or '\'' (not a lifetime): skip it whole.
            let rest: String = chars.clone().take(3).collect();
            if rest.starts_with('\\') {
                let skip = rest.find('\'').map(|k| k + 1).unwrap_or(0);
                for _ in 0..skip.max(1) {
                    chars.next();
                }
                // Escapes like '\'' close after the escaped char.
                if rest.starts_with("\\'") {
                    chars.next();
                }
            } else if rest.chars().nth(1) == Some('\'') {
                chars.next();
                chars.next();
            } else {
                out.push(c);
            }
        } else if c == '/' && chars.peek() == Some(&'/') {
            break;
        } else {
            out.push(c);
        }
    }
    out
}

#[test]
fn files_and_functions_stay_short() {
    let mut bad = Vec::new();
    for (rel, text) in sources() {
        let n = text.lines().count();
        if n > MAX_FILE_LINES {
            bad.push(format!(
                "{}: {n} lines (at most {MAX_FILE_LINES})",
                rel.display()
            ));
        }
        for (name, line, len) in functions(&text) {
            let allowed = ALLOWED
                .iter()
                .any(|(f, g, _)| Path::new(f) == rel && *g == name);
            if len > MAX_FN_LINES && !allowed {
                bad.push(format!(
                    "{}:{line}: fn {name} has {len} lines (at most {MAX_FN_LINES})",
                    rel.display()
                ));
            }
        }
    }
    assert!(bad.is_empty(), "too long:\n{}", bad.join("\n"));
}

#[test]
fn the_counter_measures_functions() {
    let text = "pub fn a() {\n    let s = \"}}}\"; // }\n    if x { y(); }\n}\nfn b(x: char) -> bool { x == '{' }\n";
    let f = functions(text);
    assert_eq!(f, vec![("a".into(), 1, 4), ("b".into(), 5, 1)]);
    let long = format!("fn c() {{\n{}}}\n", "    x();\n".repeat(200));
    assert_eq!(functions(&long)[0].2, 202);
}
