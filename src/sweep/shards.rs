//! The shards of a split sweep (`--shard I/N`, `--merge DIR`): the part files a folder holds, by
//! index; which indices are missing or unreadable; and the exact command that reruns them, which
//! every shard records beside its part file (`shards.toml`: the working folder and the
//! arguments of the command, the `--shard` option left out).

use crate::error::Error;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Name prefix of the part files of a sharded dt sweep.
pub const PART_PREFIX: &str = "sweep_part_";

/// The record of a split sweep's command, beside its part files.
pub const COMMAND_FILE: &str = "shards.toml";

/// The job array script `settle sweep --slurm N` writes into the sweep's folder (see
/// `crate::slurm`); named here so that the merge can point at it.
pub const ARRAY_SCRIPT: &str = "slurm_array.sh";

/// How the shards of a sweep were started: rerun shard `I` with `cd CWD && ARGS --shard I/N`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ShardCommand {
    /// Working folder of the command.
    pub cwd: PathBuf,
    /// The program (this binary's path) and its arguments, without `--shard I/N`.
    pub args: Vec<String>,
    /// How many shards.
    pub count: usize,
}

impl ShardCommand {
    /// The command of this process (its arguments without `--shard`), for `count` shards.
    pub fn of_this_process(count: usize) -> Self {
        Self {
            cwd: std::env::current_dir().unwrap_or_default(),
            args: this_command(&["--shard"], &[]),
            count,
        }
    }

    /// The shell command that runs shard `index` (a number, or a shell word such as `$i`).
    pub fn line(&self, index: &str) -> String {
        let args: Vec<String> = self.args.iter().map(|a| quote(a)).collect();
        format!(
            "cd {} && {} --shard {index}/{}",
            quote(&self.cwd.display().to_string()),
            args.join(" "),
            self.count
        )
    }

    /// Writes `dir/shards.toml` (atomically; every shard writes the same text).
    pub fn record(&self, dir: &Path) -> Result<(), Error> {
        let path = dir.join(COMMAND_FILE);
        let text =
            toml::to_string(self).map_err(|e| Error::Io(path.clone(), std::io::Error::other(e)))?;
        let text = format!(
            "# The command of each shard of this sweep: `cd CWD && ARGS --shard I/COUNT`\n{text}"
        );
        crate::io::write_atomic(&path, text.as_bytes()).map_err(|e| Error::Io(path, e))
    }

    /// Reads `dir/shards.toml` (None if absent or unreadable).
    pub fn read(dir: &Path) -> Option<Self> {
        toml::from_str(&std::fs::read_to_string(dir.join(COMMAND_FILE)).ok()?).ok()
    }
}

/// This process's command line (the program as the path of this binary), without the options
/// `with_value` (each with its value, as `--opt V` or `--opt=V`) and the flags `flags`.
pub fn this_command(with_value: &[&str], flags: &[&str]) -> Vec<String> {
    let mut args: Vec<String> = std::env::args_os()
        .map(|a| a.to_string_lossy().into_owned())
        .collect();
    if let Ok(exe) = std::env::current_exe() {
        if let Some(a) = args.first_mut() {
            *a = exe.display().to_string();
        }
    }
    without(args, with_value, flags)
}

/// `args` without the options `with_value` (and their values) and the flags `flags`.
pub fn without(args: Vec<String>, with_value: &[&str], flags: &[&str]) -> Vec<String> {
    let mut kept = Vec::new();
    let mut it = args.into_iter();
    while let Some(a) = it.next() {
        if with_value.contains(&a.as_str()) {
            it.next();
        } else if !(flags.contains(&a.as_str())
            || with_value.iter().any(|o| a.starts_with(&format!("{o}="))))
        {
            kept.push(a);
        }
    }
    kept
}

/// `s` quoted for a POSIX shell (unchanged when it needs no quotes).
pub fn quote(s: &str) -> String {
    let plain = !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || "-_./=:,+@%".contains(c));
    if plain {
        s.to_string()
    } else {
        format!("'{}'", s.replace('\'', r"'\''"))
    }
}

