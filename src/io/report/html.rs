//! The pieces of a report page: escaping, relative links, numbers to significant digits, base64
//! for inlined PNGs, tables from CSV files, charts inlined, and the page's style sheet.

use crate::io::fmt::sig_trim;
use std::fmt::Write as _;

/// Significant digits of the numbers a report's tables show (the CSV keeps every digit).
pub const TABLE_DIGITS: usize = 4;

/// The page's style: system fonts only (nothing fetched), a readable width, numbers right-aligned.
pub const CSS: &str = "
:root{color-scheme:light}
body{font-family:system-ui,-apple-system,'Segoe UI',Roboto,'DejaVu Sans',Arial,sans-serif;
 max-width:1180px;margin:0 auto;padding:18px 28px 60px;color:#1d1d1f;background:#fff;
 line-height:1.45;font-size:15px}
h1{font-size:1.75em;margin:.1em 0 .15em}
h2{font-size:1.3em;border-bottom:2px solid #e3e6ea;padding-bottom:.15em;margin:1.7em 0 .6em}
h3{font-size:1.05em;margin:1.2em 0 .4em}
a{color:#0b57d0}
code,pre{font-family:'DejaVu Sans Mono',Menlo,Consolas,monospace;font-size:.9em}
.desc{font-size:1.05em;color:#333;margin:.2em 0 .6em}
.badge{display:inline-block;padding:1px 9px;border-radius:10px;font-size:.85em;
 background:#e7ecf3;color:#223;margin-right:6px;vertical-align:middle}
.badge.complete{background:#d3f9d8;color:#1b5e20}
.badge.interrupted,.badge.warned{background:#ffe8cc;color:#8a3b00}
nav{margin:.6em 0 0;font-size:.92em}
nav a{margin-right:1.1em}
.box{border-left:6px solid;padding:.5em 1em;margin:.6em 0;border-radius:3px}
.box.warn{background:#fff4e6;border-color:#e8590c}
.box.ok{background:#ebfbee;border-color:#2f9e44}
.box ul{margin:.3em 0;padding-left:1.3em}
.box li{margin:.2em 0}
.note{color:#555;font-size:.9em;margin:.3em 0}
.scroll{overflow-x:auto;max-width:100%}
table{border-collapse:collapse;font-size:12.5px;margin:.3em 0}
th,td{border:1px solid #dde1e6;padding:3px 6px;vertical-align:top}
th{background:#f1f3f5;text-align:left;font-weight:600}
tbody tr{background:#fff}
tbody tr:nth-child(even){background:#f8f9fa}
.wide{width:calc(100vw - 60px);max-width:none;position:relative;left:50%;transform:translateX(-50%)}
.wide table{margin:.3em auto}
.wide td:first-child,.wide th:first-child{position:sticky;left:0;background:inherit;
 box-shadow:1px 0 0 #c9ced4}
.wide thead tr{background:#f1f3f5}
td.t{white-space:nowrap}
td.n{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
.kv{display:grid;grid-template-columns:repeat(auto-fill,minmax(270px,1fr));gap:0 18px;
 font-size:13.5px;margin:.3em 0}
.kv>div{display:flex;justify-content:space-between;gap:10px;border-bottom:1px solid #eceef1;
 padding:3px 2px}
.kv>div.long{grid-column:span 2}
.kv .k{color:#444;white-space:nowrap}
.kv .v{font-weight:600;text-align:right;overflow-wrap:anywhere}
.kv .v.n{font-variant-numeric:tabular-nums}
figure{margin:1.2em 0;padding:10px;border:1px solid #e3e6ea;border-radius:4px}
figure svg,figure img{display:block;max-width:100%;height:auto;margin:0 auto}
figcaption{margin-top:.5em;font-size:.95em;color:#333}
ul.files{columns:2;column-gap:2.5em;padding-left:1.2em}
ul.files li{break-inside:avoid}
.size{color:#777;font-size:.88em}
details{margin:.5em 0}
summary{cursor:pointer;font-weight:600}
pre{background:#f6f8fa;border:1px solid #e3e6ea;padding:10px 12px;overflow-x:auto}
";

/// Escapes text for HTML content and attribute values (`&`, `<`, `>`, `\"`, `'`).
pub fn esc(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// A relative link to a local file, percent-encoded (`/` kept) and escaped for an attribute.
pub fn href(rel: &str) -> String {
    let mut out = String::new();
    for b in rel.bytes() {
        if b.is_ascii_alphanumeric() || b"-_.~/".contains(&b) {
            out.push(b as char);
        } else {
            let _ = write!(out, "%{b:02X}");
        }
    }
    out
}

/// A CSV cell as shown: a number with a fraction or an exponent to [`TABLE_DIGITS`]
/// significant digits (whole numbers as written), and whether it is a number (right-aligned).
pub fn cell(raw: &str) -> (String, bool) {
    let t = raw.trim();
    match t.parse::<f64>() {
        Ok(x) if t.contains(['.', 'e', 'E']) && x.is_finite() => (sig_trim(x, TABLE_DIGITS), true),
        Ok(_) if t.bytes().any(|b| b.is_ascii_digit()) || t.eq_ignore_ascii_case("nan") => {
            (t.trim_start_matches('+').to_string(), true)
        }
        _ => (t.to_string(), false),
    }
}

/// Standard base64 (RFC 4648, with padding) of `bytes`, for `data:` URIs.
pub fn base64(bytes: &[u8]) -> String {
    const ABC: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for i in 0..4 {
            if i <= chunk.len() {
                out.push(ABC[((n >> (18 - 6 * i)) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// The title of an SVG chart: its first `<text>` element (settle's charts draw the title
/// first), unescaped and trimmed; `None` when it has no text.
pub fn svg_title(svg: &str) -> Option<String> {
    crate::io::chart::svg_texts(svg).into_iter().next()
}

/// An SVG file's markup for embedding in HTML: from its `<svg` element on (no XML prolog or
/// doctype), with a `viewBox` from its width and height when it has none, so that it scales
/// down to the page width. `None` when the text has no `<svg` element.
pub fn inline_svg(svg: &str) -> Option<String> {
    let start = svg.find("<svg")?;
    let body = &svg[start..];
    let open_end = body.find('>')?;
    let open = &body[..open_end];
    if open.contains("viewBox") {
        return Some(body.to_string());
    }
    let attr = |name: &str| -> Option<f64> {
        let key = format!(" {name}=\"");
        let i = open.find(&key)? + key.len();
        let v = &open[i..];
        v[..v.find('"')?].trim_end_matches("px").parse().ok()
    };
    match (attr("width"), attr("height")) {
        (Some(w), Some(hgt)) => Some(format!(
            "<svg viewBox=\"0 0 {w} {hgt}\"{}",
            &body["<svg".len()..]
        )),
        _ => Some(body.to_string()),
    }
}

/// An inlined SVG's ids prefixed with `prefix` (and the references to them), so that two charts
/// on one page never share an id (a clip path of one chart would clip the other).
pub fn scope_ids(svg: &str, prefix: &str) -> String {
    svg.replace(" id=\"", &format!(" id=\"{prefix}"))
        .replace("url(#", &format!("url(#{prefix}"))
        .replace("href=\"#", &format!("href=\"#{prefix}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_markup_and_quotes() {
        assert_eq!(
            esc("a<b & \"c\" 'd'>"),
            "a&lt;b &amp; &quot;c&quot; &#39;d&#39;&gt;"
        );
    }

    #[test]
    fn base64_matches_rfc_4648_vectors() {
        for (raw, enc) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(raw.as_bytes()), enc, "{raw}");
        }
        assert_eq!(base64(&[0xFF, 0xFE, 0xFD]), "//79");
    }

    #[test]
    fn numbers_to_significant_digits_without_noise_or_negative_zero() {
        assert_eq!(sig_trim(0.15468578413257608, 4), "0.1547");
        assert_eq!(sig_trim(9.190158771602966e7, 4), "9.19e7");
        assert_eq!(sig_trim(1.3977750784161776e-13, 4), "1.398e-13");
        assert_eq!(sig_trim(9.999999999999999e-5, 4), "1e-4");
        assert_eq!(sig_trim(0.001, 4), "0.001");
        assert_eq!(sig_trim(-0.0, 4), "0");
        assert_eq!(sig_trim(-0.00001, 1), "-1e-5");
        assert_eq!(sig_trim(2.064213979, 4), "2.064");
        assert_eq!(sig_trim(99999.96, 4), "100000");
        assert_eq!(sig_trim(f64::NAN, 4), "NaN");
    }

    #[test]
    fn cells_keep_whole_numbers_and_text() {
        assert_eq!(cell("6450"), ("6450".to_string(), true));
        assert_eq!(cell("0.0012345678"), ("0.001235".to_string(), true));
        assert_eq!(cell("NaN"), ("NaN".to_string(), true));
        assert_eq!(cell("steady"), ("steady".to_string(), false));
        assert_eq!(cell("S1-01"), ("S1-01".to_string(), false));
        assert_eq!(cell(""), (String::new(), false));
    }

    #[test]
    fn links_are_percent_encoded() {
        assert_eq!(href("../a b/report.html"), "../a%20b/report.html");
        assert_eq!(href("x\"<y"), "x%22%3Cy");
    }

    #[test]
    fn svg_title_and_view_box() {
        let svg = "<?xml version=\"1.0\"?>\n<svg width=\"900\" height=\"600\" xmlns=\"x\">\
                   <text x=\"1\">\n a &amp; b\n</text></svg>";
        assert_eq!(svg_title(svg).as_deref(), Some("a & b"));
        let inl = inline_svg(svg).unwrap();
        assert!(
            inl.starts_with("<svg viewBox=\"0 0 900 600\" width=\"900\""),
            "{inl}"
        );
    }
}
