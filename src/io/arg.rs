//! The numbers of the command line, read as a lab engineer writes them, and the checks every
//! command makes of its files before any work ([`preflight`]).
//!
//! Each parser is a clap `value_parser` (clap prints its message after the option's name, exit
//! 2): a text that is not a number says so, a number beyond the range of a real number
//! (`1e400`) is out of range, a number followed by a unit (`1ms`, `300mm`) is told to drop the
//! unit the option's name already carries, and a count must be a whole number. The range of
//! each option (a step > 0, a slump below the height) is the command's own check, reached
//! also by a negative number after a space (the options take `allow_negative_numbers`).

use crate::error::Error;
use std::path::{Path, PathBuf};

/// What is wrong with `text` as a real number whose unit is `unit` (`seconds`, `millimetres`),
/// or None when it is a finite number.
pub fn number_problem(text: &str, unit: &str) -> Option<String> {
    let t = text.trim();
    match t.parse::<f64>() {
        Ok(x) if x.is_finite() => None,
        Ok(x) if x.is_nan() => Some(format!("`{t}` is not a number: give a finite number")),
        Ok(_) if looks_numeric(t) => Some(format!(
            "{t} is out of range: a number must lie within ±1.8e308 (check the exponent)"
        )),
        Ok(_) => Some(format!("`{t}` is not a finite number: give a number")),
        Err(_) => Some(match leading_number(t) {
            Some(n) if !unit.is_empty() => format!(
                "`{t}` is not a number: give the number alone, in {unit} (e.g. {n}), without a \
                 unit"
            ),
            _ if t.is_empty() => "an empty value is not a number: give a number".to_string(),
            _ => format!("`{t}` is not a number"),
        }),
    }
}

/// Whether `t` is written as digits (not `inf`): `1e400` overflows, `inf` is a word.
fn looks_numeric(t: &str) -> bool {
    t.trim_start_matches(['+', '-'])
        .chars()
        .next()
        .is_some_and(|c| c.is_ascii_digit() || c == '.')
}

/// The number a text such as `300mm` or `1e-3s` starts with, if any.
fn leading_number(t: &str) -> Option<String> {
    (1..t.len())
        .rev()
        .filter(|&i| t.is_char_boundary(i))
        .map(|i| &t[..i])
        .find(|p| p.parse::<f64>().is_ok_and(f64::is_finite) && looks_numeric(p))
        .map(str::to_string)
}

/// A real number in `unit`, for clap: see [`number_problem`]; the range is checked later.
pub fn real(text: &str, unit: &str) -> Result<f64, String> {
    match number_problem(text, unit) {
        Some(p) => Err(p),
        None => Ok(text.trim().parse::<f64>().unwrap_or_default()),
    }
}

/// A time in seconds (`--dt`, `--checkpoint-every`).
pub fn seconds(text: &str) -> Result<f64, String> {
    real(text, "seconds")
}

/// A length in millimetres (`--height-mm`, `--slump-mm`).
pub fn millimetres(text: &str) -> Result<f64, String> {
    real(text, "millimetres")
}

/// A density in kg/m³ (`--density`).
pub fn kg_per_m3(text: &str) -> Result<f64, String> {
    real(text, "kg/m³")
}

/// An acceleration in m/s² (`--g`).
pub fn m_per_s2(text: &str) -> Result<f64, String> {
    real(text, "m/s²")
}

/// A number in the unit of the readings (`--resolution`).
pub fn reading_unit(text: &str) -> Result<f64, String> {
    real(text, "the readings' unit")
}

/// A probability, e.g. a confidence (`--bounds=P`); the range is checked later.
pub fn probability(text: &str) -> Result<f64, String> {
    real(text, "")
}

