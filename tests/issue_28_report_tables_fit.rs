//! Issue 28, item 5: on the bundled rapid traverse the report's sol-log tables were the CSV
//! dumped as HTML — 31 columns under `distance_m`-style headers, wider than the page, so at
//! 1400 px the right half was cut off — and "Against ground" was a monospace dump. In headless
//! Chromium at 1400 px every table now fits its container and the page (nothing to scroll
//! sideways, nothing cut off), no header is snake_case, and the verdict against ground is a
//! table with a row per strategy.

use crate::common;

use common::browser::check_page;
use common::run_ok;

/// Measures every table once the page has loaded and writes what it found into the page
/// (`<pre id="fit">`); a table wider than its container, a header whose text overflows its
/// cell or a page wider than the window is a `console.error`, which the harness reports.
const MEASURE: &str = r#"<script>
window.addEventListener("load", () => {
  const lines = [];
  document.querySelectorAll("table").forEach((t, i) => {
    const box = t.parentElement.getBoundingClientRect();
    const r = t.getBoundingClientRect();
    lines.push(`table ${i} ${t.className}: ${r.width.toFixed(0)} px in ${box.width.toFixed(0)} px`);
    if (r.right > box.right + 0.5 || t.scrollWidth > t.parentElement.clientWidth) {
      console.error(`table ${i} (${t.className}) is ${r.width.toFixed(0)} px wide in a container of ${box.width.toFixed(0)} px`);
    }
    t.querySelectorAll("th").forEach(th => {
      if (th.scrollWidth > th.clientWidth + 1) {
        console.error(`table ${i} (${t.className}): header "${th.textContent}" overflows its cell`);
      }
    });
  });
  const page = document.documentElement.scrollWidth;
  if (page > window.innerWidth) {
    console.error(`the page is ${page} px wide in a ${window.innerWidth} px window`);
  }
  const pre = document.createElement("pre");
  pre.id = "fit";
  pre.textContent = lines.join("\n");
  document.body.appendChild(pre);
});
</script>
"#;

#[test]
fn rapid_traverse_report_tables_fit_1400_px_with_human_headers() {
    let dir = tempfile::tempdir().expect("tempdir");
    let run = dir.path().join("run");
    run_ok(
        &[
            "compare",
            "scenarios/rapid-traverse-379-409.toml",
            "--report",
            "--out",
        ],
        &[&run],
    );
    let html = std::fs::read_to_string(run.join("report.html")).expect("report.html");

    // Headers a reader knows: no `distance_m`, `end_uncertainty_m`, … in any <th>.
    let headers: Vec<&str> = html
        .split("<th")
        .skip(1)
        .filter_map(|t| {
            t.split_once('>')
                .and_then(|(_, rest)| rest.split("</th>").next())
        })
        .collect();
    assert!(headers.len() > 50, "{} headers", headers.len());
    let snake = |h: &str| {
        let b = h.as_bytes();
        b.windows(3).any(|w| {
            w[1] == b'_'
                && (w[0].is_ascii_lowercase() || w[0].is_ascii_digit())
                && w[2].is_ascii_lowercase()
        })
    };
    let bad: Vec<&&str> = headers.iter().filter(|h| snake(h)).collect();
    assert!(bad.is_empty(), "snake_case headers: {bad:?}");
    for h in [
        "Distance (m)",
        "r at end of drive (m)",
        "Drive sols gained (kind of sol)",
    ] {
        assert!(headers.contains(&h), "{h} in {headers:?}");
    }
    // Against ground is a table, a row per strategy, ground first; no monospace dump.
    let verdict = html
        .split("id=\"verdict\"")
        .nth(1)
        .and_then(|t| t.split("<h2").next())
        .expect("the verdict section");
    assert!(!verdict.contains("<pre"), "{verdict}");
    assert!(verdict.contains("<table class=\"verdict\">"), "{verdict}");
    for s in [
        "ground",
        "replay",
        "onboard",
        "extension",
        "extension+onboard",
    ] {
        assert!(verdict.contains(&format!("<tr><td>{s}</td>")), "{s} row");
    }
    assert!(
        verdict.find("<td>ground</td>") < verdict.find("<td>replay</td>"),
        "ground first"
    );

    // In Chromium at 1400 px: every table fits (the measuring script is added to a copy; the
    // report itself has no script).
    let page = dir.path().join("measured.html");
    let measured = html.replacen("</body>", &format!("{MEASURE}</body>"), 1);
    assert_ne!(measured, html, "the script went in");
    std::fs::write(&page, measured).expect("write");
    let Some(check) = check_page(&page, (1400, 1000)) else {
        return;
    };
    assert!(
        check.console_errors.is_empty(),
        "{:#?}",
        check.console_errors
    );
    // The script ran and measured them all: the compare, verdict and five sol-log tables.
    let fit = check
        .dom
        .split("<pre id=\"fit\">")
        .nth(1)
        .and_then(|t| t.split("</pre>").next())
        .expect("the measurements");
    assert!(fit.contains(" verdict: "), "{fit}");
    assert_eq!(fit.matches(" sols: ").count(), 5, "{fit}");
}
