//! The one error type of settle and its exit codes (infrastructure layer: no domain types).
//!
//! Every failure falls into one class, and each class has one process exit code:
//!
//! | class | exit | what |
//! |---|---|---|
//! | success | 0 | |
//! | bad input | 2 | a scenario file, an input file (missing, a folder, given twice) or a command-line argument is wrong, or the output folder may not be written (`--out` a file, a non-empty folder settle did not create, another command's or input's results): the message names the file (or argument), the key or row, and what is allowed; found before any work, nothing was run or written |
//! | unstable run | 3 | the simulation went numerically unstable: the message names the body, the time and a step that would hold; nothing was written |
//! | I/O or environment | 4 | the machine refused: a file could not be read or written (disk, permissions, a read-only `--out`, `/proc`) |
//! | interrupted | 130 | Ctrl-C or SIGTERM: a sedimentation or funnel-pour run keeps what it simulated in its output folder, marked `interrupted` ([`Error::Interrupted`]); the other kinds, and files not yet started, write nothing ([`Error::InterruptedUnwritten`]); files that finished before stay |

use std::fmt;
use std::path::{Path, PathBuf};

/// Exit code of a bad input (scenario, input file or command line).
pub const EXIT_BAD_INPUT: i32 = 2;
/// Exit code of an unstable run.
pub const EXIT_UNSTABLE: i32 = 3;
/// Exit code of an I/O or environment failure.
pub const EXIT_IO: i32 = 4;
/// Exit code of an interrupted run (128 + SIGINT).
pub const EXIT_INTERRUPTED: i32 = 130;

/// Bad input: one line naming the file (or the value of a command-line argument), the key or row/column,
/// and what is wrong and what is allowed.
#[derive(Clone, Debug, PartialEq)]
pub struct BadInput {
    /// The file at fault (a scenario, an input CSV, an output folder given on the command line).
    pub file: PathBuf,
    /// The offending key (`spheres[0].diameter_m`, `name`), row/column or option (`--out`).
    pub key: Option<String>,
    /// What is wrong and what is allowed.
    pub message: String,
}

impl BadInput {
    /// A bad input naming `file` and, if known, `key`.
    pub fn new(file: &Path, key: Option<&str>, message: impl Into<String>) -> Self {
        Self {
            file: file.to_path_buf(),
            key: key.map(|k| k.replace('\n', " ")),
            message: plain(&message.into().replace('\n', " ")),
        }
    }
}

impl fmt::Display for BadInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.key {
            Some(k) => write!(f, "{}: key `{}`: {}", self.file.display(), k, self.message),
            None => write!(f, "{}: {}", self.file.display(), self.message),
        }
    }
}

impl std::error::Error for BadInput {}

/// Why a command failed; [`Error::exit_code`] maps it to the process exit code (see the module
/// doc for the classes).
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Bad input (exit 2).
    #[error("{0}")]
    BadInput(BadInput),
    /// The run of the scenario file went unstable (exit 3).
    #[error("{path}: {report}; nothing was written", path = .0.display(), report = .1)]
    Unstable(PathBuf, Unstable),
    /// A file or folder could not be read or written (exit 4).
    #[error("{path}: {cause}", path = .0.display(), cause = plain_io(.1))]
    Io(PathBuf, std::io::Error),
    /// Stopped by Ctrl-C/SIGTERM; what was simulated so far is in the output folder, marked
    /// `interrupted` in its `run.toml` (exit 130).
    #[error(
        "interrupted: what was simulated so far is in {path} (run.toml status = \"interrupted\")",
        path = .0.display()
    )]
    Interrupted(PathBuf),
    /// Stopped by Ctrl-C/SIGTERM before the run of the scenario file wrote anything: nothing of
    /// it was kept (kinds that keep no partial result, or a file not yet started; exit 130).
    #[error(
        "interrupted: {path} was stopped before its end and nothing of it was written",
        path = .0.display()
    )]
    InterruptedUnwritten(PathBuf),
}

