//! The report page of a run (issue 13, item 2): `OUT/NAME/report.html` is self-contained (no
//! script, no style sheet or font fetched, no link off the machine, every link to a file that
//! exists), inlines every chart the run wrote, shows the run's validity warnings or "none", and
//! escapes the text it inserts; `OUT/combined/report.html` links to each run's page.

use crate::common::chart::svg_texts;
use crate::common::{assert_exit, settle, tmp};
use std::path::{Path, PathBuf};

/// Runs `settle run` with `args` into `out`; panics with its output unless it exits 0.
fn run(out: &Path, args: &[&str]) {
    let o = settle()
        .arg("run")
        .args(args)
        .arg("--out")
        .arg(out)
        .arg("--quiet")
        .output()
        .expect("run settle");
    assert_exit(&o, 0);
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The values of every `NAME="…"` or `NAME='…'` attribute in `html`.
fn attribute_values(html: &str, name: &str) -> Vec<String> {
    let mut out = Vec::new();
    for quote in ['"', '\''] {
        let key = format!(" {name}={quote}");
        let mut rest = html;
        while let Some(i) = rest.find(&key) {
            rest = &rest[i + key.len()..];
            let end = rest.find(quote).expect("closed attribute");
            out.push(rest[..end].to_string());
            rest = &rest[end..];
        }
    }
    out
}

/// `%XX` escapes decoded (the page percent-encodes its links).
fn percent_decode(s: &str) -> String {
    let b = s.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' && i + 2 < b.len() {
            let hex = std::str::from_utf8(&b[i + 1..i + 3]).unwrap();
            out.push(u8::from_str_radix(hex, 16).expect("hex escape"));
            i += 3;
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    String::from_utf8(out).unwrap()
}

/// Asserts the page at `page` needs nothing from a network: no script or style sheet loaded, no
/// `src` or `href` leaving the machine, and every relative link naming a file or folder that
/// exists beside the page.
fn assert_self_contained(page: &Path) {
    let html = read(page);
    let lower = html.to_ascii_lowercase();
    for bad in [
        "<script", "<link", "@import", "<iframe", "<object", "<embed",
    ] {
        assert!(!lower.contains(bad), "{}: contains {bad}", page.display());
    }
    assert!(
        lower.matches("url(").count() == lower.matches("url(#").count(),
        "{}: a url() that is not a reference inside the page",
        page.display()
    );
    let dir = page.parent().unwrap();
    for src in attribute_values(&html, "src") {
        assert!(
            src.starts_with("data:image/png;base64,"),
            "{}: src={src:.80} is not inlined",
            page.display()
        );
    }
    let hrefs = attribute_values(&html, "href");
    assert!(!hrefs.is_empty(), "{}: links nothing", page.display());
    for href in hrefs {
        assert!(
            !href.contains("//") && !href.contains(':'),
            "{}: href={href} leaves the folder",
            page.display()
        );
        if let Some(anchor) = href.strip_prefix('#') {
            assert!(
                html.contains(&format!("id=\"{anchor}\"")),
                "{}: no #{anchor} in the page",
                page.display()
            );
        } else {
            let target: PathBuf = dir.join(percent_decode(&href));
            assert!(
                target.exists(),
                "{}: href={href} names {}, which does not exist",
                page.display(),
                target.display()
            );
        }
    }
}

/// Every `*.svg` and `*.png` under `dir`, relative to it, `/`-separated.
fn charts_in(dir: &Path) -> Vec<String> {
    crate::common::tree(dir)
        .into_iter()
        .filter(|p| matches!(p.extension().and_then(|e| e.to_str()), Some("svg" | "png")))
        .map(|p| p.to_string_lossy().replace('\\', "/"))
        .collect()
}

/// The HTML of the figure showing `rel` in `html`; panics when there is none.
fn figure<'a>(html: &'a str, rel: &str) -> &'a str {
    let key = format!("<figure data-file=\"{rel}\">");
    let start = html
        .find(&key)
        .unwrap_or_else(|| panic!("no figure for {rel}"));
    let len = html[start..].find("</figure>").expect("closed figure");
    &html[start..start + len]
}

