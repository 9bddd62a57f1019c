//! A page a person reads: `report.html` in a results folder, built only from the files the run
//! wrote there (no domain types): the scenario's name, kind and description and the run's record
//! from `run.toml`, its validity warnings, the key result tables, every chart (`*.svg` inlined,
//! `*.png` as a base64 `data:` URI), the list of output files and the effective scenario.
//!
//! The page is self-contained: one HTML file with its style sheet inlined, no script, no font or
//! image fetched from anywhere; its only links are relative, to the folder's own files and (on
//! the combined page) to the runs' pages `../NAME/report.html`.

mod html;
mod record;
mod table;

use crate::io::fmt::sig_trim;
pub use html::{base64, esc};

use crate::io::Outputs;
use html::{href, inline_svg, scope_ids, svg_title};
use record::{
    class_name, record_section, scenario_section, scenario_table, string_list, value_text,
    warnings_section,
};
use std::fmt::Write as _;
use std::fs;
use std::io;
use std::path::{Path, PathBuf};
use table::csv_table;

/// The page's file name in a results folder.
pub const FILE_NAME: &str = "report.html";

/// The result tables a run's page shows, in this order, when the run wrote them.
pub const RUN_TABLES: &[&str] = &["summary.csv", "metrics.csv", "instrument_errors.csv"];

/// The result tables the combined page shows, in this order, when present: the error statistics
/// and the instruments' errors before the long per-sphere table.
pub const COMBINED_TABLES: &[&str] = &["metrics.csv", "instrument_errors.csv", "summary.csv"];

/// The result tables a sweep's page shows, in this order, when the sweep wrote them.
pub const SWEEP_TABLES: &[&str] = &["recommended_dt.csv", "sweep.csv", "vary.csv"];

/// Rows of a table the page shows; the rest is counted and linked.
pub const MAX_ROWS: usize = 30;

/// Entries of one folder the file list names; the rest is counted.
const MAX_FILES_PER_FOLDER: usize = 25;

/// What a page shows beyond what the folder itself holds.
#[derive(Clone, Copy, Debug)]
pub struct Page<'a> {
    /// Heading when the folder has no `run.toml` (a run's page takes the scenario's name).
    pub title: &'a str,
    /// CSV files shown as tables, in this order, when present.
    pub tables: &'a [&'a str],
    /// Run folders beside this one (`../NAME/`), linked with their status and warnings: the
    /// combined page of a several-file run. Empty for a run's own page.
    pub runs: &'a [String],
}

impl<'a> Page<'a> {
    /// The page of one run (`OUT/NAME/`).
    pub fn run(title: &'a str) -> Self {
        Self {
            title,
            tables: RUN_TABLES,
            runs: &[],
        }
    }

    /// The combined page of several runs (`OUT/combined/`), linking to `../NAME/report.html`.
    pub fn combined(runs: &'a [String]) -> Self {
        Self {
            title: "combined",
            tables: COMBINED_TABLES,
            runs,
        }
    }

    /// The page of a sweep (`OUT/<name>_sweep/`).
    pub fn sweep(title: &'a str) -> Self {
        Self {
            title,
            tables: SWEEP_TABLES,
            runs: &[],
        }
    }
}

/// Writes `dir/report.html` ([`render`]) atomically.
pub fn write_report(dir: &Path, page: &Page) -> io::Result<()> {
    let text = render(dir, page)?;
    crate::io::write_atomic(&dir.join(FILE_NAME), text.as_bytes())
}

/// The report page of the results folder `dir`, as HTML text. Reads `dir/run.toml` when present,
/// the tables `page.tables`, every `*.svg` and `*.png` in `dir` and its subfolders, and for
/// `page.runs` each `../NAME/run.toml`.
pub fn render(dir: &Path, page: &Page) -> io::Result<String> {
    render_files(&Files::Folder(dir), page)
}

/// The report page of a command's `outputs` in memory, as HTML text: byte for byte the page
/// [`render`] makes of the folder `outputs` writes ([`Outputs::write_folder`]). `page.runs` must
/// be empty (the runs beside a folder exist only on disk).
pub fn render_outputs(outputs: &Outputs, page: &Page) -> String {
    debug_assert!(
        page.runs.is_empty(),
        "a page of outputs in memory links no runs"
    );
    // Reading from memory cannot fail: a name not in `outputs` is never asked for.
    render_files(&Files::Memory(outputs), page).unwrap_or_default()
}

