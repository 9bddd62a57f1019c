//! The report page of a sweep (`report.html`) as one more file of its [`Outputs`], rendered
//! from the outputs in memory ([`crate::io::report::render_outputs`]): byte for byte the page
//! of the folder the command line writes.

use crate::error::Error;
use crate::io::report::{render_outputs, Page, FILE_NAME};
use crate::io::Outputs;

/// Adds `report.html` (the page titled `title`, [`Page::sweep`]) to `outputs`, rendered from
/// the files already in it.
pub(crate) fn add_report(outputs: &mut Outputs, title: &str) -> Result<(), Error> {
    let html = render_outputs(outputs, &Page::sweep(title));
    outputs.file(FILE_NAME, html);
    Ok(())
}
