//! Infrastructure for outputs (no domain types): a staging folder renamed into place only when
//! a run succeeds (never a half-written result), that replaces only what settle wrote before;
//! atomic writes; number formatting for CSV; charts; error statistics.
//!
//! # Ownership of output folders
//!
//! settle marks each folder it creates (`OUT/NAME/`) with a file [`MARKER`] that lists the
//! entries settle wrote there, one name a line. A later run into the same folder removes only
//! those entries and keeps anything the user added (notes, plots). A folder without the marker
//! was not made by settle (or by a settle before the marker existed) and is never deleted or
//! replaced: [`check_destination_for`] refuses it before anything runs, unless it is empty. The
//! marker also names the command and input that wrote the folder ([`owner`]): a folder of
//! another command or input is never replaced either.

pub mod arg;
mod atomic;
pub mod chart;
pub mod fmt;
pub mod lab_file;
pub mod metrics;
pub mod outputs;
pub mod owner;
pub mod report;
pub mod table;
pub mod xlsx;

pub use atomic::{is_tmp_of, write_atomic, MARKER, TMP_SUFFIX};
pub use outputs::Outputs;
pub use owner::{check_destination_for, Owner};
pub use table::{Cells, Column, Table};

use std::fs;
use std::io;
use std::path::{Path, PathBuf};

/// The entries listed in the marker of `dir` (empty if there is none).
pub fn owned_entries(dir: &Path) -> Vec<String> {
    fs::read_to_string(dir.join(MARKER))
        .map(|t| {
            t.lines()
                .filter(|l| !l.is_empty() && !l.starts_with('#'))
                .filter(|l| !l.contains('/') && *l != ".." && *l != ".")
                .map(str::to_string)
                .collect()
        })
        .unwrap_or_default()
}

/// Removes the staging folders (`.NAME.partial-PID`) of processes that no longer run, whatever
/// their name (Linux: a process runs if `/proc/<pid>` exists; elsewhere nothing is removed).
pub fn clean_stale_staging(out_dir: &Path) {
    if !Path::new("/proc/self").exists() {
        return;
    }
    let Ok(entries) = fs::read_dir(out_dir) else {
        return;
    };
    for entry in entries.flatten() {
        let file = entry.file_name();
        let Some(pid) = file
            .to_str()
            .filter(|f| f.starts_with('.'))
            .and_then(|f| f.rsplit_once(".partial-"))
            .map(|(_, pid)| pid)
        else {
            continue;
        };
        let Ok(pid) = pid.parse::<u32>() else {
            continue;
        };
        if pid != std::process::id() && !Path::new("/proc").join(pid.to_string()).exists() {
            let _ = fs::remove_dir_all(entry.path());
        }
    }
}

/// A results folder written under a temporary name and moved to its final name by
/// [`StagedDir::commit`]. Dropped without commit, it removes itself.
pub struct StagedDir {
    tmp: PathBuf,
    dest: PathBuf,
    owner: Option<Owner>,
    committed: bool,
}

impl StagedDir {
    /// Stages `out_dir/name` as `out_dir/.name.partial-<pid>`, after removing the staging folders
    /// of dead processes ([`clean_stale_staging`]).
    pub fn new(out_dir: &Path, name: &str) -> io::Result<Self> {
        fs::create_dir_all(out_dir)?;
        clean_stale_staging(out_dir);
        let tmp = out_dir.join(format!(".{name}.partial-{}", std::process::id()));
        if tmp.exists() {
            fs::remove_dir_all(&tmp)?;
        }
        fs::create_dir_all(&tmp)?;
        Ok(Self {
            tmp,
            dest: out_dir.join(name),
            owner: None,
            committed: false,
        })
    }

    /// The same staging, committed only into a destination absent, empty or already
    /// `owner`'s, and marked as `owner`'s ([`check_destination_for`]).
    pub fn owned_by(mut self, owner: Owner) -> Self {
        self.owner = Some(owner);
        self
    }

    /// Path of a file inside the staging folder.
    pub fn path(&self, file: &str) -> PathBuf {
        self.tmp.join(file)
    }

    /// Final location of the folder.
    pub fn dest(&self) -> &Path {
        &self.dest
    }