/// The bytes of standard base64 text (RFC 4648, with padding), decoded here rather than encoded
/// with the crate's own encoder, so that the page is checked against the chart's file.
fn base64_decode(text: &str) -> Vec<u8> {
    const ABC: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let value = |c: u8| ABC.iter().position(|&a| a == c).expect("a base64 digit") as u32;
    let mut out = Vec::with_capacity(text.len() / 4 * 3);
    for quad in text.as_bytes().chunks(4) {
        assert_eq!(quad.len(), 4, "base64 comes in groups of 4: {text}");
        let pad = quad.iter().filter(|&&c| c == b'=').count();
        let n = quad.iter().fold(0u32, |n, &c| {
            (n << 6) | if c == b'=' { 0 } else { value(c) }
        });
        out.extend_from_slice(&n.to_be_bytes()[1..4 - pad]);
    }
    out
}

/// Asserts every chart in `dir` is inlined in its report page: an SVG's markup (its `<svg>` and
/// every `<text>` of it), a PNG as the base64 of its bytes.
fn assert_every_chart_inlined(dir: &Path) -> usize {
    let html = read(&dir.join("report.html"));
    let charts = charts_in(dir);
    for rel in &charts {
        let fig = figure(&html, rel);
        let file = dir.join(rel);
        if rel.ends_with(".svg") {
            assert!(
                fig.contains("<svg") && fig.contains("</svg>"),
                "{rel}: not inlined"
            );
            let svg_part = &fig[fig.find("<svg").unwrap()..fig.rfind("</svg>").unwrap()];
            let inlined = dir.join(".inlined.svg");
            std::fs::write(&inlined, svg_part).unwrap();
            assert_eq!(
                svg_texts(&inlined),
                svg_texts(&file),
                "{rel}: the inlined chart differs in its text"
            );
            std::fs::remove_file(&inlined).unwrap();
        } else {
            let bytes = std::fs::read(&file).unwrap();
            let prefix = "src=\"data:image/png;base64,";
            let at = fig
                .find(prefix)
                .unwrap_or_else(|| panic!("{rel}: not inlined as a PNG data URI"));
            let data = &fig[at + prefix.len()..];
            let data = &data[..data.find('"').unwrap()];
            assert_eq!(
                base64_decode(data),
                bytes,
                "{rel}: not inlined as its own bytes"
            );
        }
    }
    charts.len()
}

/// The validity warnings `run.toml` records for the run in `dir`.
fn recorded_warnings(dir: &Path) -> Vec<String> {
    let t: toml::Table = read(&dir.join("run.toml")).parse().unwrap();
    t["run"]["warnings"]
        .as_array()
        .expect("[run] warnings")
        .iter()
        .map(|w| w.as_str().unwrap().to_string())
        .collect()
}

fn escaped(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
        .replace('\'', "&#39;")
}

/// Asserts the warnings section shows each recorded warning, or says "none".
fn assert_warnings_shown(dir: &Path) {
    let html = read(&dir.join("report.html"));
    let start = html
        .find("<section id=\"warnings\">")
        .expect("warnings section");
    let section = &html[start..start + html[start..].find("</section>").unwrap()];
    let warnings = recorded_warnings(dir);
    if warnings.is_empty() {
        assert!(section.contains("<strong>none</strong>"), "{section}");
    }
    for w in warnings {
        assert!(section.contains(&escaped(&w)), "warning {w} not shown");
    }
}