/// A count: a whole number ≥ `min`.
pub fn whole(text: &str, min: u64) -> Result<u64, String> {
    let t = text.trim();
    match t.parse::<u64>() {
        Ok(n) if n >= min => Ok(n),
        Ok(n) => Err(format!(
            "{n} is out of range: allowed a whole number ≥ {min}"
        )),
        Err(_) => Err(match t.parse::<f64>() {
            Ok(x) if x.is_finite() && x < min as f64 => {
                format!("{t} is out of range: allowed a whole number ≥ {min}")
            }
            Ok(x) if x.is_finite() && x.fract() != 0.0 => {
                format!("{t} is not a whole number: allowed a whole number ≥ {min}")
            }
            Ok(_) if looks_numeric(t) => format!(
                "{t} is out of range: allowed a whole number ≥ {min}, at most {}",
                u64::MAX
            ),
            _ => format!("`{t}` is not a whole number: allowed a whole number ≥ {min}"),
        }),
    }
}

/// A count ≥ 0 (`--repeats`, `--seed`).
pub fn count(text: &str) -> Result<u64, String> {
    whole(text, 0)
}

/// A count ≥ 1 (`--bins`, `--grains`, `--per-decade`).
pub fn count1(text: &str) -> Result<u64, String> {
    whole(text, 1)
}

/// Same as [`count`], as a `usize`.
pub fn count_usize(text: &str) -> Result<usize, String> {
    count(text).and_then(to_usize(text))
}

/// Same as [`count1`], as a `usize`.
pub fn count1_usize(text: &str) -> Result<usize, String> {
    count1(text).and_then(to_usize(text))
}

fn to_usize(text: &str) -> impl Fn(u64) -> Result<usize, String> + '_ {
    move |n| usize::try_from(n).map_err(|_| format!("{} is out of range", text.trim()))
}

/// Why an input file (`what`: "scenario", "readings", …) could not be read, in the words of
/// every command and of the library alike: a missing file, a folder, or the system's reason.
pub fn unreadable(what: &str, e: &std::io::Error) -> String {
    match e.kind() {
        std::io::ErrorKind::NotFound => format!("no such {what} file: check the path"),
        std::io::ErrorKind::IsADirectory => format!("is a folder: give the {what} file itself"),
        _ => format!("cannot read the file: {e}"),
    }
}

/// The checks of a command's files before any work: every input exists and is a file (else
/// bad input, exit 2), no file is given twice (exit 2), `--out` is not a file nor under one
/// (exit 2), and something can be written there (else I/O, exit 4).
pub fn preflight(inputs: &[(&str, &Path)], out: Option<&Path>) -> Result<(), Error> {
    let mut seen: Vec<(PathBuf, &Path)> = Vec::new();
    for (what, path) in inputs {
        match std::fs::metadata(path) {
            Err(e) => return Err(Error::bad_input(path, None, unreadable(what, &e))),
            Ok(m) if m.is_dir() => {
                return Err(Error::bad_input(
                    path,
                    None,
                    format!("is a folder: give the {what} file itself"),
                ))
            }
            Ok(_) => {}
        }
        let abs = super::owner::absolute(path);
        if let Some((_, first)) = seen.iter().find(|(a, _)| *a == abs) {
            return Err(Error::bad_input(
                path,
                None,
                format!(
                    "given twice (also as {}): give each file once",
                    first.display()
                ),
            ));
        }
        seen.push((abs, path));
    }
    if let Some(out) = out {
        super::owner::check_out_dir(out)?;
        super::owner::check_writable(out)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_as_given_or_refused_in_plain_words() {
        assert_eq!(seconds("1e-3"), Ok(1e-3));
        assert_eq!(seconds(" -5 "), Ok(-5.0));
        assert!(seconds("1e400").unwrap_err().contains("out of range"));
        assert!(seconds("abc").unwrap_err().contains("not a number"));
        assert!(seconds("1ms").unwrap_err().contains("e.g. 1"));
        assert!(seconds("nan").unwrap_err().contains("not a number"));
        assert!(seconds("inf").unwrap_err().contains("not a finite number"));
        assert_eq!(count1("3"), Ok(3));
        assert!(count1("0").unwrap_err().contains("≥ 1"));
        assert!(count1("-1").unwrap_err().contains("≥ 1"));
        assert!(count1("2.5").unwrap_err().contains("not a whole number"));
        assert!(count1("1e400").unwrap_err().contains("out of range"));
        assert!(count("abc").unwrap_err().contains("not a whole number"));
    }
}