impl Error {
    /// Bad input naming `file`, `key` and the message.
    pub fn bad_input(file: &Path, key: Option<&str>, message: impl Into<String>) -> Self {
        Self::BadInput(BadInput::new(file, key, message))
    }

    /// A bad command-line argument `option` (e.g. `--out`) whose value is `value`.
    pub fn bad_argument(option: &str, value: &Path, message: impl Into<String>) -> Self {
        Self::BadInput(BadInput::new(value, Some(option), message))
    }

    /// Whether the run was stopped by Ctrl-C/SIGTERM (either interrupted variant).
    pub fn is_interrupted(&self) -> bool {
        matches!(self, Self::Interrupted(_) | Self::InterruptedUnwritten(_))
    }

    /// Process exit code of this error's class.
    pub fn exit_code(&self) -> i32 {
        match self {
            Self::BadInput(_) => EXIT_BAD_INPUT,
            Self::Unstable(..) => EXIT_UNSTABLE,
            Self::Io(..) => EXIT_IO,
            Self::Interrupted(_) | Self::InterruptedUnwritten(_) => EXIT_INTERRUPTED,
        }
    }
}

impl From<BadInput> for Error {
    fn from(e: BadInput) -> Self {
        Self::BadInput(e)
    }
}

/// The operating system's words for `e`, without Rust's `(os error N)`.
pub fn plain_io(e: &std::io::Error) -> String {
    strip_os_error(&e.to_string())
}

/// `text` without the ` (os error N)` Rust appends to the system's words.
fn strip_os_error(text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(i) = rest.find(" (os error ") {
        out.push_str(&rest[..i]);
        let tail = &rest[i..];
        rest = tail.find(')').map_or("", |j| &tail[j + 1..]);
    }
    out.push_str(rest);
    out
}

/// A message in a lab engineer's words: the `(os error N)` of the system's messages dropped,
/// and the type names of the TOML reader (`invalid type: string "abc", expected f64`) said as
/// what was given and what is needed (`"abc" is not a number`).
pub fn plain(message: &str) -> String {
    let message = strip_os_error(message);
    let Some(i) = message.find("invalid type: ") else {
        return message;
    };
    let rest = &message[i + "invalid type: ".len()..];
    let Some(j) = rest.find(", expected ") else {
        return message;
    };
    let given = &rest[..j];
    let tail = &rest[j + ", expected ".len()..];
    let end = tail.find([';', '\n']).unwrap_or(tail.len());
    let (wanted, after) = (&tail[..end], &tail[end..]);
    let needed = if ["f64", "f32", "float"].iter().any(|w| wanted.contains(w)) {
        "a number"
    } else if ["u64", "u32", "usize", "i64", "i32", "integer"]
        .iter()
        .any(|w| wanted.contains(w))
    {
        "a whole number"
    } else if wanted.contains("bool") {
        "true or false"
    } else if wanted.contains("sequence") {
        "a list [ … ]"
    } else if wanted.contains("map") || wanted.contains("struct") {
        "a table"
    } else {
        "a word in quotes"
    };
    let said = match given.strip_prefix("string ") {
        Some(q) => {
            let v = q.trim_matches('"');
            if v.trim().parse::<f64>().is_ok_and(f64::is_infinite)
                && v.trim_start_matches(['+', '-'])
                    .starts_with(|c: char| c.is_ascii_digit())
            {
                format!("{v} is out of range: a number must lie within ±1.8e308")
            } else if needed == "a number" && v.starts_with(|c: char| c.is_ascii_digit()) {
                format!(
                    "\"{v}\" is not a number: give the number alone, without a unit (the key's \
                     name carries it)"
                )
            } else {
                format!("\"{v}\" is not {needed}")
            }
        }
        None => {
            let v = given
                .split_once('`')
                .map_or("this value", |(_, v)| v.trim_end_matches('`'));
            format!("{v} is not {needed}")
        }
    };
    format!("{}{said}{after}", &message[..i])
}