/// Where a page's files come from: a results folder, or a command's outputs in memory.
enum Files<'a> {
    Folder(&'a Path),
    Memory(&'a Outputs),
}

impl Files<'_> {
    /// Every file (relative paths, `/`-separated), in the order [`list_files`] gives a folder's.
    fn list(&self) -> io::Result<Vec<String>> {
        match self {
            Files::Folder(dir) => list_files(dir),
            Files::Memory(o) => Ok(walk_order(
                o.tables()
                    .iter()
                    .map(|t| t.name().to_string())
                    .chain(o.file_names().map(str::to_string)),
            )),
        }
    }

    /// The bytes of the file `rel`.
    fn read(&self, rel: &str) -> io::Result<Vec<u8>> {
        match self {
            Files::Folder(dir) => fs::read(dir.join(rel)),
            Files::Memory(o) => o
                .bytes(rel)
                .ok_or_else(|| io::Error::new(io::ErrorKind::NotFound, rel.to_string())),
        }
    }

    /// The folder the files are in, when they are on disk.
    fn folder(&self) -> Option<&Path> {
        match self {
            Files::Folder(dir) => Some(dir),
            Files::Memory(_) => None,
        }
    }
}

/// The relative paths `names` in the order [`list_files`] walks a folder holding them: at each
/// level the files first, sorted, then each subfolder's, sorted; hidden entries, temporary files,
/// the page itself and anything deeper than four levels left out.
fn walk_order(names: impl Iterator<Item = String>) -> Vec<String> {
    let mut out: Vec<String> = names
        .filter(|n| {
            let parts: Vec<&str> = n.split('/').collect();
            n != FILE_NAME
                && parts.len() <= 4
                && !parts.iter().any(|p| p.starts_with('.'))
                && !n.ends_with(crate::io::TMP_SUFFIX)
        })
        .collect();
    out.sort_by(|a, b| {
        let (pa, pb): (Vec<&str>, Vec<&str>) = (a.split('/').collect(), b.split('/').collect());
        for i in 0..pa.len().min(pb.len()) {
            if pa[i] != pb[i] {
                let (a_file, b_file) = (i + 1 == pa.len(), i + 1 == pb.len());
                return b_file.cmp(&a_file).then_with(|| pa[i].cmp(pb[i]));
            }
        }
        pa.len().cmp(&pb.len())
    });
    out.dedup();
    out
}

/// The page of the files `files`.
fn render_files(files: &Files, page: &Page) -> io::Result<String> {
    let dir = files.folder();
    let listed = files.list()?;
    let run_toml = read_run_toml(files);
    let run = run_toml.as_ref().and_then(|t| t.get("run")?.as_table());
    let scenario = run_toml.as_ref().map(scenario_table);
    let field = |k: &str| scenario.as_ref().and_then(|s| s.get(k)?.as_str());
    let name = field("name").unwrap_or(page.title);
    let charts = charts_of(&listed);
    let mut h = String::new();
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\
         <title>{} — settle report</title><style>{}</style></head><body>\n",
        esc(name),
        html::CSS
    );
    // Header: name, kind, status, description.
    let _ = write!(h, "<header><h1>{}</h1><div>", esc(name));
    if let Some(kind) = field("kind") {
        let _ = write!(h, "<span class=\"badge\">kind: {}</span>", esc(kind));
    }
    if let Some(status) = run.and_then(|r| r.get("status")?.as_str()) {
        let _ = write!(
            h,
            "<span class=\"badge {}\">{}</span>",
            class_name(status),
            esc(status)
        );
    }
    let n_warnings = string_list(run.and_then(|r| r.get("warnings"))).len();
    if n_warnings > 0 {
        let _ = write!(
            h,
            "<a class=\"badge warned\" href=\"#warnings\">{n_warnings} validity warning{}</a>",
            if n_warnings == 1 { "" } else { "s" }
        );
    }
    if !page.runs.is_empty() {
        let _ = write!(
            h,
            "<span class=\"badge\">{} runs combined</span>",
            page.runs.len()
        );
    }
    h.push_str("</div>");
    if let Some(d) = field("description").filter(|d| !d.trim().is_empty()) {
        let _ = write!(h, "<p class=\"desc\">{}</p>", esc(d));
    }
    let mut sections: Vec<(&str, &str, String)> = Vec::new();
    if let Some(run) = run {
        sections.push(("warnings", "Warnings", warnings_section(run)));
        sections.push(("record", "Run record", record_section(run)));
    }
    let runs = match dir {
        Some(dir) if !page.runs.is_empty() => Some((dir, page.runs)),
        _ => None,
    };
    if let Some((dir, names)) = runs {
        sections.push(("runs", "Runs", runs_section(dir, names)));
    }
    sections.push((
        "results",
        "Results",
        tables_section(files, &listed, page.tables),
    ));
    sections.push(("charts", "Charts", charts_section(files, &charts, runs)?));
    sections.push(("files", "Files", files_section(files, &listed)?));
    if let Some(s) = &scenario {
        sections.push(("scenario", "Scenario", scenario_section(s)));
    }
    sections.retain(|(_, _, html)| !html.is_empty());
    h.push_str("<nav>");
    for (id, label, _) in &sections {
        let _ = write!(h, "<a href=\"#{id}\">{label}</a>");
    }
    h.push_str("</nav></header>\n");
    for (_, _, html) in &sections {
        h.push_str(html);
    }
    h.push_str(
        "<footer><p class=\"note\">Written by settle from the files of this folder; \
         the numbers in the tables are rounded to 4 significant digits (hover for the \
         value in the CSV).</p></footer>\n</body></html>\n",
    );
    Ok(h)
}

