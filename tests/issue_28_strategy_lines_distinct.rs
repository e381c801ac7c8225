//! Issue 28, item 5: in the uncertainty figure of the rapid traverse five strategies' lines lay
//! on top of each other (same colour weight, all solid), so onboard's was hidden where the
//! others drew over it. Each strategy's line now has its own dash pattern and a marker at the
//! end of each drive, and the lines are shifted 2 px apart, so where the data coincide the
//! lines do not.

use crate::common;

use common::run_ok;

/// The attribute `name` of one SVG element's attribute text.
fn attr<'a>(element: &'a str, name: &str) -> Option<&'a str> {
    let at = element.find(&format!(" {name}=\""))? + name.len() + 3;
    element[at..].split('"').next()
}

/// (x, y) pixels of a `points` attribute.
fn points(text: &str) -> Vec<(f64, f64)> {
    text.split_whitespace()
        .filter_map(|p| {
            let (x, y) = p.split_once(',')?;
            Some((x.parse().ok()?, y.parse().ok()?))
        })
        .collect()
}

#[test]
fn strategies_lines_differ_in_dash_marker_and_place() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("a");
    run_ok(
        &["compare", "scenarios/rapid-traverse-379-409.toml", "--out"],
        &[&out],
    );
    let svg = std::fs::read_to_string(out.join("rapid-traverse-379-409.uncertainty.svg"))
        .expect("the figure");
    let strategies = [
        ("replay", "#8C564B"),
        ("ground", "#1F77B4"),
        ("onboard", "#2CA02C"),
        ("extension", "#FF7F0E"),
        ("extension+onboard", "#9467BD"),
    ];
    let mut dashes: Vec<String> = Vec::new();
    let mut starts: Vec<(f64, f64)> = Vec::new();
    for (name, colour) in strategies {
        // The strategy's line in the plot: its polyline with more than the legend swatch's two
        // points; the swatch in the legend has the same dashes.
        let lines: Vec<&str> = svg
            .split("<polyline")
            .skip(1)
            .map(|e| e.split("/>").next().expect("element"))
            .filter(|e| attr(e, "stroke") == Some(colour))
            .collect();
        let plot: Vec<&&str> = lines
            .iter()
            .filter(|e| points(attr(e, "points").unwrap_or("")).len() > 2)
            .collect();
        assert_eq!(plot.len(), 1, "{name}: one line in the plot");
        let dash = attr(plot[0], "stroke-dasharray")
            .unwrap_or("solid")
            .to_string();
        assert!(
            lines
                .iter()
                .all(|e| attr(e, "stroke-dasharray").unwrap_or("solid") == dash),
            "{name}: the legend shows the line's dashes"
        );
        dashes.push(dash);
        starts.push(points(attr(plot[0], "points").expect("points"))[0]);
        // A marker at the end of each drive (and one in the legend), in the strategy's colour.
        let doc: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(out.join(format!("rapid-traverse-379-409.{name}.json")))
                .expect("run JSON"),
        )
        .expect("JSON");
        let drives = doc["sols"]
            .as_array()
            .expect("sols")
            .iter()
            .filter(|s| s["drove"] == true)
            .count();
        let markers = ["<circle", "<polygon"]
            .iter()
            .flat_map(|tag| svg.split(tag).skip(1))
            .filter(|e| {
                e.split("/>")
                    .next()
                    .is_some_and(|e| attr(e, "fill") == Some(colour))
            })
            .count();
        assert_eq!(
            markers,
            drives + 1,
            "{name}: a marker per drive and in the legend"
        );
    }
    let mut distinct = dashes.clone();
    distinct.sort();
    distinct.dedup();
    assert_eq!(distinct.len(), 5, "five dash patterns: {dashes:?}");
    // Every strategy starts sol 379 at r = 0: the same datum, yet the lines start at least
    // 2 px apart from each other.
    for (i, a) in starts.iter().enumerate() {
        for b in &starts[i + 1..] {
            assert!(
                (a.0 - b.0).hypot(a.1 - b.1) >= 2.0,
                "lines start together: {starts:?}"
            );
        }
    }
}
