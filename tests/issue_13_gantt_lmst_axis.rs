//! Regression (issue 13 review): the Gantt chart divided seconds by 3600, so bars sat 18-25
//! min late on the LMST axis (a Mars hour is 3698.96 s); and maps were not at equal scale
//! (1.01-1.12 px/m north against east) because the plot size was assumed, not measured.

use crate::common;

use common::run_ok;

fn run_doc(dir: &std::path::Path, name: &str) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join(name)).expect("run JSON")).expect("JSON")
}

fn compare_svg(scenario: &str, out: &std::path::Path) {
    run_ok(&["compare", scenario, "--out"], &[out]);
}

/// `(x, y, text)` of every `<text>` of a plotters SVG.
fn texts(svg: &str) -> Vec<(f64, f64, String)> {
    svg.split("<text ")
        .skip(1)
        .filter_map(|t| {
            let attr = |name: &str| -> Option<f64> {
                let at = t
                    .find(&format!(" {name}=\""))
                    .or_else(|| t.starts_with(&format!("{name}=\"")).then_some(0))?;
                let rest = &t[at..];
                let start = rest.find('"')? + 1;
                let end = start + rest[start..].find('"')?;
                rest[start..end].parse().ok()
            };
            let body = t
                .split_once('>')?
                .1
                .split("</text>")
                .next()?
                .trim()
                .to_string();
            Some((attr("x")?, attr("y")?, body))
        })
        .collect()
}

/// Pixels per unit along an axis from its tick labels (numbers), and the labels' shared
/// coordinate: x-axis labels share y, y-axis labels share x.
fn axis_scale(labels: &[(f64, f64)]) -> f64 {
    let (a, b) = (
        labels.first().expect("ticks"),
        labels.last().expect("ticks"),
    );
    ((b.1 - a.1) / (b.0 - a.0)).abs()
}

#[test]
fn maps_have_equal_scale_and_gantt_bars_sit_at_their_lmst() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("a");
    compare_svg("scenarios/crater-floor-passage.toml", &out);
    let read = |n: &str| std::fs::read_to_string(out.join(n)).expect("figure");
    for name in [
        "crater-floor-passage.ground.map.svg",
        "crater-floor-passage.replay.fault-sol385.map.svg",
    ] {
        let t = texts(&read(name));
        let numeric: Vec<(f64, f64, f64)> = t
            .iter()
            .filter_map(|(x, y, s)| s.parse::<f64>().ok().map(|v| (*x, *y, v)))
            .collect();
        // x-axis ticks: the numbers on the lowest row; y-axis ticks: on the leftmost column.
        let bottom = numeric.iter().map(|n| n.1).fold(f64::MIN, f64::max);
        let left = numeric.iter().map(|n| n.0).fold(f64::MAX, f64::min);
        let xs: Vec<(f64, f64)> = numeric
            .iter()
            .filter(|n| (n.1 - bottom).abs() < 0.5)
            .map(|n| (n.2, n.0))
            .collect();
        let ys: Vec<(f64, f64)> = numeric
            .iter()
            .filter(|n| (n.0 - left).abs() < 0.5)
            .map(|n| (n.2, n.1))
            .collect();
        assert!(xs.len() >= 3 && ys.len() >= 3, "{name}: {xs:?} {ys:?}");
        let (sx, sy) = (axis_scale(&xs), axis_scale(&ys));
        assert!(
            (sx / sy - 1.0).abs() < 0.01,
            "{name}: {sx:.4} px/m east against {sy:.4} px/m north"
        );
    }
    // The onboard plans: sol 383's heating starts at 11:01 LMST (its JSON); on the chart its
    // bar's left edge lies at 11:01 between the 11:00 and 12:00 ticks (a Mars hour is
    // 3698.96 s, not 3600).
    let onboard = run_doc(&out, "crater-floor-passage.onboard.json");
    let heating = onboard["sols"][0]["activity_plan"]["timeline"]
        .as_array()
        .expect("timeline")
        .iter()
        .find(|t| t["activity"] == "heating")
        .expect("heating")
        .clone();
    let start = heating["start_lmst"].as_str().expect("LMST");
    let (h, m) = start.split_once(':').expect("HH:MM");
    let hours: f64 = h.parse::<f64>().expect("h") + m.parse::<f64>().expect("m") / 60.0;
    let svg = read("crater-floor-passage.onboard.plans.svg");
    let t = texts(&svg);
    let tick = |label: &str| {
        t.iter()
            .find(|(_, _, s)| s == label)
            .map(|(x, _, _)| *x)
            .unwrap_or_else(|| panic!("tick {label}"))
    };
    let (x11, x12) = (tick("11:00"), tick("12:00"));
    let bar_x: f64 = svg
        .split("<rect ")
        .find(|r| r.contains("fill=\"#D62728\""))
        .and_then(|r| r.split("x=\"").nth(1))
        .and_then(|r| r.split('"').next())
        .and_then(|x| x.parse().ok())
        .expect("the first heating bar");
    let drawn = 11.0 + (bar_x - x11) / (x12 - x11);
    assert!(
        (drawn - hours).abs() < 1.5 / 60.0,
        "heating drawn at {drawn:.3} h, starts at {start} ({hours:.3} h)"
    );
}
