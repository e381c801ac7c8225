//! Figures (issue 13, item 1, first part): `solsim compare` writes
//! `<scenario>.uncertainty.svg`, the uncertainty radius against sol per strategy (paper 000
//! Fig. 2 and 5), beside its other files. The SVG is well-formed XML (Python's
//! `xml.etree.ElementTree` parses it), names every strategy, draws one line each and marks
//! faults, and is the same byte for byte on a second run.

mod common;

use common::{root, solsim, stderr};

fn compare_svg(scenario: &str, out: &std::path::Path) -> String {
    let o = solsim()
        .current_dir(root())
        .args(["compare", scenario, "--out"])
        .arg(out)
        .output()
        .expect("runs");
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let name = std::path::Path::new(scenario)
        .file_stem()
        .and_then(|s| s.to_str())
        .expect("name");
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains(&format!("{name}.uncertainty.svg")),
        "{stdout}"
    );
    std::fs::read_to_string(out.join(format!("{name}.uncertainty.svg"))).expect("the figure")
}

#[test]
fn compare_writes_the_uncertainty_figure() {
    let dir = tempfile::tempdir().expect("tempdir");
    let svg = compare_svg("scenarios/sol383-386.toml", &dir.path().join("a"));
    // Well-formed: parsed by an independent XML parser.
    let parsed = std::process::Command::new("python3")
        .args([
            "-c",
            "import sys, xml.etree.ElementTree as E; r = E.parse(sys.argv[1]).getroot(); \
             print(r.tag, len(list(r.iter())))",
        ])
        .arg(dir.path().join("a/sol383-386.uncertainty.svg"))
        .output()
        .expect("python3 runs");
    assert!(
        parsed.status.success(),
        "not well-formed XML: {}",
        stderr(&parsed)
    );
    assert!(
        String::from_utf8_lossy(&parsed.stdout).starts_with("{http://www.w3.org/2000/svg}svg"),
        "{}",
        String::from_utf8_lossy(&parsed.stdout)
    );
    // plotters writes each text on its own line inside <text>.
    let text = |t: &str| svg.contains(&format!("\n{t}\n</text>"));
    for strategy in [
        "replay",
        "ground",
        "onboard",
        "extension",
        "extension+onboard",
    ] {
        assert!(text(strategy), "{strategy} not in the legend");
    }
    assert!(text("uncertainty radius r (m)") && text("sol"), "axes");
    // One tick per sol, each once.
    for sol in 383..=388 {
        assert_eq!(
            svg.matches(&format!("\n{sol}\n</text>")).count(),
            1,
            "sol {sol}"
        );
    }
    // One line per strategy, plus the legend's five swatches.
    assert!(svg.matches("<polyline").count() >= 5, "{svg}");
    // The replay faults NO_PATH on sol 385: a red cross (two red strokes).
    assert!(svg.contains("#FF0000"), "the fault marker");
    // Deterministic.
    let again = compare_svg("scenarios/sol383-386.toml", &dir.path().join("b"));
    assert_eq!(svg, again);
}
