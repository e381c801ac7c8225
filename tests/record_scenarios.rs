//! The bundled historic scenarios are what `scenarios/tools/rebuild_from_record.sh` makes of the
//! bundled record (`solsim record import` plus the hand-written claims of `scenarios/claims/`),
//! byte for byte: the scenario files, their zones and their maps. Edit the import or the claims,
//! not the scenarios.

use crate::common::root;

#[test]
fn bundled_historic_scenarios_are_the_record_import() {
    let out = tempfile::tempdir().expect("tempdir");
    let o = std::process::Command::new("bash")
        .arg(root().join("scenarios/tools/rebuild_from_record.sh"))
        .arg(env!("CARGO_BIN_EXE_solsim"))
        .env("REBUILD_OUT", out.path())
        .output()
        .expect("bash runs");
    assert!(
        o.status.success(),
        "rebuild failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    let mut compared = 0;
    for name in ["rapid-traverse-379-409", "sol383-386", "sol717-719"] {
        let mut files = vec![
            format!("scenarios/{name}.toml"),
            format!("scenarios/{name}.zones.geojson"),
        ];
        for f in ["appearance.tif", "dem.tif", "terrain.tif", "recipe.toml"] {
            files.push(format!("maps/assets/{name}/{f}"));
        }
        for f in files {
            let bundled = std::fs::read(root().join(&f)).expect("bundled file");
            let rebuilt = std::fs::read(out.path().join(&f)).expect("rebuilt file");
            assert!(
                bundled == rebuilt,
                "{f}: the bundled file differs from scenarios/tools/rebuild_from_record.sh's output; rerun it"
            );
            compared += 1;
        }
    }
    assert_eq!(compared, 18);
}