/// A run that went unstable: which body, when, what quantity, and a step that would be stable.
#[derive(Clone, Debug, PartialEq)]
pub struct Unstable {
    /// Identifier of the body.
    pub body: String,
    /// Simulated time at which the instability was detected, s.
    pub time_s: f64,
    /// Step index at detection.
    pub step: u64,
    /// What went wrong (`velocity is NaN`, `velocity oscillates with growing amplitude`, …).
    pub what: String,
    /// The time step in use, s.
    pub dt_s: f64,
    /// Largest time step expected to be stable for this body, s (infinite if unknown; 0 when no
    /// step is stable for the scheme in use, e.g. explicit drag at a yield-stress stop).
    pub stable_dt_s: f64,
    /// How `stable_dt_s` was found, which sets the advice printed.
    pub dt_basis: DtBasis,
}

/// How the suggested step of an [`Unstable`] report was found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum DtBasis {
    /// The explicit drag update's limit 2 m/(dF/dv) (0: no step holds a yield-stress stop).
    #[default]
    ExplicitDrag,
    /// Half the step in use: a fault of the contacts, the speed cap or the domain, which a
    /// body travelling a smaller fraction of its diameter per step avoids.
    Halved,
}

impl fmt::Display for Unstable {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "unstable: body `{}` at t = {:.6e} s (step {}): {} with dt = {:.3e} s",
            self.body, self.time_s, self.step, self.what, self.dt_s
        )?;
        if self.dt_basis == DtBasis::Halved {
            write!(
                f,
                "; try dt ≤ {:.3e} s (half the step: contacts and the speed cap hold when a body \
                 travels a small fraction of its diameter per step), or check the initial \
                 positions and the scene's settings",
                self.stable_dt_s
            )?;
        } else if self.stable_dt_s == 0.0 {
            write!(
                f,
                "; no time step makes the explicit scheme hold a body at rest against a yield stress: use integrator = \"implicit\" or \"exponential\""
            )?;
        } else if self.stable_dt_s.is_finite() {
            write!(
                f,
                "; largest stable dt for this body ≈ {:.3e} s (2m/(dF/dv)): use dt < {:.3e} s or integrator = \"exponential\"",
                self.stable_dt_s, self.stable_dt_s
            )?;
        }
        Ok(())
    }
}

impl std::error::Error for Unstable {}

#[cfg(test)]
mod tests {
    use super::*;

    /// No type names or system codes reach a message.
    #[test]
    fn messages_in_plain_words() {
        assert_eq!(
            plain("invalid type: string \"abc\", expected f64"),
            "\"abc\" is not a number"
        );
        assert!(plain("invalid type: string \"1e400\", expected f64").contains("out of range"));
        assert_eq!(
            plain("x: invalid type: unit variant, expected string only"),
            "x: this value is not a word in quotes"
        );
        assert_eq!(
            plain("a: No such file or directory (os error 2); b"),
            "a: No such file or directory; b"
        );
    }

    /// The interrupted message says whether anything was kept, and both exit 130.
    #[test]
    fn interrupted_messages_say_whether_anything_was_kept() {
        let kept = Error::Interrupted(PathBuf::from("out/sed"));
        let none = Error::InterruptedUnwritten(PathBuf::from("scenarios/stokes_single.toml"));
        assert!(kept
            .to_string()
            .contains("what was simulated so far is in out/sed"));
        let m = none.to_string();
        assert!(m.contains("scenarios/stokes_single.toml"), "{m}");
        assert!(m.contains("nothing of it was written"), "{m}");
        assert!(!m.contains("run.toml"), "{m}");
        for e in [kept, none] {
            assert!(e.is_interrupted());
            assert_eq!(e.exit_code(), EXIT_INTERRUPTED);
        }
    }
}
