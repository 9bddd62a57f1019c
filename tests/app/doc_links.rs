//! Every relative link of the documentation resolves: the Markdown files at the top of the
//! repository (`README.md`, …) and every page under `docs/`. A link names an existing file or
//! folder, and its `#anchor`, when it points into a Markdown page, names one of that page's
//! headings (as GitHub spells the anchor of a heading). Links to the web are not followed.

use crate::common::tmp;
use std::path::{Path, PathBuf};

/// The anchor GitHub gives a heading: lower case, every character that is not a letter, a digit,
/// `_`, `-` or a space dropped, spaces turned into `-`.
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, '_' | '-' | ' '))
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// The lines of `text` outside fenced code blocks.
fn prose_lines(text: &str) -> Vec<&str> {
    let mut fenced = false;
    let mut out = Vec::new();
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
        } else if !fenced {
            out.push(line);
        }
    }
    out
}

/// The anchors of a Markdown text: its headings' (a repeated heading gets `-1`, `-2`, …) and
/// its HTML `id="…"` attributes.
fn anchors(text: &str) -> Vec<String> {
    let mut seen: Vec<String> = Vec::new();
    let mut bases: Vec<String> = Vec::new();
    for line in prose_lines(text) {
        for part in line.split("id=\"").skip(1) {
            if let Some((id, _)) = part.split_once('"') {
                seen.push(id.to_string());
            }
        }
        let Some(h) = line.strip_prefix('#') else {
            continue;
        };
        let base = slug(h.trim_start_matches('#'));
        let n = bases.iter().filter(|b| **b == base).count();
        seen.push(if n == 0 {
            base.clone()
        } else {
            format!("{base}-{n}")
        });
        bases.push(base);
    }
    seen
}

/// The link targets `[text](target)` of a Markdown text, outside code blocks and code spans.
fn links(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for line in prose_lines(text) {
        // Drop code spans: the odd pieces between backticks.
        let prose: String = line.split('`').step_by(2).collect::<Vec<_>>().join(" ");
        let mut rest = prose.as_str();
        while let Some(i) = rest.find("](") {
            let after = &rest[i + 2..];
            let Some(end) = after.find(')') else {
                break;
            };
            out.push(after[..end].trim().to_string());
            rest = &after[end..];
        }
    }
    out
}

/// The relative links of the Markdown file `file` that do not resolve, each as
/// `file: target (why)`, and the number of relative links checked.
fn broken_links(file: &Path) -> (Vec<String>, usize) {
    let text = std::fs::read_to_string(file).unwrap();
    let dir = file.parent().unwrap();
    let mut broken = Vec::new();
    let mut checked = 0;
    for target in links(&text) {
        if target.contains("://") || target.starts_with("mailto:") {
            continue;
        }
        checked += 1;
        let (path, anchor) = match target.split_once('#') {
            Some((p, a)) => (p, Some(a)),
            None => (target.as_str(), None),
        };
        let resolved = if path.is_empty() {
            file.to_path_buf()
        } else {
            dir.join(path)
        };
        if !resolved.exists() {
            broken.push(format!("{}: {target} (no such file)", file.display()));
            continue;
        }
        let Some(anchor) = anchor else {
            continue;
        };
        if resolved.extension().is_some_and(|e| e == "md") {
            let page = std::fs::read_to_string(&resolved).unwrap();
            if !anchors(&page).iter().any(|a| a == anchor) {
                broken.push(format!("{}: {target} (no such heading)", file.display()));
            }
        }
    }
    (broken, checked)
}

/// The Markdown files of `dir`, and of its folders below.
fn markdown_under(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let p = e.path();
        if p.is_dir() {
            markdown_under(&p, out);
        } else if p.extension().is_some_and(|x| x == "md") {
            out.push(p);
        }
    }
}

#[test]
fn the_anchor_of_a_heading_is_spelt_as_github_spells_it() {
    assert_eq!(slug(" Speed of the cylinder"), "speed-of-the-cylinder");
    assert_eq!(slug(" `[fluid]`"), "fluid");
    assert_eq!(
        slug(" The suspended grains packed; the cost with contacts against N (issue 17, stop 21)"),
        "the-suspended-grains-packed-the-cost-with-contacts-against-n-issue-17-stop-21"
    );
    assert_eq!(
        anchors("# A\n## B\n## B c\n```\n# not a heading\n```\n## B\n<a id=\"here\"></a>x\n"),
        ["a", "b", "b-c", "b-1", "here"]
    );
    assert_eq!(
        links("[x](a.md) `[y](code.md)` ![z](img/p.png#top)\n```\n[w](in_block.md)\n```\n"),
        ["a.md", "img/p.png#top"]
    );
}

/// The checker fails on a missing file and on a missing heading, and passes good links.
#[test]
fn a_link_to_a_missing_file_or_heading_is_reported() {
    let dir = tmp();
    let page = dir.path().join("page.md");
    std::fs::write(dir.path().join("other.md"), "# Other\n## Its part\n").unwrap();
    std::fs::write(
        &page,
        "# Page\n[ok](other.md#its-part) [self](#page) [web](https://example.org/x.md)\n\
         [gone](missing.md) [no heading](other.md#nothing)\n",
    )
    .unwrap();
    let (broken, checked) = broken_links(&page);
    assert_eq!(checked, 4);
    assert_eq!(broken.len(), 2, "{broken:?}");
    assert!(
        broken[0].contains("missing.md (no such file)"),
        "{broken:?}"
    );
    assert!(
        broken[1].contains("other.md#nothing (no such heading)"),
        "{broken:?}"
    );
}

/// Every relative link of `README.md` (and the other Markdown files at the top) and of
/// `docs/**/*.md` points to an existing file, and to an existing heading where it names one.
#[test]
fn every_relative_link_of_the_readme_and_docs_resolves() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files: Vec<PathBuf> = std::fs::read_dir(root)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.is_file() && p.extension().is_some_and(|x| x == "md"))
        .collect();
    markdown_under(&root.join("docs"), &mut files);
    assert!(files.iter().any(|f| f.ends_with("README.md")), "{files:?}");
    let mut broken = Vec::new();
    let mut checked = 0;
    for f in &files {
        let (b, n) = broken_links(f);
        broken.extend(b);
        checked += n;
    }
    assert!(checked >= 100, "only {checked} relative links found");
    assert!(
        broken.is_empty(),
        "{} broken links:\n{}",
        broken.len(),
        broken.join("\n")
    );
}
