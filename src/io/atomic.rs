//! Atomic writes, and the name of the marker file of settle's folders (the two things every
//! writer of `io` needs).

use std::fs;
use std::io;
use std::path::Path;

/// Name of the file that marks a folder as settle's and lists the entries settle wrote in it.
pub const MARKER: &str = ".settle-run";

/// Writes a file atomically: to a temporary `NAME.<pid>-<n>.tmp` beside it, then renamed. The
/// temporary name is unique per call, so two threads writing the same file never rename each
/// other's half-written file (issue 8 regression: two funnel repeats saving their first checkpoint at once
/// both wrote `request.toml.tmp`; the second rename found nothing and the run failed).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> io::Result<()> {
    write_atomic_with(path, &|w: &mut dyn io::Write| w.write_all(bytes))
}

/// [`write_atomic`] of the bytes `write` writes (buffered), for a file too large to hold in
/// memory first: the temporary file is removed when `write` fails.
pub fn write_atomic_with(
    path: &Path,
    write: &dyn Fn(&mut dyn io::Write) -> io::Result<()>,
) -> io::Result<()> {
    static COUNTER: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let n = COUNTER.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let name = path
        .file_name()
        .map(|f| f.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = path.with_file_name(format!("{name}.{}-{n}{TMP_SUFFIX}", std::process::id()));
    let written = fs::File::create(&tmp).and_then(|f| {
        let mut w = io::BufWriter::new(f);
        write(&mut w)?;
        io::Write::flush(&mut w)
    });
    written
        .and_then(|()| fs::rename(&tmp, path))
        .inspect_err(|_| {
            let _ = fs::remove_file(&tmp);
        })
}

/// The suffix of the temporary files [`write_atomic`] writes: `NAME.<pid>-<n>.tmp`.
pub const TMP_SUFFIX: &str = ".tmp";

/// Whether `file_name` is a temporary file [`write_atomic`] made while writing `target`.
pub fn is_tmp_of(file_name: &str, target: &str) -> bool {
    file_name
        .strip_prefix(target)
        .and_then(|rest| rest.strip_prefix('.'))
        .and_then(|rest| rest.strip_suffix(TMP_SUFFIX))
        .is_some_and(|mid| {
            mid.split_once('-').is_some_and(|(a, b)| {
                !a.is_empty()
                    && !b.is_empty()
                    && a.bytes().all(|c| c.is_ascii_digit())
                    && b.bytes().all(|c| c.is_ascii_digit())
            })
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A writer that fails half-way leaves neither the file nor its temporary behind, and an
    /// earlier file of that name as it was.
    #[test]
    fn a_failed_write_leaves_the_old_file_and_no_temporary() {
        let dir = std::env::temp_dir().join(format!("settle-atomic-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        let path = dir.join("a.vtp");
        write_atomic(&path, b"old").unwrap();
        let e = write_atomic_with(&path, &|w| {
            w.write_all(b"half")?;
            Err(io::Error::other("disk full"))
        })
        .unwrap_err();
        assert_eq!(e.to_string(), "disk full");
        assert_eq!(fs::read(&path).unwrap(), b"old");
        let names: Vec<_> = fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, ["a.vtp"]);
        write_atomic_with(&path, &|w| w.write_all(b"new")).unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"new");
        fs::remove_dir_all(&dir).unwrap();
    }
}
