//! Reading a chart back: every piece of text of an SVG file settle wrote (plotters writes each
//! as one `<text>` element), for the report page's captions and for the tests that read a chart
//! as a person would.

/// Every piece of text in an SVG document, in document order: tags inside a `<text>` element
/// dropped, XML entities unescaped, white space collapsed; empty texts skipped.
pub fn svg_texts(svg: &str) -> Vec<String> {
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

#[cfg(test)]
mod tests {
    use super::svg_texts;

    #[test]
    fn texts_are_unescaped_and_nested_tags_dropped() {
        let svg = r#"<svg><text x="1">A &lt;b&gt; &amp; c</text><text><tspan>d</tspan>  e</text><text> </text></svg>"#;
        assert_eq!(svg_texts(svg), vec!["A <b> & c", "d e"]);
    }
}
