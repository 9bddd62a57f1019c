//! Checkpoints of long runs: the whole state of a scene (our state, the Rapier world when there
//! is one, the outputs recorded so far) written atomically so that `settle run --resume DIR`
//! continues the run and produces the same outputs, bit for bit, as an uninterrupted one.
//!
//! # Layout
//!
//! A run with `--checkpoint-every SECONDS` (or one stopped by Ctrl-C/SIGTERM) keeps its
//! checkpoints in `OUT/checkpoint/`:
//! - `request.toml`: the request (scenario files, overrides, `--dt`, the checkpoint period), so
//!   that `--resume OUT` needs nothing else;
//! - `<scenario name>.<part>.bin`: the state of one part of a scene (`state` for the
//!   sedimentation cylinder, `repeat<i>` for each repeat of a funnel pour), in bincode, behind a
//!   [`Header`] that names the format version, the settle version and the scenario, so that a
//!   checkpoint of another scenario or version is refused with a clear message.
//!
//! Every file is written to a temporary name and renamed, so a kill at any moment (even during
//! a write) leaves the previous checkpoint intact. Scenes without a checkpointed state (free
//! settling, drops, calibrations: seconds of work) run again from their start on resume; the
//! outputs are the same because every run is deterministic (seeded RNG, fixed summation order).
//! The folder is removed once the whole request has completed.
//!
//! Format: bincode 1 (compact and exact for f64, as Rapier's own testbed snapshots use it).

use crate::error::Error;
use serde::{de::DeserializeOwned, Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Version of the checkpoint format; bumped whenever a checkpointed state changes layout.
/// 4: the sedimentation state holds the grains' heights (and horizontal positions once a
/// contact moved one), their kinds and initial positions being the setup's.
pub const FORMAT_VERSION: u32 = 4;

/// Name of the checkpoint folder inside the output folder.
pub const DIR_NAME: &str = "checkpoint";

/// What every checkpoint file starts with.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Header {
    /// [`FORMAT_VERSION`] of the writer.
    pub format_version: u32,
    /// settle version of the writer.
    pub settle_version: String,
    /// Scenario name.
    pub scenario: String,
    /// Part of the scene (e.g. `state`, `repeat3`).
    pub part: String,
}

/// The request of a checkpointed run (`OUT/checkpoint/request.toml`).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SavedRequest {
    /// Scenario files, as absolute paths (so that `--resume` works from any directory).
    pub files: Vec<PathBuf>,
    /// `--set` overrides.
    pub overrides: Vec<String>,
    /// `--dt`, s.
    pub dt_s: Option<f64>,
    /// `--checkpoint-every`, s of wall time (None: checkpoints only on interruption).
    pub checkpoint_every_s: Option<f64>,
    /// `--force`.
    #[serde(default)]
    pub force: bool,
    /// The effective scenarios (TOML) at the start, one per file: a resume refuses scenario
    /// files changed since.
    #[serde(default)]
    pub scenarios: Vec<String>,
}

/// Where and how often a run writes checkpoints.
#[derive(Clone, Debug)]
pub struct Checkpoints {
    dir: PathBuf,
    every: Option<Duration>,
    /// Written to `request.toml` beside the first state saved (so that a run that never saves
    /// writes nothing).
    request: Option<SavedRequest>,
}

impl Checkpoints {
    /// Checkpoints in `out_dir/checkpoint/`, every `every_s` seconds of wall time (None: only
    /// when interrupted).
    pub fn new(out_dir: &Path, every_s: Option<f64>) -> Self {
        Self {
            dir: out_dir.join(DIR_NAME),
            every: every_s.map(Duration::from_secs_f64),
            request: None,
        }
    }

    /// The same, writing `request` to `request.toml` with the first state saved.
    pub fn with_request(mut self, request: SavedRequest) -> Self {
        self.request = Some(request);
        self
    }

    /// The checkpoint folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// A timer for one part of a scene, started now.
    pub fn timer(&self) -> Timer {
        Timer {
            every: self.every,
            last: Instant::now(),
        }
    }