#[test]
fn a_run_report_is_self_contained_and_escapes_what_it_shows() {
    let out = tmp();
    let description = "Clay <b>suspension</b> 1 & \"spheres\" <script>alert(1)</script>";
    run(
        out.path(),
        &[
            "scenarios/valentik_susp1.toml",
            "--set",
            &format!("description={description}"),
        ],
    );
    let dir = out.path().join("valentik_susp1");
    let page = dir.join("report.html");
    assert_self_contained(&page);
    let html = read(&page);
    assert!(
        html.contains(&escaped(description)),
        "description not shown escaped"
    );
    assert!(
        !html.contains("<b>suspension"),
        "the description's markup was not escaped"
    );
    assert!(
        assert_every_chart_inlined(&dir) >= 1,
        "the run wrote no chart"
    );
    assert_warnings_shown(&dir);
    // The record and the key results: status, wall time (the cost), the first sphere's row.
    for part in [
        "complete",
        "wall_time_s",
        "the run's cost",
        "summary.csv",
        "S1-01",
    ] {
        assert!(html.contains(&escaped(part)), "no {part} in the page");
    }
    // The effective scenario, folded, and the output files listed.
    assert!(html.contains("<details>") && html.contains("[fluid]"));
    assert!(html.contains("href=\"timeseries.csv\""), "files not listed");
}

#[test]
fn a_cylinder_report_inlines_its_charts_and_its_instrument_errors() {
    let out = tmp();
    run(
        out.path(),
        &[
            "scenarios/sedimentation_sample2.toml",
            "--set",
            "sample.particles=2000",
        ],
    );
    let dir = out.path().join("sedimentation_sample2");
    assert_self_contained(&dir.join("report.html"));
    let charts = charts_in(&dir);
    // The cylinder picture (seed Fig. 11) is an SVG since issue 13 (`cylinder.png` is gone).
    for c in ["cylinder.svg", "granulometry.svg", "transient.svg"] {
        assert!(charts.iter().any(|x| x == c), "no {c} in {charts:?}");
    }
    assert_eq!(assert_every_chart_inlined(&dir), charts.len());
    assert_warnings_shown(&dir);
    let html = read(&dir.join("report.html"));
    assert!(html.contains("instrument_errors.csv") && html.contains("hydrometer"));
}

#[test]
fn the_combined_report_links_each_run_with_its_status_and_warnings() {
    let out = tmp();
    run(
        out.path(),
        &[
            "scenarios/valentik_susp1.toml",
            "scenarios/valentik_susp2.toml",
        ],
    );
    let page = out.path().join("combined/report.html");
    assert_self_contained(&page);
    let html = read(&page);
    for name in ["valentik_susp1", "valentik_susp2"] {
        let link = format!("<a href=\"../{name}/report.html\">{name}</a>");
        let row_start = html
            .find(&link)
            .unwrap_or_else(|| panic!("no link to {name}"));
        let row = &html[row_start..row_start + html[row_start..].find("</tr>").unwrap()];
        let n = recorded_warnings(&out.path().join(name)).len();
        assert!(row.contains("complete"), "{name}: status not shown: {row}");
        assert!(
            row.contains(&format!(">{n}<")),
            "{name}: {n} warnings not counted: {row}"
        );
    }
    // The combined folder's charts, and each run's, are inlined too.
    let combined = out.path().join("combined");
    assert_eq!(
        assert_every_chart_inlined(&combined),
        charts_in(&combined).len()
    );
    for name in ["valentik_susp1", "valentik_susp2"] {
        for rel in charts_in(&out.path().join(name)) {
            figure(&html, &format!("../{name}/{rel}"));
        }
    }
    assert!(
        html.contains("<a href=\"summary.csv\">summary.csv</a>"),
        "no combined table"
    );
}

#[test]
fn a_sweep_gets_a_report_with_its_charts_and_recommendation() {
    let out = tmp();
    let o = settle()
        .args([
            "sweep",
            "scenarios/stokes_single.toml",
            "--dt",
            "1e-2,1e-3",
            "--out",
        ])
        .arg(out.path())
        .arg("--quiet")
        .output()
        .expect("run settle");
    assert_exit(&o, 0);
    let dir = out.path().join("stokes_single_sweep");
    assert_self_contained(&dir.join("report.html"));
    assert!(
        assert_every_chart_inlined(&dir) >= 1,
        "the sweep wrote no chart"
    );
    let html = read(&dir.join("report.html"));
    assert!(html.contains("<a href=\"recommended_dt.csv\">recommended_dt.csv</a>"));
}
