//! The shape of the crate: the import layers of `src/lib.rs`, file and function lengths.

use std::path::{Path, PathBuf};

mod cycles;
mod formatters;
mod layers;
mod shape;
mod typed_scenario;

/// Every `.rs` file under `src/`, relative to it, with its text, sorted by path.
fn sources() -> Vec<(PathBuf, String)> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut out = Vec::new();
    let mut stack = vec![src.clone()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).expect("read src") {
            let p = e.expect("entry").path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "rs") {
                let text = std::fs::read_to_string(&p).expect("read source");
                out.push((p.strip_prefix(&src).expect("prefix").to_path_buf(), text));
            }
        }
    }
    out.sort();
    out
}