    fn file(&self, scenario: &str, part: &str) -> PathBuf {
        self.dir.join(format!("{scenario}.{part}.bin"))
    }

    /// Writes the state of part `part` of scenario `scenario`, atomically.
    pub fn save<T: Serialize>(&self, scenario: &str, part: &str, state: &T) -> std::io::Result<()> {
        std::fs::create_dir_all(&self.dir)?;
        if let Some(req) = &self.request {
            if !self.dir.join("request.toml").exists() {
                self.save_request(req)?;
            }
        }
        let header = Header {
            format_version: FORMAT_VERSION,
            settle_version: env!("CARGO_PKG_VERSION").to_string(),
            scenario: scenario.to_string(),
            part: part.to_string(),
        };
        let mut bytes = bincode::serialize(&header).map_err(std::io::Error::other)?;
        bincode::serialize_into(&mut bytes, state).map_err(std::io::Error::other)?;
        crate::io::write_atomic(&self.file(scenario, part), &bytes)
    }

    /// Reads the state of part `part` of scenario `scenario`: `Ok(None)` if there is none; an
    /// I/O error if it is unreadable; bad input naming the file if it was written by another
    /// format, settle version or scenario.
    pub fn load<T: DeserializeOwned>(
        &self,
        scenario: &str,
        part: &str,
    ) -> Result<Option<T>, Error> {
        let path = self.file(scenario, part);
        let bytes = match std::fs::read(&path) {
            Ok(b) => b,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
            Err(e) => return Err(Error::Io(path, e)),
        };
        let mut reader = bytes.as_slice();
        let bad = |what: String| {
            Error::bad_input(&path, None, format!("{what}; delete it to start afresh"))
        };
        let header: Header = bincode::deserialize_from(&mut reader)
            .map_err(|e| bad(format!("not a settle checkpoint ({e})")))?;
        if header.format_version != FORMAT_VERSION
            || header.settle_version != env!("CARGO_PKG_VERSION")
        {
            return Err(bad(format!(
                "written by settle {} (checkpoint format {}), this is settle {} (format {})",
                header.settle_version,
                header.format_version,
                env!("CARGO_PKG_VERSION"),
                FORMAT_VERSION
            )));
        }
        if header.scenario != scenario || header.part != part {
            return Err(bad(format!(
                "holds `{}` part `{}`, expected `{scenario}` part `{part}`",
                header.scenario, header.part
            )));
        }
        bincode::deserialize_from(&mut reader)
            .map(Some)
            .map_err(|e| bad(format!("corrupt checkpoint ({e})")))
    }

    /// Writes the request beside the checkpoints.
    pub fn save_request(&self, req: &SavedRequest) -> std::io::Result<()> {
        std::fs::create_dir_all(&self.dir)?;
        let text = toml::to_string(req).map_err(std::io::Error::other)?;
        crate::io::write_atomic(&self.dir.join("request.toml"), text.as_bytes())
    }

    /// Reads the request saved in `out_dir/checkpoint/request.toml`; a folder without one is a
    /// bad `--resume` argument.
    pub fn load_request(out_dir: &Path) -> Result<SavedRequest, Error> {
        let path = out_dir.join(DIR_NAME).join("request.toml");
        let text = std::fs::read_to_string(&path).map_err(|e| {
            Error::bad_argument(
                "--resume",
                out_dir,
                format!(
                    "cannot resume: no checkpointed run here ({}: {e})",
                    path.display()
                ),
            )
        })?;
        toml::from_str(&text).map_err(|e| Error::bad_input(&path, None, e.message().to_string()))
    }