/// `run.toml` of `files` as a table; `None` when absent or unreadable.
fn read_run_toml(files: &Files) -> Option<toml::Table> {
    String::from_utf8(files.read("run.toml").ok()?)
        .ok()?
        .parse()
        .ok()
}

/// The combined page's list of runs: each linked to its own page, with its kind, status,
/// number of warnings (and the warnings themselves) and wall time.
fn runs_section(dir: &Path, runs: &[String]) -> String {
    let parent = dir.parent().map(Path::to_path_buf).unwrap_or_default();
    let mut h = String::from(
        "<section id=\"runs\"><h2>Runs</h2><div class=\"scroll\"><table><thead><tr>\
         <th>run</th><th>kind</th><th>status</th><th>warnings</th><th>wall time (s)</th>\
         <th>description</th></tr></thead><tbody>\n",
    );
    let mut all_warnings = Vec::new();
    for name in runs {
        let t = read_run_toml(&Files::Folder(&parent.join(name)));
        let run = t.as_ref().and_then(|t| t.get("run")?.as_table());
        let sc = t.as_ref().map(scenario_table);
        let get = |k: &str| {
            sc.as_ref()
                .and_then(|s| s.get(k)?.as_str().map(str::to_string))
                .unwrap_or_default()
        };
        let status = run
            .and_then(|r| r.get("status")?.as_str())
            .unwrap_or("no run.toml");
        let warnings = string_list(run.and_then(|r| r.get("warnings")));
        let wall = run
            .and_then(|r| r.get("wall_time_s"))
            .map(value_text)
            .unwrap_or_default();
        let link = href(&format!("../{name}/{FILE_NAME}"));
        let _ = writeln!(
            h,
            "<tr><td><a href=\"{link}\">{}</a></td><td>{}</td>\
             <td><span class=\"badge {}\">{}</span></td>\
             <td class=\"n\">{}</td><td class=\"n\">{}</td><td>{}</td></tr>",
            esc(name),
            esc(&get("kind")),
            class_name(status),
            esc(status),
            if warnings.is_empty() {
                "0".to_string()
            } else {
                format!("<span class=\"badge warned\">{}</span>", warnings.len())
            },
            esc(&wall),
            esc(&get("description")),
        );
        all_warnings.extend(warnings.into_iter().map(|w| (name.clone(), w)));
    }
    h.push_str("</tbody></table></div>");
    if all_warnings.is_empty() {
        h.push_str(
            "<div class=\"box ok\">Validity warnings: <strong>none</strong> in any run.</div>",
        );
    } else {
        let _ = write!(
            h,
            "<div class=\"box warn\"><strong>{} validity warning{}</strong> in these runs:<ul>",
            all_warnings.len(),
            if all_warnings.len() == 1 { "" } else { "s" }
        );
        for (run, w) in &all_warnings {
            let _ = write!(h, "<li><strong>{}</strong>: {}</li>", esc(run), esc(w));
        }
        h.push_str("</ul></div>");
    }
    h.push_str("</section>\n");
    h
}

