//! The report page of a sweep (`report.html`) as one more file of its [`Outputs`].
//!
//! [`crate::io::report::render`] builds a page from the files of a folder (their list and
//! sizes, the tables, every chart). A sweep's outputs are in memory, so the page is rendered
//! from a private scratch folder holding exactly those files, removed afterwards: the same page,
//! byte for byte, as rendering from the command line's staging folder.

use crate::error::Error;
use crate::io::report::{render, Page, FILE_NAME};
use crate::io::Outputs;
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};

/// Scratch folders made by this process so far (their names must differ across threads).
static SCRATCH: AtomicU64 = AtomicU64::new(0);

/// A scratch folder removed when dropped.
struct Scratch(PathBuf);

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Adds `report.html` (the page titled `title`, [`Page::sweep`]) to `outputs`, rendered from
/// the files already in it.
pub(crate) fn add_report(outputs: &mut Outputs, title: &str) -> Result<(), Error> {
    let n = SCRATCH.fetch_add(1, Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!(".settle-page-{}-{n}", std::process::id()));
    let io = |e: std::io::Error| Error::Io(dir.clone(), e);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).map_err(io)?;
    let scratch = Scratch(dir.clone());
    outputs.write_into(&scratch.0).map_err(io)?;
    let html = render(&scratch.0, &Page::sweep(title)).map_err(io)?;
    drop(scratch);
    outputs.file(FILE_NAME, html);
    Ok(())
}
