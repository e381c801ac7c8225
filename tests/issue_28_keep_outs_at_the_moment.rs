//! Issue 28, item 5: ground's map of the rapid traverse grew every keep-out by the run's
//! largest r (32.99 m), at which the sol 385 passage is closed — while the drawn path runs
//! through it, since ground drove it at about 25 m. The map now grows each keep-out by the r the
//! rover had where its path came closest to it, and zooms on each passage: in the SVG no
//! vertex of the driven path lies inside a grown keep-out, on the overview or on the panels,
//! and the sol 385 panel shows it threading a passage grown by more than 20 m. The same
//! measure on the map grown at the run's largest r (`--map-r-m`) finds the path inside: what the
//! old map drew.

use crate::common;

use common::run_ok;

/// The fill of a grown keep-out (orange at 45 %).
const GROWN: &str = "fill=\"#FFA03C\"";
const GROUND: &str = "#1F77B4";

fn points(text: &str) -> Vec<(f64, f64)> {
    text.split_whitespace()
        .filter_map(|p| {
            let (x, y) = p.split_once(',')?;
            Some((x.parse().ok()?, y.parse().ok()?))
        })
        .collect()
}

/// The `points` of every `tag` element of `svg` whose attributes contain `has`.
fn shapes(svg: &str, tag: &str, has: &str) -> Vec<Vec<(f64, f64)>> {
    svg.split(&format!("<{tag} "))
        .skip(1)
        .filter_map(|e| e.split("/>").next())
        .filter(|e| e.contains(has))
        .filter_map(|e| e.split("points=\"").nth(1)?.split('"').next())
        .map(points)
        .collect()
}

fn inside(p: (f64, f64), poly: &[(f64, f64)]) -> bool {
    let mut c = false;
    for (i, a) in poly.iter().enumerate() {
        let b = poly[(i + 1) % poly.len()];
        if (a.1 > p.1) != (b.1 > p.1) && p.0 < (b.0 - a.0) * (p.1 - a.1) / (b.1 - a.1) + a.0 {
            c = !c;
        }
    }
    c
}

fn to_edge(p: (f64, f64), poly: &[(f64, f64)]) -> f64 {
    (0..poly.len())
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            let (dx, dy) = (b.0 - a.0, b.1 - a.1);
            let l = dx * dx + dy * dy;
            let t = if l == 0.0 {
                0.0
            } else {
                (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / l).clamp(0.0, 1.0)
            };
            (p.0 - a.0 - t * dx).hypot(p.1 - a.1 - t * dy)
        })
        .fold(f64::INFINITY, f64::min)
}

/// How deep (pixels) the driven path's vertices go into the grown keep-outs of a map, and how
/// many grown keep-outs and path vertices there are. The path is ground's 2 px polylines that
/// are not closed rings (the discs are).
fn deepest(svg: &str) -> (f64, usize, usize) {
    let grown = shapes(svg, "polygon", GROWN);
    let path: Vec<(f64, f64)> = shapes(svg, "polyline", &format!("stroke=\"{GROUND}\""))
        .into_iter()
        .filter(|l| l.len() >= 2 && l.first() != l.last())
        .flatten()
        .collect();
    let depth = path
        .iter()
        .flat_map(|p| {
            grown
                .iter()
                .filter(|g| inside(*p, g))
                .map(|g| to_edge(*p, g))
        })
        .fold(0.0, f64::max);
    (depth, grown.len(), path.len())
}

#[test]
fn ground_map_shows_the_passages_open_where_it_drove_through() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("a");
    run_ok(
        &["compare", "scenarios/rapid-traverse-379-409.toml", "--out"],
        &[&out],
    );
    let read = |n: &str| std::fs::read_to_string(out.join(n)).expect("figure");
    for name in [
        "rapid-traverse-379-409.ground.map.svg",
        "rapid-traverse-379-409.ground.passages.svg",
    ] {
        let (depth, grown, vertices) = deepest(&read(name));
        assert!(
            grown >= 14 && vertices > 500,
            "{name}: {grown} keep-outs, {vertices} vertices"
        );
        assert!(
            depth < 0.5,
            "{name}: the path is {depth:.1} px inside a grown keep-out"
        );
    }
    // The sol 385 passage (paper 000 Fig. 4): ground drove it at r of 20 m and more, so its
    // panel's keep-outs are grown by that and the path still goes between them.
    let passages = read("rapid-traverse-379-409.ground.passages.svg");
    let caption = passages
        .split('\n')
        .find(|l| l.contains("sol 385 passage, passed sol 385 at r = "))
        .expect("the sol 385 panel");
    let r: f64 = caption
        .split(" at r = ")
        .nth(1)
        .and_then(|t| t.split(['-', ' ']).next())
        .and_then(|t| t.parse().ok())
        .expect("its r");
    assert!(r > 20.0, "{caption}");
    // The run's largest r, from its JSON: grown by that (the old map), the path lies inside.
    let doc: serde_json::Value =
        serde_json::from_str(&read("rapid-traverse-379-409.ground.json")).expect("JSON");
    let max_r = doc["totals"]["max_uncertainty_m"].as_f64().expect("max r");
    assert!(max_r > r + 5.0, "{max_r} against {r}");
    let old = dir.path().join("b");
    run_ok(
        &[
            "compare",
            "scenarios/rapid-traverse-379-409.toml",
            "--map-r-m",
            &format!("{max_r:.2}"),
            "--out",
        ],
        &[&old],
    );
    let svg =
        std::fs::read_to_string(old.join("rapid-traverse-379-409.ground.map.svg")).expect("figure");
    let (depth, _, _) = deepest(&svg);
    assert!(
        depth > 2.0,
        "at r = {max_r} the path is only {depth:.1} px inside"
    );
}