    /// Moves the staged entries into place. A destination settle made before loses only the
    /// entries its marker lists; a destination settle did not make is refused (error kind
    /// `AlreadyExists`, nothing touched), as is a user's file in the way of a staged one.
    pub fn commit(mut self) -> io::Result<PathBuf> {
        let mut names: Vec<String> = fs::read_dir(&self.tmp)?
            .flatten()
            .filter_map(|e| e.file_name().to_str().map(str::to_string))
            .filter(|n| n != MARKER)
            .collect();
        names.sort();
        let marker = format!(
            "# written by settle: a rerun replaces the entries listed here and keeps the others\n{}{}\n",
            self.owner.as_ref().map(Owner::marker_lines).unwrap_or_default(),
            names.join("\n")
        );
        write_atomic(&self.tmp.join(MARKER), marker.as_bytes())?;
        match check_destination_for(&self.dest, self.owner.as_ref()) {
            Err(r) => {
                return Err(io::Error::new(
                    io::ErrorKind::AlreadyExists,
                    owner::refusal_text(
                        &self.dest,
                        &r,
                        self.owner.as_ref(),
                        "choose another --out",
                    ),
                ))
            }
            Ok(()) if !self.dest.exists() => fs::rename(&self.tmp, &self.dest)?,
            Ok(()) => self.merge_into_dest(&names)?,
        }
        self.committed = true;
        Ok(self.dest.clone())
    }

    /// Replaces the entries settle wrote in an existing destination by the staged ones.
    fn merge_into_dest(&self, names: &[String]) -> io::Result<()> {
        let old = owned_entries(&self.dest);
        for n in names {
            let target = self.dest.join(n);
            if target.symlink_metadata().is_ok() && !old.contains(n) {
                return Err(io::Error::new(
                    io::ErrorKind::AlreadyExists,
                    format!(
                        "{}: not written by settle, and this run writes a file of that name: \
                         move it away and run again",
                        target.display()
                    ),
                ));
            }
        }
        for n in &old {
            remove_entry(&self.dest.join(n))?;
        }
        for n in names {
            fs::rename(self.tmp.join(n), self.dest.join(n))?;
        }
        fs::rename(self.tmp.join(MARKER), self.dest.join(MARKER))?;
        fs::remove_dir_all(&self.tmp)
    }
}

/// Removes a file or a folder; absent is fine.
fn remove_entry(path: &Path) -> io::Result<()> {
    let r = match path.symlink_metadata() {
        Err(_) => return Ok(()),
        Ok(m) if m.is_dir() => fs::remove_dir_all(path),
        Ok(_) => fs::remove_file(path),
    };
    match r {
        Err(e) if e.kind() != io::ErrorKind::NotFound => Err(e),
        _ => Ok(()),
    }
}

impl Drop for StagedDir {
    fn drop(&mut self) {
        if !self.committed {
            let _ = fs::remove_dir_all(&self.tmp);
        }
    }
}

#[cfg(test)]
mod tests;

// Here, not in outputs.rs: writing a folder needs the staging of this file, and outputs.rs
// stays a leaf (no import loop between the two).
impl Outputs {
    /// Writes the folder `out_dir/name/` as a command does (staged, then moved into place):
    /// refused as bad input on `--out` when that folder is not a folder, is not empty and was
    /// not made by settle (no `.settle-run` marker), or holds the results of another owner
    /// ([`Outputs::owner`]). Returns the folder.
    pub fn write_folder(
        &self,
        out_dir: &Path,
        name: &str,
    ) -> Result<std::path::PathBuf, crate::error::Error> {
        use crate::error::Error;
        let dest = out_dir.join(name);
        owner::check_out_dir(out_dir)?;
        if let Err(r) = check_destination_for(&dest, self.owner()) {
            return Err(Error::bad_argument(
                "--out",
                &dest,
                owner::refusal_text(&dest, &r, self.owner(), "choose another --out"),
            ));
        }
        let ioe = |e: io::Error| Error::Io(dest.clone(), e);
        let mut stage = StagedDir::new(out_dir, name).map_err(ioe)?;
        if let Some(o) = self.owner() {
            stage = stage.owned_by(o.clone());
        }
        self.write_into(&stage.path("")).map_err(ioe)?;
        stage.commit().map_err(ioe)
    }
}
