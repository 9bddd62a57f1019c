//! The outputs of a run or a command, in memory: its tables ([`Table`]) and its other files
//! (charts, pages, pictures) as bytes. A scene or a command fills an [`Outputs`]; the command
//! line writes it into a staging folder ([`Outputs::write_into`], then
//! [`super::StagedDir::commit`]), and the library API hands it to the caller as it is.

use super::chart::data::Figure;
use super::chart::Chart;
use super::table::Table;
use rayon::prelude::*;
use std::io;
use std::path::Path;
use std::sync::Arc;

/// Tables and files of one run, in the order they were made. Names are relative to the run's
/// folder (`summary.csv`, `charts/velocity.svg`); a later entry of the same name replaces an
/// earlier one.
#[derive(Clone, Debug, Default)]
pub struct Outputs {
    tables: Vec<Table>,
    files: Vec<(String, FileBody)>,
    figures: Vec<(String, Figure)>,
    owner: Option<super::owner::Owner>,
}

/// Writes the bytes of a file made when it is written or read ([`Outputs::made_file`]).
pub type MakeFile = dyn Fn(&mut dyn io::Write) -> io::Result<()> + Send + Sync;

/// The bytes of a file of [`Outputs`]: held, or made when the file is written or read.
#[derive(Clone)]
enum FileBody {
    /// The bytes.
    Bytes(Vec<u8>),
    /// What writes them.
    Made(Arc<MakeFile>),
}

impl std::fmt::Debug for FileBody {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FileBody::Bytes(b) => write!(f, "Bytes({} B)", b.len()),
            FileBody::Made(_) => f.write_str("Made"),
        }
    }
}

impl FileBody {
    /// The bytes (made now for a made file).
    fn bytes(&self) -> io::Result<Vec<u8>> {
        match self {
            FileBody::Bytes(b) => Ok(b.clone()),
            FileBody::Made(make) => {
                let mut b = Vec::new();
                make(&mut b)?;
                Ok(b)
            }
        }
    }
}

impl Outputs {
    /// No outputs yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Records the command and input these outputs are the results of: their folder is marked
    /// as theirs, and never replaces the folder of another owner ([`super::owner`]).
    pub fn set_owner(&mut self, owner: super::owner::Owner) {
        self.owner = Some(owner);
    }

    /// The command and input these outputs are the results of, if recorded.
    pub fn owner(&self) -> Option<&super::owner::Owner> {
        self.owner.as_ref()
    }

    /// Adds a table (replacing one of the same name).
    pub fn table(&mut self, t: Table) {
        self.tables.retain(|x| x.name() != t.name());
        self.tables.push(t);
    }

    /// Adds a file that is not a table (replacing one of the same name).
    pub fn file(&mut self, name: impl Into<String>, bytes: impl Into<Vec<u8>>) {
        self.put_file(name.into(), FileBody::Bytes(bytes.into()));
    }

    /// Adds a file that is not a table, whose bytes `make` writes when the file is written or
    /// read (replacing one of the same name): for a file as large as its data (a snapshot's
    /// VTK points), which is then never held whole in memory.
    pub fn made_file(&mut self, name: impl Into<String>, make: Arc<MakeFile>) {
        self.put_file(name.into(), FileBody::Made(make));
    }

    fn put_file(&mut self, name: String, body: FileBody) {
        self.files.retain(|(n, _)| *n != name);
        self.files.push((name, body));
    }

    /// Adds the chart `c` as the SVG file `name`.
    pub fn chart(&mut self, name: impl Into<String>, c: &Chart) -> io::Result<()> {
        let name = name.into();
        let svg = c.svg_string()?;
        self.figure(name.clone(), Figure::single(c));
        self.file(name, svg);
        Ok(())
    }

    /// Adds `charts` as panels of the one SVG file `name` (small multiples under `title`,
    /// `columns` per row).
    pub fn grid_chart(
        &mut self,
        name: impl Into<String>,
        title: &str,
        charts: &[Chart],
        columns: usize,
    ) -> io::Result<()> {
        let name = name.into();
        let svg = super::chart::grid_svg_string(title, charts, columns)?;
        self.figure(name.clone(), Figure::grid(title, charts, columns));
        self.file(name, svg);
        Ok(())
    }

    /// Records the data of a chart file `name` drawn otherwise than by [`Outputs::chart`] (a
    /// scene's own plotters drawing), so that callers can draw it too.
    pub fn add_figure(&mut self, name: impl Into<String>, f: Figure) {
        self.figure(name.into(), f);
    }

    /// Records the data of the chart file `name` (replacing one of the same name).
    fn figure(&mut self, name: String, f: Figure) {
        self.figures.retain(|(n, _)| *n != name);
        self.figures.push((name, f));
    }

    /// The data of every chart made with [`Outputs::chart`] or [`Outputs::grid_chart`], by file
    /// name (`charts/velocity.svg`), in the order they were made: what the SVG file draws, for
    /// a caller that draws it itself. (Charts drawn otherwise, e.g. pictures of the cylinder,
    /// are files only.)
    pub fn figures(&self) -> &[(String, Figure)] {
        &self.figures
    }

