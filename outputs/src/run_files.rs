//! The files of a run: its JSON document with provenance, the per-sol CSV, and its GIS layers
//! ([`crate::gis`]) written into an [`OutputSet`]; [`write_atomic`] for a single file.
//!
//! Every file is written atomically (a temporary file in the same folder, then a rename, or a
//! whole output set swapped into place), so a crash or a full disk never leaves half an output
//! behind.

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};

use serde_json::{Value, json};

use crate::gis::{run_layers, scenario_layers, write_layers};
use crate::output_set::{OutputSet, OutputSetError};
use sim::CampaignOutcome;
use sim::run::outcome::LegClearance;
use study::Scenario;

/// Provenance written into every JSON output.
#[must_use]
pub fn provenance(scenario: &Scenario) -> Value {
    json!({
        "scenario": scenario.name,
        "scenario_file": scenario.path.display().to_string(),
        "scenario_sha256": scenario.sha256,
        "inputs_sha256": scenario
            .inputs_sha256
            .iter()
            .map(|(field, _, sha)| (field.to_string(), Value::from(sha.as_str())))
            .collect::<serde_json::Map<String, Value>>(),
        "seed": scenario.seed,
        "solsim_version": env!("CARGO_PKG_VERSION"),
    })
}

/// The JSON document of one run.
#[must_use]
pub fn run_json(scenario: &Scenario, outcome: &CampaignOutcome, legs: &[LegClearance]) -> Value {
    json!({
        "provenance": provenance(scenario),
        "strategy": outcome.strategy,
        "seed": outcome.seed,
        "sols": outcome.sols,
        "totals": outcome.totals,
        "route_legs": legs,
    })
}

/// Write `bytes` to `path` atomically.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir)?;
    let file_name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    let tmp = dir.join(format!(".{file_name}.tmp-{}", std::process::id()));
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Per-sol CSV of one run.
#[must_use]
pub fn sols_csv(outcome: &CampaignOutcome) -> String {
    let mut s = String::from(
        "strategy,sol,plan_uplink_sol,drove,skip_reason,distance_m,d_vo_m,d_novo_m,drive_time_s,start_uncertainty_m,end_uncertainty_m,fault,fault_after_m,fault_uncertainty_m,passage_clearance_m,ground_localized,onboard_localization,onboard_localizer,onboard_start_lmst,onboard_duration_s,onboard_error_m,onboard_semi_major_m,onboard_semi_minor_m,onboard_mmgis_angle_deg,end_x_m,end_y_m,true_x_m,true_y_m,truth_error_m,truth_inside_disc,reached_goal\n",
    );
    for r in &outcome.sols {
        let onboard = match &r.onboard_localization {
            None => "",
            Some(l) if l.applied => "applied",
            Some(_) => "rejected",
        };
        let ob = r.onboard_localization.as_ref();
        let ellipse = ob.and_then(|l| l.ellipse);
        let ellipse_cell = |f: fn(&sim::run::outcome::PositionEllipse) -> f64| {
            ellipse.map_or(String::new(), |e| format!("{:.3}", f(&e)))
        };
        let onboard_detail = format!(
            "{},{},{},{},{},{},{}",
            ob.map_or("", |l| l.localizer),
            ob.and_then(|l| l.start_lmst.as_deref()).unwrap_or(""),
            ob.and_then(|l| l.duration_s)
                .map_or(String::new(), |d| format!("{d:.0}")),
            ob.and_then(|l| l.error_m)
                .map_or(String::new(), |e| format!("{e:.3}")),
            ellipse_cell(|e| e.semi_major_m),
            ellipse_cell(|e| e.semi_minor_m),
            ellipse_cell(|e| e.mmgis_angle_deg),
        );
        let _ = writeln!(
            s,
            "{},{},{},{},{},{:.3},{:.3},{:.3},{:.0},{:.3},{:.3},{},{},{},{},{},{},{},{:.3},{:.3},{:.3},{:.3},{:.3},{},{}",
            outcome.strategy,
            r.sol,
            r.plan_uplink_sol,
            r.drove,
            r.skip_reason
                .map(|why| csv_quote(&why.to_string()))
                .unwrap_or_default(),
            r.distance_m,
            r.d_vo_m,
            r.d_novo_m,
            r.drive_time_s,
            r.start_uncertainty_m,
            r.end_uncertainty_m,
            r.fault.as_ref().map_or("", |f| f.kind.name()),
            r.fault
                .as_ref()
                .map_or(String::new(), |f| format!("{:.3}", f.after_m)),
            r.fault
                .as_ref()
                .map_or(String::new(), |f| format!("{:.3}", f.uncertainty_m)),
            r.passage_clearance_m
                .map_or(String::new(), |c| format!("{c:.3}")),
            r.ground_localization.is_some(),
            onboard,
            onboard_detail,
            r.end_position_m[0],
            r.end_position_m[1],
            r.end_true_position_m[0],
            r.end_true_position_m[1],
            r.truth_error_m,
            r.truth_inside_disc.map_or(String::new(), |b| b.to_string()),
            r.reached_goal,
        );
    }
    s
}

fn csv_quote(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// Write the JSON and CSV of one run and its GIS layers ([`crate::gis::run_layers`],
/// each in longitude/latitude and in the map's CRS) into `set`; returns the paths written.
pub fn write_run_files(
    set: &OutputSet,
    scenario: &Scenario,
    outcome: &CampaignOutcome,
    legs: &[LegClearance],
) -> Result<Vec<PathBuf>, OutputSetError> {
    let stem = format!("{}.{}", scenario.name, outcome.strategy);
    let mut written = [
        (
            format!("{stem}.json"),
            pretty(&run_json(scenario, outcome, legs)),
        ),
        (format!("{stem}.sols.csv"), sols_csv(outcome)),
    ]
    .iter()
    .map(|(name, text)| set.write(name, text.as_bytes()))
    .collect::<Result<Vec<_>, _>>()?;
    written.extend(write_layers(set, scenario, &run_layers(scenario, outcome))?);
    Ok(written)
}

/// Write the GIS layers every strategy shares — the route and the zones as given
/// ([`crate::gis::scenario_layers`]) — into `set`; returns the paths written.
pub fn write_scenario_files(
    set: &OutputSet,
    scenario: &Scenario,
) -> Result<Vec<PathBuf>, OutputSetError> {
    write_layers(set, scenario, &scenario_layers(scenario))
}

/// Pretty JSON with a trailing newline.
#[must_use]
pub fn pretty(v: &Value) -> String {
    let mut s =
        serde_json::to_string_pretty(v).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"));
    s.push('\n');
    s
}
