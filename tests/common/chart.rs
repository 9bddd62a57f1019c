//! Reading a chart as a person would: its title, its axis labels with units, and tick labels that
//! print at most 6 significant digits (issue 13). Works on the SVG files settle writes (plotters
//! writes every piece of text as one `<text>` element).

use std::path::Path;

/// Every piece of text in an SVG file, unescaped, trimmed, in document order (as settle's own
/// `io::chart::svg_texts`, which the library keeps to itself).
pub fn svg_texts(path: &Path) -> Vec<String> {
    let svg = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("{}: cannot read ({e})", path.display()));
    texts_of(&svg)
}

/// Every piece of text in an SVG document, in document order: tags inside a `<text>` element
/// dropped, XML entities unescaped, white space collapsed; empty texts skipped.
fn texts_of(svg: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = svg;
    while let Some(i) = rest.find("<text") {
        rest = &rest[i..];
        let (Some(open_end), Some(close)) = (rest.find('>'), rest.find("</text>")) else {
            break;
        };
        let mut text = String::new();
        let mut in_tag = false;
        for c in rest[open_end + 1..close].chars() {
            match c {
                '<' => in_tag = true,
                '>' => in_tag = false,
                c if !in_tag => text.push(c),
                _ => {}
            }
        }
        let text = text
            .replace("&lt;", "<")
            .replace("&gt;", ">")
            .replace("&quot;", "\"")
            .replace("&apos;", "'")
            .replace("&#39;", "'")
            .replace("&amp;", "&");
        let text = text.split_whitespace().collect::<Vec<_>>().join(" ");
        if !text.is_empty() {
            out.push(text);
        }
        rest = &rest[close + "</text>".len()..];
    }
    out
}

/// The number a tick label prints, if the text is one (a leading sign, `−` or `-`, an optional
/// exponent `e-5`, `E+3` or `×10^-5`, an optional trailing `%`).
pub fn tick_value(text: &str) -> Option<f64> {
    let t = text.replace('−', "-").replace('%', "");
    let t = t.trim();
    if let Ok(x) = t.parse::<f64>() {
        return Some(x);
    }
    let (m, e) = t.split_once("×10^")?;
    Some(m.trim().parse::<f64>().ok()? * 10f64.powi(e.trim().parse::<i32>().ok()?))
}

/// Significant digits a numeric label prints: `0.00012` → 2, `1.2500e-4` → 5, `120` → 2,
/// `1.0000000000000002e-14` → 17.
pub fn significant_digits(text: &str) -> usize {
    let t = text.replace('−', "-");
    let mantissa = t
        .split(['e', 'E', '×'])
        .next()
        .unwrap_or("")
        .trim()
        .trim_start_matches(['-', '+']);
    let digits: String = mantissa.chars().filter(|c| c.is_ascii_digit()).collect();
    let trimmed = digits.trim_start_matches('0');
    if mantissa.contains('.') {
        trimmed.len().max(1)
    } else {
        trimmed.trim_end_matches('0').len().max(1)
    }
}

/// Whether a label names a unit: `(m/s)`, `[mm]`, or `(-)` for a pure number.
pub fn has_unit(label: &str) -> bool {
    let inside = |o: char, c: char| {
        label
            .rfind(o)
            .is_some_and(|i| label[i + o.len_utf8()..].contains(c) && label.ends_with(c))
    };
    inside('(', ')') || inside('[', ']')
}

/// Asserts that the SVG chart at `path` reads as issue 13 asks: a text containing `title`, one
/// text containing each of `axes` (x label, y label, …) that ends with its unit in brackets, and
/// every numeric label printed with at most 6 significant digits. Returns the texts for further
/// checks.
pub fn assert_readable_chart(path: &Path, title: &str, axes: &[&str]) -> Vec<String> {
    assert!(path.exists(), "{} was not written", path.display());
    let texts = svg_texts(path);
    let name = path.display();
    assert!(
        texts.iter().any(|t| t.contains(title)),
        "{name}: no title containing `{title}` among {texts:?}"
    );
    for axis in axes {
        let label = texts
            .iter()
            .find(|t| t.contains(axis))
            .unwrap_or_else(|| panic!("{name}: no axis label containing `{axis}` in {texts:?}"));
        assert!(
            has_unit(label),
            "{name}: axis label `{label}` has no unit in brackets"
        );
    }
    let ticks: Vec<&String> = texts.iter().filter(|t| tick_value(t).is_some()).collect();
    assert!(!ticks.is_empty(), "{name}: no tick labels in {texts:?}");
    for t in ticks {
        assert!(
            significant_digits(t) <= 6,
            "{name}: tick label `{t}` prints more than 6 significant digits"
        );
    }
    texts
}

#[test]
fn the_reader_counts_digits_and_units_as_a_person_does() {
    assert_eq!(significant_digits("0.00012"), 2);
    assert_eq!(significant_digits("1.2500e-4"), 5);
    assert_eq!(significant_digits("120"), 2);
    assert_eq!(significant_digits("−3.5"), 2);
    assert_eq!(significant_digits("9.999999999999999e-5"), 16);
    assert_eq!(significant_digits("1.0000000000000002e-14"), 17);
    assert_eq!(tick_value("1.5×10^-3"), Some(1.5e-3));
    assert_eq!(tick_value("25%"), Some(25.0));
    assert_eq!(tick_value("sphere 3"), None);
    assert!(has_unit("velocity (m/s)"));
    assert!(has_unit("depth [cm]"));
    assert!(has_unit("Reynolds number Re′ (-)"));
    assert!(!has_unit("velocity"));
}
