//! The reports in a real browser (issue 13, item 2): report.html of `compare --report` on
//! scenarios/crater-floor-passage.toml and of `solsim report` on a sweep directory, loaded in headless
//! Chromium (Debian's package, which `.ci/run` installs; without it this test fails under CI
//! and says SKIPPED loudly elsewhere): the page loads with no console error, no failed load
//! and no uncaught exception; the screenshot is not blank and shows the figures' strategy
//! colours (so the inline SVG was drawn, not only present); every figure is in the DOM.

use crate::common;

use std::path::Path;

use common::browser::check_page;
use common::run_ok;

/// Pixels of exactly `rgb` in the screenshot.
fn pixels_of(png: &Path, rgb: [u8; 3]) -> usize {
    let img = image::open(png).expect("the screenshot decodes").to_rgba8();
    img.pixels().filter(|p| p.0[..3] == rgb).count()
}

/// Loads `html`, checks what every report must show in a browser, returns the screenshot
/// path's check for further looks.
fn check_report(html: &Path, figures: usize) -> Option<common::browser::PageCheck> {
    let page = check_page(html, (1280, 6000))?;
    assert!(
        page.console_errors.is_empty(),
        "console errors: {:#?}",
        page.console_errors
    );
    assert!(
        page.non_background_fraction > 0.03,
        "the screenshot is (nearly) blank: {:.4} of pixels drawn",
        page.non_background_fraction
    );
    assert!(
        page.distinct_colours > 20,
        "{} colours",
        page.distinct_colours
    );
    assert_eq!(
        page.dom.matches("<figure").count(),
        figures,
        "figures in the DOM"
    );
    assert_eq!(
        page.dom.matches("<svg").count(),
        figures,
        "inline SVG in the DOM"
    );
    Some(page)
}

#[test]
fn the_sol383_386_report_renders_in_chromium() {
    let dir = tempfile::tempdir().expect("tempdir");
    let run = dir.path().join("run");
    run_ok(
        &[
            "compare",
            "scenarios/crater-floor-passage.toml",
            "--report",
            "--out",
        ],
        &[&run],
    );
    let Some(page) = check_report(&run.join("report.html"), 18) else {
        return;
    };
    // The first figures (uncertainty per sol, metres per sol) are on screen: the strategies'
    // line and bar colours are drawn (ground blue, onboard green, extension orange).
    for (name, rgb) in [
        ("ground", [31, 119, 180]),
        ("onboard", [44, 160, 44]),
        ("extension", [255, 127, 14]),
    ] {
        let n = pixels_of(&page.screenshot_png, rgb);
        assert!(n > 200, "{name}'s colour drawn on {n} pixels only");
    }
    // The compare table and the verdict are in the page as text.
    assert!(page.dom.contains("Against ground-in-the-loop"));
    assert!(page.dom.contains("<td>extension+onboard</td>"));
}

#[test]
fn a_sweep_report_renders_in_chromium() {
    let dir = tempfile::tempdir().expect("tempdir");
    let sweep = dir.path().join("sweep");
    common::sweep_rapid_traverse(30, &sweep);
    let out = dir.path().join("report");
    run_ok(&["report"], &[&sweep, Path::new("--out"), &out]);
    let Some(page) = check_report(&out.join("report.html"), 2) else {
        return;
    };
    // The CDF and the rates figure are drawn in the strategies' colours (ground blue,
    // onboard green).
    let drawn: usize = [[31, 119, 180], [44, 160, 44]]
        .iter()
        .map(|&rgb| pixels_of(&page.screenshot_png, rgb))
        .sum();
    assert!(drawn > 200, "strategy colours on {drawn} pixels only");
    assert!(page.dom.contains("Rates (95 % Wilson intervals"));
}
