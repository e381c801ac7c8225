//! The HTML of `report.html`: escaping, the page with its inline style, figures, tables.

use std::fmt::Write as _;

/// Text for HTML: `&`, `<`, `>` and quotes escaped.
#[must_use]
pub fn escape(text: &str) -> String {
    let mut s = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => s.push_str("&amp;"),
            '<' => s.push_str("&lt;"),
            '>' => s.push_str("&gt;"),
            '"' => s.push_str("&quot;"),
            '\'' => s.push_str("&#39;"),
            c => s.push(c),
        }
    }
    s
}

/// The page: up to 1320 px of text and figures (a 1400 px figure is shown nearly at its size
/// on a 1400 px screen); tables wrap their header and text cells to fit, and sit in a
/// container that scrolls sideways rather than cut a column off if a table still does not fit.
const STYLE: &str = "body{font-family:sans-serif;margin:2em auto;max-width:1320px;color:#222;\
padding:0 1em}h1{font-size:1.6em}h2{margin-top:2em;border-bottom:1px solid #ccc}\
table{border-collapse:collapse;font-size:.85em;margin:.5em 0}\
th,td{border:1px solid #ccc;padding:2px 6px;text-align:right}\
th{background:#f2f2f2;vertical-align:bottom}td{vertical-align:top}\
td:first-child,th:first-child,td.l,th.l{text-align:left}\
pre{background:#f7f7f7;padding:.8em;overflow-x:auto;font-size:.85em}\
figure{margin:1.5em 0}figure svg{max-width:100%;height:auto;border:1px solid #eee}\
figcaption{font-size:.9em;color:#555}.scroll{overflow-x:auto;max-width:100%}\
.meta td,.meta th{text-align:left}";

pub(crate) fn page(title: &str, body: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>{}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n{body}</body>\n</html>\n",
        escape(title)
    )
}

pub(crate) fn figure_html(s: &mut String, id: &str, caption: &str, svg: &str) {
    // The SVG document's XML declaration (if any) is not valid inside HTML.
    let svg = svg.find("<svg").map_or(svg, |at| &svg[at..]).trim_end();
    let _ = writeln!(
        s,
        "<figure id=\"{}\">\n{svg}\n<figcaption>{}</figcaption>\n</figure>",
        escape(id),
        escape(caption)
    );
}

/// A table from rows of cells (the first row is the header).
pub(crate) fn table(s: &mut String, class: &str, rows: &[Vec<String>]) {
    table_aligned(s, class, rows, &[]);
}

/// A table from rows of cells (the first row is the header), the columns `left` (text)
/// aligned left, the others (numbers) right.
pub(crate) fn table_aligned(s: &mut String, class: &str, rows: &[Vec<String>], left: &[usize]) {
    let _ = writeln!(s, "<div class=\"scroll\"><table class=\"{class}\">");
    for (i, row) in rows.iter().enumerate() {
        let tag = if i == 0 { "th" } else { "td" };
        s.push_str("<tr>");
        for (j, cell) in row.iter().enumerate() {
            let align = if j > 0 && left.contains(&j) {
                " class=\"l\""
            } else {
                ""
            };
            let _ = write!(s, "<{tag}{align}>{}</{tag}>", escape(cell));
        }
        s.push_str("</tr>\n");
    }
    s.push_str("</table></div>\n");
}

/// A two-column table of names and values (no header row).
pub(crate) fn meta_table(s: &mut String, rows: &[[String; 2]]) {
    s.push_str("<table class=\"meta\">\n");
    for [name, value] in rows {
        let _ = writeln!(
            s,
            "<tr><th scope=\"row\">{}</th><td>{}</td></tr>",
            escape(name),
            escape(value)
        );
    }
    s.push_str("</table>\n");
}