    /// Moves every table and file of `other` in (replacing those of the same names).
    pub fn extend(&mut self, other: Outputs) {
        for t in other.tables {
            self.table(t);
        }
        for (n, b) in other.files {
            self.put_file(n, b);
        }
        for (n, f) in other.figures {
            self.figure(n, f);
        }
        if self.owner.is_none() {
            self.owner = other.owner;
        }
    }

    /// The tables, in the order they were made.
    pub fn tables(&self) -> &[Table] {
        &self.tables
    }

    /// The table whose file is `name` (`summary.csv`) or whose stem is `name` (`summary`).
    pub fn get(&self, name: &str) -> Option<&Table> {
        self.tables
            .iter()
            .find(|t| t.name() == name || t.stem() == name)
    }

    /// The names of the files that are not tables, in the order they were made.
    pub fn file_names(&self) -> impl Iterator<Item = &str> {
        self.files.iter().map(|(n, _)| n.as_str())
    }

    /// The bytes of the file `name` (a table's CSV bytes when `name` is a table's file name;
    /// a made file's made now), or None when there is no such file or it could not be made.
    pub fn bytes(&self, name: &str) -> Option<Vec<u8>> {
        if let Some(t) = self.tables.iter().find(|t| t.name() == name) {
            return t.to_csv().ok();
        }
        self.files
            .iter()
            .find(|(n, _)| n == name)
            .and_then(|(_, b)| b.bytes().ok())
    }

    /// True when nothing was made.
    pub fn is_empty(&self) -> bool {
        self.tables.is_empty() && self.files.is_empty()
    }

    /// Writes every table (as CSV) and file into the folder `dir` (a staging folder), creating
    /// sub-folders as needed; each file atomically (written beside, then renamed). The files
    /// are written in parallel (a large run's snapshots are formatted as they are written);
    /// the error returned is that of the first file that failed, in the order they were made.
    pub fn write_into(&self, dir: &Path) -> io::Result<()> {
        let tables = self
            .tables
            .par_iter()
            .map(|t| write_file(dir, t.name(), &|w| t.write_csv(w)));
        let files = self.files.par_iter().map(|(n, b)| match b {
            FileBody::Bytes(b) => write_file(dir, n, &|w| w.write_all(b)),
            FileBody::Made(make) => write_file(dir, n, &**make),
        });
        let done: Vec<io::Result<()>> = tables.chain(files).collect();
        done.into_iter().collect()
    }

    /// Reads the files of a folder (recursively): `.csv` files as tables, the others as bytes.
    /// Names are relative to `dir` with `/` between folders; settle's marker is skipped.
    pub fn read_dir(dir: &Path) -> io::Result<Self> {
        let mut out = Outputs::new();
        read_into(dir, "", &mut out)?;
        Ok(out)
    }
}

fn write_file(
    dir: &Path,
    name: &str,
    write: &dyn Fn(&mut dyn io::Write) -> io::Result<()>,
) -> io::Result<()> {
    let path = dir.join(name);
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent)?;
    }
    super::atomic::write_atomic_with(&path, write)
}

fn read_into(dir: &Path, prefix: &str, out: &mut Outputs) -> io::Result<()> {
    let mut entries: Vec<_> = std::fs::read_dir(dir)?.collect::<Result<_, _>>()?;
    entries.sort_by_key(|e| e.file_name());
    for e in entries {
        let Some(n) = e.file_name().to_str().map(str::to_string) else {
            continue;
        };
        if n == super::atomic::MARKER {
            continue;
        }
        let name = format!("{prefix}{n}");
        if e.file_type()?.is_dir() {
            read_into(&e.path(), &format!("{name}/"), out)?;
        } else {
            let bytes = std::fs::read(e.path())?;
            if name.ends_with(".csv") {
                out.table(Table::from_csv(name, &bytes)?);
            } else {
                out.file(name, bytes);
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outputs_written_read_back_equal() {
        let dir = std::env::temp_dir().join(format!("settle-outputs-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let mut o = Outputs::new();
        let mut t = Table::new("summary.csv", ["a_m"]);
        t.push(vec!["1".into()]);
        o.table(t.clone());
        o.file("sub/x.txt", "hello");
        o.made_file(
            "sub/made.txt",
            Arc::new(|w: &mut dyn io::Write| w.write_all(b"made on demand")),
        );
        assert_eq!(o.bytes("sub/made.txt").unwrap(), b"made on demand");
        o.write_into(&dir).unwrap();
        let back = Outputs::read_dir(&dir).unwrap();
        assert_eq!(back.get("summary"), Some(&t));
        assert_eq!(back.bytes("sub/x.txt").unwrap(), b"hello");
        assert_eq!(back.bytes("sub/made.txt").unwrap(), b"made on demand");
        assert_eq!(
            back.file_names().collect::<Vec<_>>(),
            ["sub/made.txt", "sub/x.txt"]
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