/// The key result tables present among `files` (`listed`), each headed by its linked file name.
fn tables_section(files: &Files, listed: &[String], tables: &[&str]) -> String {
    let mut h = String::from("<section id=\"results\"><h2>Results</h2>");
    let mut any = false;
    for name in tables {
        if !listed.iter().any(|l| l == name) {
            continue;
        }
        let _ = write!(h, "<h3><a href=\"{}\">{}</a></h3>", href(name), esc(name));
        match files
            .read(name)
            .ok()
            .and_then(|b| csv_table(&b, name, MAX_ROWS))
        {
            Some(t) => h.push_str(&t),
            None => h.push_str("<p class=\"note\">(not readable as a table)</p>"),
        }
        any = true;
    }
    if !any {
        h.push_str("<p class=\"note\">No result table in this folder: see the files below.</p>");
    }
    h.push_str("</section>\n");
    h
}

/// Every chart in `dir` and its subfolders (`*.svg`, `*.png`), as paths relative to `dir`:
/// the folder's own first, then each subfolder's, each sorted by name.
pub fn chart_files(dir: &Path) -> io::Result<Vec<String>> {
    Ok(charts_of(&list_files(dir)?))
}

/// The charts (`*.svg`, `*.png`) among the relative paths `listed`, in their order.
fn charts_of(listed: &[String]) -> Vec<String> {
    listed
        .iter()
        .filter(|r| {
            let l = r.to_ascii_lowercase();
            l.ends_with(".svg") || l.ends_with(".png")
        })
        .cloned()
        .collect()
}

/// Every file in `dir` and its subfolders (relative paths, `/`-separated; hidden entries,
/// temporary files and the page itself left out): the folder's own files first, sorted, then
/// each subfolder's.
fn list_files(dir: &Path) -> io::Result<Vec<String>> {
    fn walk(base: &Path, rel: &str, depth: usize, out: &mut Vec<String>) -> io::Result<()> {
        let here: PathBuf = if rel.is_empty() {
            base.to_path_buf()
        } else {
            base.join(rel)
        };
        let mut entries: Vec<(String, bool)> = fs::read_dir(&here)?
            .flatten()
            .filter_map(|e| {
                let n = e.file_name().to_str()?.to_string();
                let is_dir = e.file_type().ok()?.is_dir();
                (!n.starts_with('.') && !n.ends_with(crate::io::TMP_SUFFIX)).then_some((n, is_dir))
            })
            .collect();
        entries.sort();
        let join = |n: &str| {
            if rel.is_empty() {
                n.to_string()
            } else {
                format!("{rel}/{n}")
            }
        };
        for (n, _) in entries
            .iter()
            .filter(|(n, d)| !*d && (!rel.is_empty() || n != FILE_NAME))
        {
            out.push(join(n));
        }
        if depth < 3 {
            for (n, _) in entries.iter().filter(|(_, d)| *d) {
                walk(base, &join(n), depth + 1, out)?;
            }
        }
        Ok(())
    }
    let mut out = Vec::new();
    walk(dir, "", 0, &mut out)?;
    Ok(out)
}