/// The index and count of a part file `PREFIX<I>_of_<N>.csv`.
pub fn parse_name(name: &str, prefix: &str) -> Option<(usize, usize)> {
    let rest = name.strip_prefix(prefix)?.strip_suffix(".csv")?;
    let (i, n) = rest.split_once("_of_")?;
    Some((i.parse().ok()?, n.parse().ok()?))
}

/// The part files of one folder, by index.
#[derive(Clone, Debug, Default)]
pub struct Parts {
    /// The part files, sorted by index.
    pub files: Vec<(usize, PathBuf)>,
    /// How many shards the parts say there are (the largest N of their names).
    pub count: usize,
}

impl Parts {
    /// The part files `PREFIX<I>_of_<N>.csv` of `dir`, sorted by index (none: empty).
    pub fn of(dir: &Path, prefix: &str) -> Self {
        let mut files = Vec::new();
        let mut count = 0;
        for e in std::fs::read_dir(dir).into_iter().flatten().flatten() {
            let name = e.file_name();
            if let Some((i, n)) = name.to_str().and_then(|n| parse_name(n, prefix)) {
                count = count.max(n);
                files.push((i, e.path()));
            }
        }
        files.sort();
        Self { files, count }
    }

    /// The counts N of the part names when they are not all the same, listed (`4, 16`).
    pub fn mixed_counts(&self) -> Option<String> {
        let counts: std::collections::BTreeSet<usize> = self
            .files
            .iter()
            .filter_map(|(_, f)| {
                let name = f.file_name()?.to_str()?;
                let rest = name.strip_suffix(".csv")?;
                rest.rsplit_once("_of_")?.1.parse().ok()
            })
            .collect();
        let list: Vec<String> = counts.iter().map(|n| n.to_string()).collect();
        (counts.len() > 1).then(|| list.join(", "))
    }

    /// The shard indices 1..=count without a part file.
    pub fn missing(&self) -> Vec<usize> {
        let mut have = vec![false; self.count + 1];
        for (i, _) in &self.files {
            if *i <= self.count {
                have[*i] = true;
            }
        }
        (1..=self.count).filter(|i| !have[*i]).collect()
    }
}

/// Indices as `3,7,12-15` (Slurm's `--array` syntax).
pub fn ranges(indices: &[usize]) -> String {
    let mut out: Vec<String> = Vec::new();
    let mut k = 0;
    while k < indices.len() {
        let start = indices[k];
        let mut end = start;
        while k + 1 < indices.len() && indices[k + 1] == end + 1 {
            k += 1;
            end = indices[k];
        }
        out.push(if end > start {
            format!("{start}-{end}")
        } else {
            start.to_string()
        });
        k += 1;
    }
    out.join(",")
}

