//! Outputs: a staging folder renamed into place only when a run succeeds (never a half-written
//! result), CSV tables, `run.toml`, metrics and charts.

pub mod chart;
pub mod drop;
pub mod free_settling;
pub mod funnel;
pub use crate::scenes::sedimentation::output::granulometry;
pub mod metrics;

use std::fs;
use std::io;
use std::path::{Path, PathBuf};

/// A results folder written under a temporary name and renamed to its final name by
/// [`StagedDir::commit`]. Dropped without commit, it removes itself.
pub struct StagedDir {
    tmp: PathBuf,
    dest: PathBuf,
    committed: bool,
}

impl StagedDir {
    /// Stages `out_dir/name` as `out_dir/.name.partial-<pid>`. Staging folders of the same
    /// name left by processes that no longer run (killed with SIGKILL, or the machine stopped)
    /// are removed (Linux: a process runs if `/proc/<pid>` exists).
    pub fn new(out_dir: &Path, name: &str) -> io::Result<Self> {
        fs::create_dir_all(out_dir)?;
        let prefix = format!(".{name}.partial-");
        if Path::new("/proc/self").exists() {
            for entry in fs::read_dir(out_dir)?.flatten() {
                let file = entry.file_name();
                let Some(pid) = file.to_str().and_then(|f| f.strip_prefix(&prefix)) else {
                    continue;
                };
                if pid.parse::<u32>().is_ok() && !Path::new("/proc").join(pid).exists() {
                    let _ = fs::remove_dir_all(entry.path());
                }
            }
        }
        let tmp = out_dir.join(format!("{prefix}{}", std::process::id()));
        if tmp.exists() {
            fs::remove_dir_all(&tmp)?;
        }
        fs::create_dir_all(&tmp)?;
        Ok(Self {
            tmp,
            dest: out_dir.join(name),
            committed: false,
        })
    }

    /// Path of a file inside the staging folder.
    pub fn path(&self, file: &str) -> PathBuf {
        self.tmp.join(file)
    }

    /// Final location of the folder.
    pub fn dest(&self) -> &Path {
        &self.dest
    }

    /// Replaces any previous result folder by the staged one.
    pub fn commit(mut self) -> io::Result<PathBuf> {
        if self.dest.exists() {
            fs::remove_dir_all(&self.dest)?;
        }
        fs::rename(&self.tmp, &self.dest)?;
        self.committed = true;
        Ok(self.dest.clone())
    }
}

impl Drop for StagedDir {
    fn drop(&mut self) {
        if !self.committed {
            let _ = fs::remove_dir_all(&self.tmp);
        }
    }
}

/// Writes a file atomically: to `path.tmp`, then renamed.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let tmp = path.with_extension(format!(
        "{}.tmp",
        path.extension().and_then(|e| e.to_str()).unwrap_or("")
    ));
    fs::write(&tmp, bytes)?;
    fs::rename(&tmp, path)
}

/// Formats a number for CSV: shortest round-trip form, in exponent notation when very small or
/// very large.
pub fn num(x: f64) -> String {
    let a = x.abs();
    if a != 0.0 && a.is_finite() && !(1e-4..1e7).contains(&a) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// Formats an optional number for CSV (empty when absent).
pub fn opt(x: Option<f64>) -> String {
    x.map(num).unwrap_or_default()
}