/// Every chart of `files` (and, on the combined page, of each run in `runs`: the results folder
/// and the runs' names beside it), inlined, numbered, with a caption: its title and its linked
/// file name.
fn charts_section(
    files: &Files,
    charts: &[String],
    runs: Option<(&Path, &[String])>,
) -> io::Result<String> {
    let (dir, runs) = runs.unwrap_or((Path::new(""), &[]));
    let parent = dir.parent().map(Path::to_path_buf).unwrap_or_default();
    let mut groups: Vec<(Option<&str>, Vec<String>)> = Vec::new();
    if !charts.is_empty() {
        groups.push((None, charts.to_vec()));
    }
    for run in runs {
        let files = chart_files(&parent.join(run)).unwrap_or_default();
        if !files.is_empty() {
            groups.push((Some(run), files));
        }
    }
    if groups.is_empty() {
        return Ok(String::new());
    }
    let mut h = String::from("<section id=\"charts\"><h2>Charts</h2>\n");
    let mut n = 0;
    for (run, group) in &groups {
        if let Some(run) = run {
            let _ = writeln!(
                h,
                "<h3>{} <span class=\"note\">(<a href=\"{}\">its report</a>)</span></h3>",
                esc(run),
                href(&format!("../{run}/{FILE_NAME}"))
            );
        }
        for rel in group {
            n += 1;
            let (bytes, link) = match run {
                Some(run) => (
                    fs::read(parent.join(run).join(rel))?,
                    format!("../{run}/{rel}"),
                ),
                None => (files.read(rel)?, rel.clone()),
            };
            h.push_str(&figure(&bytes, &link, n));
        }
    }
    h.push_str("</section>\n");
    Ok(h)
}

/// One chart as a numbered figure: an SVG inlined (its ids made unique to figure `n`), a PNG as
/// a base64 `data:` URI, captioned with the chart's title and a link to the file.
fn figure(bytes: &[u8], link: &str, n: usize) -> String {
    let (body, title) = if link.to_ascii_lowercase().ends_with(".svg") {
        let text = String::from_utf8_lossy(bytes);
        match inline_svg(&text) {
            Some(svg) => (scope_ids(&svg, &format!("f{n}-")), svg_title(&text)),
            None => (
                "<p class=\"note\">(not a readable SVG)</p>".to_string(),
                None,
            ),
        }
    } else {
        (
            format!(
                "<img alt=\"{}\" src=\"data:image/png;base64,{}\">",
                esc(link),
                base64(bytes)
            ),
            None,
        )
    };
    format!(
        "<figure data-file=\"{}\">{body}<figcaption><strong>Figure {n}.</strong> {}\
         <a href=\"{}\">{}</a></figcaption></figure>\n",
        esc(link),
        title.map(|t| format!("{} — ", esc(&t))).unwrap_or_default(),
        href(link),
        esc(link)
    )
}

/// A file size as a person reads it (B, kB, MB, GB; powers of 1000).
fn size_text(bytes: u64) -> String {
    let b = bytes as f64;
    match bytes {
        0..=999 => format!("{bytes} B"),
        1_000..=999_999 => format!("{} kB", sig_trim(b / 1e3, 3)),
        1_000_000..=999_999_999 => format!("{} MB", sig_trim(b / 1e6, 3)),
        _ => format!("{} GB", sig_trim(b / 1e9, 3)),
    }
}

/// Every output file, linked, with its size; a folder with many files names the first
/// [`MAX_FILES_PER_FOLDER`] and counts the rest.
fn files_section(source: &Files, files: &[String]) -> io::Result<String> {
    let mut h = format!(
        "<section id=\"files\"><h2>Files</h2><p class=\"note\">{} files in this folder \
         (links open them).</p><ul class=\"files\">",
        files.len()
    );
    let mut per_folder: std::collections::BTreeMap<&str, usize> = Default::default();
    for rel in files {
        let folder = rel.rsplit_once('/').map_or("", |(f, _)| f);
        let n = per_folder.entry(folder).or_default();
        *n += 1;
        if !folder.is_empty() && *n > MAX_FILES_PER_FOLDER {
            continue;
        }
        let size = match source {
            Files::Folder(dir) => fs::metadata(dir.join(rel)).map(|m| m.len()).unwrap_or(0),
            Files::Memory(o) => o.bytes(rel).map_or(0, |b| b.len() as u64),
        };
        let _ = write!(
            h,
            "<li><a href=\"{}\">{}</a> <span class=\"size\">{}</span></li>",
            href(rel),
            esc(rel),
            size_text(size)
        );
    }
    for (folder, n) in per_folder
        .iter()
        .filter(|(f, n)| !f.is_empty() && **n > MAX_FILES_PER_FOLDER)
    {
        let _ = write!(
            h,
            "<li>… {} more in <a href=\"{}/\">{}/</a></li>",
            n - MAX_FILES_PER_FOLDER,
            href(folder),
            esc(folder)
        );
    }
    h.push_str("</ul></section>\n");
    Ok(h)
}

#[cfg(test)]
mod tests;