/// The error of a merge whose folder `dir` lacks shards `missing` or holds unreadable parts
/// `failed` (file and why). Prints on stderr the shards by index, each unreadable part with
/// why, and the exact commands that rerun them (from `shards.toml`; the `sbatch --array` line
/// when settle wrote a job array there); returns the one-line error.
pub fn incomplete(
    dir: &Path,
    count: usize,
    missing: &[usize],
    failed: &[(usize, PathBuf, String)],
) -> Error {
    let mut redo: Vec<usize> = missing.to_vec();
    redo.extend(failed.iter().map(|(i, _, _)| *i));
    redo.sort();
    redo.dedup();
    let mut lines = Vec::new();
    if !missing.is_empty() {
        lines.push(format!(
            "missing shards (no part file: never run, still running, or failed): {}",
            ranges(missing)
        ));
    }
    for (i, f, why) in failed {
        lines.push(format!("failed shard {i}: {} ({why})", f.display()));
    }
    match ShardCommand::read(dir) {
        Some(c) => {
            lines.push("rerun them with:".into());
            if redo.len() == 1 {
                lines.push(format!("  {}", c.line(&redo[0].to_string())));
            } else {
                let list: Vec<String> = redo.iter().map(|i| i.to_string()).collect();
                lines.push(format!(
                    "  for i in {}; do ({}); done",
                    list.join(" "),
                    c.line("$i")
                ));
            }
            let script = dir.join(ARRAY_SCRIPT);
            if script.exists() {
                lines.push(format!(
                    "or on Slurm: sbatch --array={} {}",
                    ranges(&redo),
                    quote(&script.display().to_string())
                ));
            }
        }
        None => lines.push(format!(
            "rerun shards {} (--shard I/{count}) with the sweep's command",
            ranges(&redo)
        )),
    }
    lines.push(format!(
        "then: settle sweep --merge {}",
        quote(&dir.display().to_string())
    ));
    eprintln!("{}", lines.join("\n"));
    Error::bad_argument(
        "--merge",
        dir,
        format!(
            "{} of {count} shards missing or failed ({}): nothing merged; rerun them as printed \
             above",
            redo.len(),
            ranges(&redo)
        ),
    )
}

/// The part files `PREFIX*.csv` of the `--merge` folders, each folder's by index; a folder whose
/// shards are not all there is an error listing the missing indices and the command that reruns
/// them ([`shards::incomplete`]). `read` reads one part (an unreadable one is a failed shard).
pub fn read_parts<T>(
    dirs: &[PathBuf],
    prefix: &str,
    read: impl Fn(&Path) -> Result<T, String>,
) -> Result<Vec<(PathBuf, T)>, Error> {
    let mut all = Vec::new();
    for dir in dirs {
        if let Err(e) = std::fs::read_dir(dir) {
            return Err(Error::bad_argument(
                "--merge",
                dir,
                format!("cannot read the folder: {e}"),
            ));
        }
        let parts = Parts::of(dir, prefix);
        if let Some(n) = parts.mixed_counts() {
            return Err(Error::bad_argument(
                "--merge",
                dir,
                format!(
                    "holds the parts of several splits ({n}): keep one split's \
                     {prefix}I_of_N.csv files in the folder"
                ),
            ));
        }
        let mut failed = Vec::new();
        for (i, f) in &parts.files {
            match read(f) {
                Ok(t) => all.push((f.clone(), t)),
                Err(e) => failed.push((*i, f.clone(), e)),
            }
        }
        let missing = parts.missing();
        if !missing.is_empty() || !failed.is_empty() {
            return Err(incomplete(dir, parts.count, &missing, &failed));
        }
    }
    Ok(all)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_ranges_and_quotes() {
        assert_eq!(
            parse_name("sweep_part_3_of_16.csv", "sweep_part_"),
            Some((3, 16))
        );
        assert_eq!(
            parse_name("sweep_part_3_of_16.csv.tmp", "sweep_part_"),
            None
        );
        assert_eq!(parse_name("vary_part_1_of_2.csv", "sweep_part_"), None);
        assert_eq!(ranges(&[1, 2, 3, 5, 7, 8]), "1-3,5,7-8");
        assert_eq!(ranges(&[]), "");
        assert_eq!(quote("a/b.toml"), "a/b.toml");
        let argv = |s: &str| s.split(' ').map(String::from).collect::<Vec<_>>();
        assert_eq!(
            without(
                argv("settle sweep a.toml --slurm 4 --wait --sbatch-arg=-p --shard=1/2 --dt 1"),
                &["--slurm", "--sbatch-arg", "--shard"],
                &["--wait"]
            ),
            argv("settle sweep a.toml --dt 1")
        );
        assert_eq!(quote("it's here"), r"'it'\''s here'");
        let p = Parts {
            files: vec![(1, "a".into()), (4, "b".into())],
            count: 5,
        };
        assert_eq!(p.missing(), vec![2, 3, 5]);
    }
}
