//! Who owns an output folder of settle: the command and the input whose results it holds,
//! recorded in the folder's marker ([`MARKER`]) as `# command = …` and `# input = …` lines
//! (comment lines, so that the list of entries below them reads as before).
//!
//! A command writes only into a folder that is absent, empty, or marked by the same command
//! on the same input ([`check_destination_for`]): a run of a scenario named `X_sweep` never
//! replaces the folder of the sweep of `X`, and the reduction of `b/readings.csv` never
//! replaces that of `a/readings.csv` (both `readings_reduced/`).

use super::atomic::MARKER;
use crate::error::Error;
use std::fs;
use std::path::{Path, PathBuf};

/// The command and input that wrote an output folder.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Owner {
    /// The command (`run`, `sweep`, `sweep --vary`, `fit`, `reduce`, `invert`, `laws`, `bench`).
    pub command: String,
    /// What it ran on: `scenario NAME` for the commands of scenario files (a rerun of the same
    /// scenario name, from any file or its `run.toml`, replaces its results), the input files'
    /// absolute paths (joined by ` + `) for the commands of lab files.
    pub input: String,
}

impl Owner {
    /// The owner `command` of `input`.
    pub fn new(command: &str, input: impl Into<String>) -> Self {
        Self {
            command: command.to_string(),
            input: input.into().replace('\n', " "),
        }
    }

    /// The owner `command` of the scenario named `name`.
    pub fn scenario(command: &str, name: &str) -> Self {
        Self::new(command, format!("scenario {name}"))
    }

    /// The owner `command` of the files `files`: their absolute paths (canonical when they
    /// exist), joined by ` + `.
    pub fn of_files<P: AsRef<Path>>(command: &str, files: &[P]) -> Self {
        let names: Vec<String> = files
            .iter()
            .map(|f| absolute(f.as_ref()).display().to_string())
            .collect();
        Self::new(command, names.join(" + "))
    }

    /// The owner recorded in the marker of `dir` (none: no marker, or a marker of a settle
    /// that did not record owners).
    pub fn read(dir: &Path) -> Option<Self> {
        let text = fs::read_to_string(dir.join(MARKER)).ok()?;
        let field = |key: &str| {
            text.lines().find_map(|l| {
                l.strip_prefix('#')
                    .and_then(|l| l.trim().strip_prefix(key))
                    .and_then(|l| l.trim_start().strip_prefix('='))
                    .map(|v| v.trim().to_string())
            })
        };
        Some(Self {
            command: field("command")?,
            input: field("input")?,
        })
    }

    /// The marker lines recording this owner.
    pub fn marker_lines(&self) -> String {
        format!("# command = {}\n# input = {}\n", self.command, self.input)
    }

    /// `settle COMMAND` of INPUT, for messages.
    pub fn describe(&self) -> String {
        format!("`settle {}` of {}", self.command, self.input)
    }
}

/// `path` made absolute (canonical when it exists).
pub fn absolute(path: &Path) -> PathBuf {
    fs::canonicalize(path)
        .or_else(|_| std::path::absolute(path))
        .unwrap_or_else(|_| path.to_path_buf())
}

/// Why an output destination cannot be used.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Refusal {
    /// The destination exists and is not a folder.
    NotAFolder,
    /// The destination is a folder that settle did not create (no [`MARKER`]) and that is not
    /// empty.
    NotOurs,
    /// The destination holds the results of another command or input.
    OwnedBy(Owner),
}

/// Checks that `dest` may receive the outputs of `owner`: absent, an empty folder, or a folder
/// settle created for the same owner (or for no recorded owner: an older settle, or `owner`
/// none).
pub fn check_destination_for(dest: &Path, owner: Option<&Owner>) -> Result<(), Refusal> {
    match fs::symlink_metadata(dest) {
        Err(_) => Ok(()),
        Ok(m) if !m.is_dir() => Err(Refusal::NotAFolder),
        Ok(_) if dest.join(MARKER).is_file() => match (Owner::read(dest), owner) {
            (Some(had), Some(mine)) if had != *mine => Err(Refusal::OwnedBy(had)),
            _ => Ok(()),
        },
        Ok(_) if is_empty_dir(dest) => Ok(()),
        Ok(_) => Err(Refusal::NotOurs),
    }
}

fn is_empty_dir(dir: &Path) -> bool {
    fs::read_dir(dir).is_ok_and(|mut e| e.next().is_none())
}

/// What is wrong with `dest` (`refusal`) for the outputs of `owner`, and the fix `fix`: one
/// sentence for a message.
pub fn refusal_text(dest: &Path, refusal: &Refusal, owner: Option<&Owner>, fix: &str) -> String {
    let d = dest.display();
    match refusal {
        Refusal::NotAFolder => format!("{d} exists and is not a folder: {fix}"),
        Refusal::NotOurs => format!(
            "{d} exists, was not created by settle (it has no {MARKER} marker) and is not \
             empty, so settle will not write into it: {fix} (or move that folder away)"
        ),
        Refusal::OwnedBy(had) => format!(
            "{d} holds the results of {}; settle will not replace them{}: {fix} (or remove \
             that folder)",
            had.describe(),
            owner
                .map(|o| format!(" with those of {}", o.describe()))
                .unwrap_or_default()
        ),
    }
}

/// Refuses (bad input on `--out`, before any work) an output folder `dest` that may not
/// receive the outputs of `owner` ([`check_destination_for`]).
pub fn check_owned(dest: &Path, owner: &Owner) -> Result<(), Error> {
    check_destination_for(dest, Some(owner)).map_err(|r| {
        Error::bad_argument(
            "--out",
            dest,
            refusal_text(dest, &r, Some(owner), "choose another --out"),
        )
    })
}

/// Refuses (bad input on `--out`, exit 2, before any work) an `--out` that names a file, or
/// lies under one.
pub fn check_out_dir(out_dir: &Path) -> Result<(), Error> {
    for a in out_dir.ancestors().filter(|a| !a.as_os_str().is_empty()) {
        match fs::metadata(a) {
            Ok(m) if m.is_dir() => return Ok(()),
            Ok(_) => {
                return Err(Error::bad_argument(
                    "--out",
                    out_dir,
                    if a == out_dir {
                        "names a file: give a folder (it is created if absent)".to_string()
                    } else {
                        format!(
                            "lies under {}, which is a file: give a folder (it is created if \
                             absent)",
                            a.display()
                        )
                    },
                ))
            }
            Err(_) => continue,
        }
    }
    Ok(())
}

/// Refuses (I/O, exit 4, before any work) an `--out` in which nothing can be written: the
/// folder (or its first existing parent) gets a probe file, removed at once.
pub fn check_writable(out_dir: &Path) -> Result<(), Error> {
    let Some(dir) = out_dir
        .ancestors()
        .map(|a| {
            if a.as_os_str().is_empty() {
                Path::new(".")
            } else {
                a
            }
        })
        .find(|a| a.is_dir())
    else {
        return Ok(());
    };
    let probe = dir.join(format!(".settle-probe-{}", std::process::id()));
    match fs::write(&probe, b"") {
        Ok(()) => {
            let _ = fs::remove_file(&probe);
            Ok(())
        }
        Err(e) => Err(Error::Io(
            out_dir.to_path_buf(),
            std::io::Error::new(
                e.kind(),
                format!(
                    "cannot write in {} ({}): choose an --out you can write to",
                    dir.display(),
                    crate::error::plain_io(&e)
                ),
            ),
        )),
    }
}
