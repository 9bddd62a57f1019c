//! The report page on small folders and on outputs in memory.

use super::*;

/// A results folder with a run.toml recording two warnings (one with markup), a table and
/// a chart, removed when dropped.
struct Folder(PathBuf);

impl Drop for Folder {
    fn drop(&mut self) {
        let _ = fs::remove_dir_all(&self.0);
    }
}

fn folder(test: &str) -> Folder {
    let dir = std::env::temp_dir().join(format!("settle-report-{test}-{}", std::process::id()));
    fs::create_dir_all(dir.join("snapshots")).unwrap();
    fs::write(
        dir.join("run.toml"),
        "[run]\nstatus = \"complete\"\nwall_time_s = 2.064213979\n\
         warnings = [\"Re = 12 > 0.5: Stokes drag <invalid>\", \"second\"]\n\
         overrides = { set = [\"a.b=1\", \"c=2\"] }\n\
         [scenario]\nname = \"demo\"\nkind = \"free_settling\"\ndescription = \"a < b\"\n",
    )
    .unwrap();
    fs::write(
        dir.join("summary.csv"),
        "id,v_m_s,regime\nS1,0.123456,jump\n",
    )
    .unwrap();
    fs::write(
        dir.join("snapshots/v.svg"),
        "<svg width=\"10\" height=\"5\"><text>Title &amp; more</text></svg>",
    )
    .unwrap();
    Folder(dir)
}

#[test]
fn warnings_stand_out_escaped_and_every_part_is_there() {
    let f = folder("warnings");
    let h = render(&f.0, &Page::run("demo")).unwrap();
    assert!(
        h.contains("<div class=\"box warn\"><strong>2 warnings</strong>"),
        "{h}"
    );
    assert!(h.contains("<li>Re = 12 &gt; 0.5: Stokes drag &lt;invalid&gt;</li>"));
    assert!(h.contains("<p class=\"desc\">a &lt; b</p>"));
    assert!(h.contains("2.064 s (the run&#39;s cost)"));
    assert!(h.contains(">set: a.b=1, c=2<"), "{h}");
    assert!(h.contains("<td class=\"n\" title=\"0.123456\">0.1235</td>"));
    assert!(h.contains("<figure data-file=\"snapshots/v.svg\"><svg viewBox=\"0 0 10 5\""));
    assert!(h.contains("Title &amp; more — <a href=\"snapshots/v.svg\">"));
    assert!(h.contains("[scenario]") || h.contains("name = &quot;demo&quot;"));
    assert!(!h.contains("report.html\">"), "the page lists itself");
}

#[test]
fn no_warnings_reads_none() {
    let f = folder("none");
    let t = fs::read_to_string(f.0.join("run.toml")).unwrap();
    let t = t.replace(
        "warnings = [\"Re = 12 > 0.5: Stokes drag <invalid>\", \"second\"]",
        "warnings = []",
    );
    fs::write(f.0.join("run.toml"), t).unwrap();
    let h = render(&f.0, &Page::run("demo")).unwrap();
    assert!(
        h.contains("<div class=\"box ok\"><strong>none</strong>"),
        "{h}"
    );
}

/// The page of a command's outputs in memory is the page of the folder they are written
/// to, byte for byte: the same files in the same order (root files before subfolders, at
/// every depth), the same tables, charts and sizes; hidden files and the page itself left
/// out in both.
#[test]
fn outputs_in_memory_render_as_their_folder() {
    let mut o = Outputs::new();
    o.table(crate::io::Table::from_csv("sweep.csv", b"dt_s,error\n0.001,0.5\n").unwrap());
    o.table(crate::io::Table::from_csv("recommended_dt.csv", b"id,dt_s\nS1,1e-3\n").unwrap());
    o.file(
        "b/z.svg",
        "<svg width=\"2\" height=\"1\"><text>Z</text></svg>",
    );
    o.file("b/a/deep.txt", "x");
    o.file(
        "a.svg",
        "<svg width=\"3\" height=\"1\"><text>A</text></svg>",
    );
    o.file("b/c/d/e/too_deep.txt", "y");
    o.file("b/.hidden", "h");
    o.file("ab.png", [137u8, 80, 78, 71]);
    o.file(
        "run.toml",
        "[scenario]\nname = \"s\"\nkind = \"free_settling\"\n",
    );
    let dir = std::env::temp_dir().join(format!("settle-report-mem-{}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    let f = Folder(dir);
    o.write_into(&f.0).unwrap();
    let page = Page::sweep("s");
    let from_folder = render(&f.0, &page).unwrap();
    assert_eq!(render_outputs(&o, &page), from_folder);
    let order: Vec<&str> = [
        "a.svg",
        "ab.png",
        "run.toml",
        "sweep.csv",
        "b/z.svg",
        "b/a/deep.txt",
    ]
    .into_iter()
    .collect();
    let pos: Vec<usize> = order
        .iter()
        .map(|n| from_folder.find(&format!(">{n}</a> <span")).expect(n))
        .collect();
    assert!(pos.windows(2).all(|w| w[0] < w[1]), "{order:?} at {pos:?}");
    assert!(!from_folder.contains("too_deep") && !from_folder.contains(".hidden"));
}
