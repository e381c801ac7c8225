//! The headless-Chromium helper (tests/common/browser.rs) on small pages written into a temporary
//! directory: it passes a clean page with an inline SVG and reports what a report test must catch
//! (console errors, uncaught exceptions, failed local and network loads, a blank page).

use crate::common;

use common::browser::{PageCheck, check_page};

const WINDOW: (u32, u32) = (640, 400);

/// `body` as `page.html` in a new temporary directory, checked in Chromium (`None`: skipped).
fn check(body: &str) -> Option<(PageCheck, tempfile::TempDir)> {
    let dir = tempfile::tempdir().expect("tempdir");
    let html = dir.path().join("page.html");
    let page = format!(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>t</title></head>\n\
         <body style=\"margin:0;background:#fff\">\n{body}\n</body></html>\n"
    );
    std::fs::write(&html, page).expect("write page.html");
    let check = check_page(&html, WINDOW)?;
    Some((check, dir))
}

/// The one error of `check`, which must contain every string of `needles`.
fn assert_one_error(check: &PageCheck, needles: &[&str]) {
    assert_eq!(
        check.console_errors.len(),
        1,
        "one error expected: {:#?}",
        check.console_errors
    );
    for n in needles {
        assert!(
            check.console_errors[0].contains(n),
            "error lacks {n:?}: {:#?}",
            check.console_errors
        );
    }
}

#[test]
fn clean_page_with_inline_svg() {
    let Some((check, _dir)) = check(
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="300" height="200" id="fig">
  <rect x="10" y="10" width="200" height="120" fill="#1f77b4"/>
  <text x="20" y="170" font-size="24" fill="#d62728">Sol 717</text>
</svg>
<script>console.log("informational messages are not errors"); console.warn("nor warnings");</script>"##,
    ) else {
        return;
    };
    assert!(
        check.console_errors.is_empty(),
        "{:#?}",
        check.console_errors
    );
    assert_eq!(check.screenshot_size, WINDOW);
    assert!(check.screenshot_png.is_file());
    // White, the rectangle, and the antialiased text.
    assert!(check.distinct_colours >= 3, "{}", check.distinct_colours);
    // The rectangle alone is 200×120 of 640×400 pixels (9.4 %).
    assert!(
        check.non_background_fraction > 0.09 && check.non_background_fraction < 0.2,
        "{}",
        check.non_background_fraction
    );
    assert_eq!(check.dom.matches("<svg").count(), 1, "{}", check.dom);
    assert!(check.dom.contains("<rect"), "{}", check.dom);
    assert!(check.dom.contains("Sol 717</text>"), "{}", check.dom);
    // The rectangle's colour is in the screenshot.
    let image = image::open(&check.screenshot_png)
        .expect("screenshot")
        .to_rgba8();
    let rect = image.get_pixel(100, 60).0;
    assert_eq!(rect, [0x1f, 0x77, 0xb4, 0xff]);
}

#[test]
fn console_error_is_reported() {
    let Some((check, _dir)) = check(r#"<p>x</p><script>console.error("boom")</script>"#) else {
        return;
    };
    assert_one_error(&check, &["console.error: boom", "page.html:4"]);
}

#[test]
fn failed_console_assert_is_reported() {
    let Some((check, _dir)) = check(
        r#"<script>console.assert(1 + 1 === 2, "fine"); console.assert(false, "axes missing")</script>"#,
    ) else {
        return;
    };
    assert_one_error(&check, &["console.assert: axes missing"]);
}

#[test]
fn uncaught_exception_is_reported() {
    let Some((check, _dir)) = check(r#"<script>throw new Error("x")</script>"#) else {
        return;
    };
    assert_one_error(&check, &["Uncaught Error: x", "page.html:4"]);
}

#[test]
fn exception_in_a_timer_is_reported_without_waiting() {
    // Virtual time: the 3-s timer runs, but the check does not take 3 s longer.
    let Some((check, _dir)) = check(
        r#"<p id="p">before</p>
<script>setTimeout(() => { document.getElementById("p").textContent = "after"; null.x; }, 3000)</script>"#,
    ) else {
        return;
    };
    assert_one_error(&check, &["Uncaught TypeError"]);
    assert!(
        check.dom.contains(r#"<p id="p">after</p>"#),
        "{}",
        check.dom
    );
}

#[test]
fn missing_local_image_is_reported() {
    let Some((check, _dir)) = check(r#"<img src="missing.png" alt="figure">"#) else {
        return;
    };
    assert_one_error(
        &check,
        &[
            "network: Failed to load resource: net::ERR_FILE_NOT_FOUND",
            "/missing.png",
        ],
    );
}

#[test]
fn network_resources_fail_to_load() {
    let Some((check, _dir)) = check(
        r#"<link rel="stylesheet" href="https://cdn.example.com/style.css">
<img src="http://example.com/figure.png">"#,
    ) else {
        return;
    };
    assert_eq!(check.console_errors.len(), 2, "{:#?}", check.console_errors);
    for url in [
        "https://cdn.example.com/style.css",
        "http://example.com/figure.png",
    ] {
        assert!(
            check.console_errors.iter().any(|e| e.contains(url)
                && e.contains("Failed to load resource: net::ERR_NAME_NOT_RESOLVED")),
            "{url}: {:#?}",
            check.console_errors
        );
    }
}

#[test]
fn blank_page_is_all_background() {
    let Some((check, _dir)) = check("") else {
        return;
    };
    assert!(
        check.console_errors.is_empty(),
        "{:#?}",
        check.console_errors
    );
    assert_eq!(check.distinct_colours, 1);
    assert_eq!(check.non_background_fraction, 0.0);
    // So the assertion a report test makes about its figures fails here (the panic message is
    // expected in the captured output).
    let not_blank = std::panic::catch_unwind(|| {
        assert!(
            check.non_background_fraction > 0.01,
            "blank page (this failure is expected: it shows the not-blank check can fail)"
        );
    });
    assert!(not_blank.is_err());
}