    /// Removes what settle wrote in the checkpoint folder (`request.toml`, `*.bin` and their
    /// temporary files), then the folder if that leaves it empty: files a user put there stay.
    pub fn clear(&self) -> std::io::Result<()> {
        let entries = match std::fs::read_dir(&self.dir) {
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
            r => r?,
        };
        for entry in entries.flatten() {
            let name = entry.file_name();
            let name = name.to_string_lossy();
            let ours = name == "request.toml"
                || name.ends_with(".bin")
                || crate::io::is_tmp_of(&name, "request.toml")
                || name
                    .rsplit_once(".bin.")
                    .is_some_and(|(stem, _)| crate::io::is_tmp_of(&name, &format!("{stem}.bin")));
            if ours && entry.file_type().is_ok_and(|t| t.is_file()) {
                std::fs::remove_file(entry.path())?;
            }
        }
        match std::fs::remove_dir(&self.dir) {
            // Not empty: a user's file is in it; keep it.
            Err(e) if e.kind() == std::io::ErrorKind::DirectoryNotEmpty => Ok(()),
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(e),
            _ => Ok(()),
        }
    }
}

/// Wall-clock timer of one part: [`Timer::due`] is true once per period.
#[derive(Clone, Debug)]
pub struct Timer {
    every: Option<Duration>,
    last: Instant,
}

impl Timer {
    /// True if a period has passed since the last time it returned true (or since the start);
    /// never true without a period.
    pub fn due(&mut self) -> bool {
        match self.every {
            Some(p) if self.last.elapsed() >= p => {
                self.last = Instant::now();
                true
            }
            _ => false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_is_exact_and_checks_the_header() {
        let dir = tempfile::tempdir().unwrap();
        let c = Checkpoints::new(dir.path(), None);
        let state = (vec![0.1f64, 1.0 / 3.0, f64::MIN_POSITIVE, -0.0], 42u64);
        c.save("sample", "state", &state).unwrap();
        let back: (Vec<f64>, u64) = c.load("sample", "state").unwrap().unwrap();
        assert_eq!(
            back.0.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
            state.0.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
        );
        assert_eq!(back.1, 42);
        assert!(c
            .load::<(Vec<f64>, u64)>("sample", "other")
            .unwrap()
            .is_none());
        // A file renamed to another scenario is refused, naming the file.
        std::fs::copy(
            dir.path().join("checkpoint/sample.state.bin"),
            dir.path().join("checkpoint/other.state.bin"),
        )
        .unwrap();
        let err = c
            .load::<(Vec<f64>, u64)>("other", "state")
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("other.state.bin") && err.contains("expected `other`"),
            "{err}"
        );
        // Garbage is refused, not a panic.
        std::fs::write(dir.path().join("checkpoint/bad.state.bin"), b"\x01\x02").unwrap();
        let err = c
            .load::<(Vec<f64>, u64)>("bad", "state")
            .unwrap_err()
            .to_string();
        assert!(err.contains("not a settle checkpoint"), "{err}");
        c.clear().unwrap();
        assert!(!dir.path().join("checkpoint").exists());
    }

    /// A checkpoint of an older format (3: the sedimentation state held whole grains) is
    /// refused with a message naming both formats and the way out, not read as garbage.
    #[test]
    fn older_format_is_refused_clearly() {
        let dir = tempfile::tempdir().unwrap();
        let c = Checkpoints::new(dir.path(), None);
        let header = Header {
            format_version: 3,
            settle_version: env!("CARGO_PKG_VERSION").to_string(),
            scenario: "sample".into(),
            part: "state".into(),
        };
        let mut bytes = bincode::serialize(&header).unwrap();
        bincode::serialize_into(&mut bytes, &(vec![0.5f64; 3], 7u64)).unwrap();
        std::fs::create_dir_all(dir.path().join("checkpoint")).unwrap();
        std::fs::write(dir.path().join("checkpoint/sample.state.bin"), bytes).unwrap();
        let err = c
            .load::<(Vec<f64>, u64)>("sample", "state")
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("sample.state.bin")
                && err.contains("checkpoint format 3")
                && err.contains(&format!("(format {FORMAT_VERSION})"))
                && err.contains("delete it to start afresh"),
            "{err}"
        );
    }

    #[test]
    fn timer_without_period_is_never_due() {
        let c = Checkpoints::new(Path::new("/nonexistent"), None);
        let mut t = c.timer();
        assert!(!t.due());
        let c = Checkpoints::new(Path::new("/nonexistent"), Some(0.0));
        let mut t = c.timer();
        assert!(t.due());
    }
}
