//! Why a sweep stops. A local type until the crate has one error type (issue 12, item 4): bad
//! input exits 2 before anything is written; output failures exit 1.

use crate::scenario::ScenarioError;
use std::fmt;
use std::path::PathBuf;

/// A sweep that cannot run or whose results cannot be written.
#[derive(Debug)]
pub enum Error {
    /// A scenario file that cannot be loaded, or lacks what a sweep needs (exit 2).
    Scenario(ScenarioError),
    /// A scenario of a kind sweeps do not support (exit 2, nothing written).
    Unsweepable {
        /// The scenario file.
        file: PathBuf,
        /// Its kind, as written in the file.
        kind: String,
    },
    /// A command-line option with a value that cannot be used (exit 2).
    Usage {
        /// The option, e.g. `--merge`.
        option: &'static str,
        /// What is wrong and what is allowed.
        message: String,
    },
    /// A part file of `--merge` that is not a sweep table (exit 2).
    BadPart(PathBuf, csv::Error),
    /// An output that could not be written (exit 1).
    Io(PathBuf, std::io::Error),
}

impl Error {
    /// Process exit code: 2 bad input (nothing written), 1 output failure.
    pub fn exit_code(&self) -> i32 {
        match self {
            Self::Io(..) => 1,
            _ => 2,
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Scenario(e) => write!(f, "{e}"),
            Self::Unsweepable { file, kind } => write!(
                f,
                "{}: a scenario of kind `{kind}` cannot be swept; kinds that can: {}; nothing was written",
                file.display(),
                super::targets::SWEEPABLE_NAMES.join(", ")
            ),
            Self::Usage { option, message } => write!(f, "{option}: {message}"),
            Self::BadPart(p, e) => write!(f, "{}: not a sweep part table: {e}", p.display()),
            Self::Io(p, e) => write!(f, "{}: cannot write outputs: {e}", p.display()),
        }
    }
}

impl std::error::Error for Error {}

impl From<ScenarioError> for Error {
    fn from(e: ScenarioError) -> Self {
        Self::Scenario(e)
    }
}
