//! Output files and tables: JSON, per-sol CSV, GeoJSON for MMGIS/QGIS (the layers are
//! [`crate::report_gis`]), and the terminal tables.
//!
//! Every file is written atomically (a temporary file in the same folder, then a rename), so a
//! crash or a full disk never leaves half an output behind.

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};

use serde_json::{Value, json};

use crate::output_set::{OutputSet, OutputSetError};
use sim::CampaignOutcome;
use sim::outcome::LegClearance;
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
        "seed": scenario.campaign.seed,
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
        let ellipse_cell = |f: fn(&sim::outcome::PositionEllipse) -> f64| {
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

/// Write the JSON and CSV of one run and its GIS layers ([`crate::report_gis::run_layers`],
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
    written.extend(crate::report_gis::write_layers(
        set,
        scenario,
        &crate::report_gis::run_layers(scenario, outcome),
    )?);
    Ok(written)
}

/// Write the GIS layers every strategy shares — the route and the zones as given
/// ([`crate::report_gis::scenario_layers`]) — into `set`; returns the paths written.
pub fn write_scenario_files(
    set: &OutputSet,
    scenario: &Scenario,
) -> Result<Vec<PathBuf>, OutputSetError> {
    crate::report_gis::write_layers(set, scenario, &crate::report_gis::scenario_layers(scenario))
}

/// Pretty JSON with a trailing newline.
#[must_use]
pub fn pretty(v: &Value) -> String {
    let mut s =
        serde_json::to_string_pretty(v).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"));
    s.push('\n');
    s
}

/// The per-sol table of one run.
#[must_use]
pub fn sol_table(outcome: &CampaignOutcome) -> String {
    let mut s = format!("strategy: {}\n", outcome.strategy);
    let faults: Vec<String> = outcome
        .sols
        .iter()
        .map(|r| {
            r.fault.as_ref().map_or(String::new(), |f| {
                format!(
                    "{} after {:.1} m at r={:.2} m",
                    f.kind.name(),
                    f.after_m,
                    f.uncertainty_m
                )
            })
        })
        .collect();
    // Wide enough for every fault, so the note column starts in one place.
    let fault_w = faults
        .iter()
        .map(|f| f.chars().count())
        .max()
        .unwrap_or(0)
        .max(28);
    let _ = writeln!(
        s,
        "{:>5}  {:>10}  {:>11}  {:>11}  {:>11}  {:>12}  {:<fault_w$}  note",
        "sol", "distance_m", "start_r_m", "end_r_m", "d_novo_m", "passage_m", "fault"
    );
    for (r, fault) in outcome.sols.iter().zip(faults) {
        // In the order things happened: the ground's fix with the uplink, why the sol did not
        // drive or why its drive ended, then the onboard localization after it.
        let mut note: Vec<String> = Vec::new();
        if r.ground_localization.is_some() {
            note.push("ground-localized".into());
        }
        if let Some(why) = r.skip_reason {
            note.push(format!("skipped: {why}"));
        }
        if let Some(end) = r.drive_end {
            note.push(end.to_string());
        }
        if let Some(l) = &r.onboard_localization {
            let when = match (&l.start_lmst, l.duration_s) {
                (Some(start), Some(d)) => format!(" {start} +{:.0} min", d / 60.0),
                _ => String::new(),
            };
            let ellipse = l.ellipse.map_or(String::new(), |e| {
                format!(
                    ", 1σ {:.2}×{:.2} m az {:.0}°",
                    e.semi_major_m, e.semi_minor_m, e.azimuth_deg
                )
            });
            note.push(if l.applied {
                format!(
                    "onboard loc ({}{when}{ellipse}) → r={:.2} m",
                    l.localizer, l.uncertainty_after_m
                )
            } else {
                format!(
                    "onboard loc ({}{when}) lost: {}",
                    l.localizer,
                    l.reason
                        .as_ref()
                        .map(ToString::to_string)
                        .unwrap_or_default()
                )
            });
        }
        let note = note.join("; ");
        let _ = writeln!(
            s,
            "{:>5}  {:>10.2}  {:>11.2}  {:>11.2}  {:>11.2}  {:>12}  {:<fault_w$}  {}",
            r.sol,
            r.distance_m,
            r.start_uncertainty_m,
            r.end_uncertainty_m,
            r.d_novo_m,
            r.passage_clearance_m
                .map_or("-".into(), |c| format!("{c:.2}")),
            fault,
            note
        );
    }
    let t = &outcome.totals;
    let _ = writeln!(
        s,
        "totals: {:.1} m in {} drive sols of {}; sols to goal {}; {} NO_PATH / {} faults; max r {:.2} m; localizations: {} ground, {} onboard applied, {} rejected; truth outside disc on {} sols",
        t.distance_m,
        t.drive_sols,
        t.sols,
        t.sols_to_goal
            .map_or("not reached".into(), |n| n.to_string()),
        t.no_path_faults,
        t.faults,
        t.max_uncertainty_m,
        t.ground_localizations,
        t.onboard_localizations_applied,
        t.onboard_localizations_rejected,
        t.truth_outside_disc
    );
    if !t.science.is_empty() {
        let tally: Vec<String> = t
            .science
            .iter()
            .map(|(c, n)| format!("{c} {} done, {} failed", n.done, n.failed))
            .collect();
        let _ = writeln!(s, "science: {}", tally.join("; "));
    }
    s
}

/// The side-by-side table of `solsim compare`.
#[must_use]
pub fn compare_table(outcomes: &[CampaignOutcome]) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<18}  {:>11}  {:>10}  {:>10}  {:>11}  {:>7}  {:>7}  {:>9}  {:>16}  {:>12}",
        "strategy",
        "sols_to_goal",
        "drive_sols",
        "distance_m",
        "m_per_drive",
        "NO_PATH",
        "faults",
        "max_r_m",
        "onboard_loc a/r",
        "ground_loc"
    );
    for o in outcomes {
        let t = &o.totals;
        let per = if t.drive_sols > 0 {
            t.distance_m / f64::from(t.drive_sols)
        } else {
            0.0
        };
        let _ = writeln!(
            s,
            "{:<18}  {:>11}  {:>10}  {:>10.1}  {:>11.1}  {:>7}  {:>7}  {:>9.2}  {:>16}  {:>12}",
            o.strategy,
            t.sols_to_goal.map_or("-".into(), |n| n.to_string()),
            t.drive_sols,
            t.distance_m,
            per,
            t.no_path_faults,
            t.faults,
            t.max_uncertainty_m,
            format!(
                "{}/{}",
                t.onboard_localizations_applied, t.onboard_localizations_rejected
            ),
            t.ground_localizations
        );
    }
    science_table(outcomes, &mut s);
    s
}

/// Science campaigns side by side (`done/failed` per campaign), if the scenario has any.
fn science_table(outcomes: &[CampaignOutcome], s: &mut String) {
    let Some(first) = outcomes.iter().find(|o| !o.totals.science.is_empty()) else {
        return;
    };
    let campaigns: Vec<&String> = first.totals.science.keys().collect();
    let _ = write!(
        s,
        "\nscience campaigns, members done/failed:\n{:<18}",
        "strategy"
    );
    for c in &campaigns {
        let _ = write!(s, "  {c:>12}");
    }
    let _ = writeln!(s, "  {:>16}", "plan_replans");
    for o in outcomes {
        let _ = write!(s, "{:<18}", o.strategy);
        for c in &campaigns {
            let n = o.totals.science.get(*c).copied().unwrap_or_default();
            let _ = write!(s, "  {:>12}", format!("{}/{}", n.done, n.failed));
        }
        let replans = o
            .sols
            .iter()
            .filter_map(|r| r.activity_plan.as_ref())
            .flat_map(|p| &p.changes)
            .filter(|c| c.ends_with("replanned"))
            .count();
        let _ = writeln!(s, "  {replans:>16}");
    }
}

/// The kinds of sol a gained drive can fall on, in the order a gained sol is counted by: the
/// first that applies. Each is a reason the ground-in-the-loop practice cannot use the sol; a
/// sol with none of them is an `ordinary sol` (the ground skipped it by its own rules).
pub const GAINED_SOL_KINDS: [&str; 4] = [
    "no downlink pass",
    "restricted",
    "no uplink (weekend or multi-sol plan)",
    "ordinary sol",
];

/// The kind a gained drive sol is counted under: the first of [`GAINED_SOL_KINDS`] that
/// applies to its calendar entry.
fn gained_sol_kind(entry: &sim::SolEntry) -> &'static str {
    if !entry.downlink {
        GAINED_SOL_KINDS[0]
    } else if entry.restricted {
        GAINED_SOL_KINDS[1]
    } else if !entry.uplink {
        GAINED_SOL_KINDS[2]
    } else {
        GAINED_SOL_KINDS[3]
    }
}

/// "1 no downlink pass", "1 restricted", …: the gained sols counted once each, by their first
/// kind ([`GAINED_SOL_KINDS`] order), kinds with none left out.
fn gained_kind_counts(gained: &[u32], cal: &sim::Calendar) -> Vec<String> {
    GAINED_SOL_KINDS
        .iter()
        .filter_map(|kind| {
            let n = gained
                .iter()
                .filter(|sol| {
                    cal.sols
                        .iter()
                        .find(|e| e.sol == **sol)
                        .is_some_and(|e| gained_sol_kind(e) == *kind)
                })
                .count();
            (n > 0).then(|| format!("{n} {kind}"))
        })
        .collect()
}

/// Sols `o` drove that `base` did not while `base` was still short of the goal (gained), and sols
/// `base` drove that `o` did not while `o` was still short of it (lost). A strategy that has
/// reached the goal has no more sols to lose: not driving after it is not a loss.
pub(crate) fn gained_lost(o: &CampaignOutcome, base: &CampaignOutcome) -> (Vec<u32>, Vec<u32>) {
    let drove = |o: &CampaignOutcome| -> Vec<u32> {
        o.sols.iter().filter(|r| r.drove).map(|r| r.sol).collect()
    };
    // The sol each reached the goal on, if it did.
    let goal_sol = |o: &CampaignOutcome| -> Option<u32> {
        let first = o.sols.first()?.sol;
        o.totals.sols_to_goal.map(|n| first + n.saturating_sub(1))
    };
    let still_driving = |o: &CampaignOutcome, sol: u32| goal_sol(o).is_none_or(|g| sol <= g);
    let (mine, theirs) = (drove(o), drove(base));
    let gained = mine
        .iter()
        .copied()
        .filter(|&d| !theirs.contains(&d) && still_driving(base, d))
        .collect();
    let lost = theirs
        .iter()
        .copied()
        .filter(|&d| !mine.contains(&d) && still_driving(o, d))
        .collect();
    (gained, lost)
}

/// `sols 403, 406 (1 no downlink pass, 1 restricted)`, or `none`: gained sols with their kinds.
pub(crate) fn gained_text(gained: &[u32], cal: &sim::Calendar) -> String {
    if gained.is_empty() {
        return "none".into();
    }
    let kinds = gained_kind_counts(gained, cal);
    if kinds.is_empty() {
        format!("sols {}", sol_list(gained))
    } else {
        format!("sols {} ({})", sol_list(gained), kinds.join(", "))
    }
}

/// `sols 624`, or `none`.
pub(crate) fn lost_text(lost: &[u32]) -> String {
    if lost.is_empty() {
        "none".into()
    } else {
        format!("sols {}", sol_list(lost))
    }
}

/// Plans (distinct uplink sols) that commanded at least one of the run's drives.
pub(crate) fn uplinks_with_drive_plans(o: &CampaignOutcome) -> usize {
    let mut u: Vec<u32> = o
        .sols
        .iter()
        .filter(|r| r.drove)
        .map(|r| r.plan_uplink_sol)
        .collect();
    u.dedup();
    u.len()
}

/// Hours the run's drives took.
pub(crate) fn drive_hours(o: &CampaignOutcome) -> f64 {
    o.sols.iter().map(|r| r.drive_time_s).sum::<f64>() / 3600.0
}

/// `403, 406`.
fn sol_list(sols: &[u32]) -> String {
    sols.iter()
        .map(u32::to_string)
        .collect::<Vec<_>>()
        .join(", ")
}

/// `403, 406, 410-415`: runs of consecutive sols as ranges.
fn sol_ranges(sols: &[u32]) -> String {
    let mut runs: Vec<(u32, u32)> = Vec::new();
    for &sol in sols {
        match runs.last_mut() {
            Some((_, end)) if *end + 1 == sol => *end = sol,
            _ => runs.push((sol, sol)),
        }
    }
    runs.iter()
        .map(|&(a, b)| match b - a {
            0 => a.to_string(),
            1 => format!("{a}, {b}"),
            _ => format!("{a}-{b}"),
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// `1 sol` / `2 sols`, with `noun` for the word.
fn count(n: usize, noun: &str) -> String {
    format!("{n} {noun}{}", if n == 1 { "" } else { "s" })
}

/// The plain-words name of a strategy in the verdict.
fn plain_name(strategy: sim::Strategy) -> &'static str {
    match strategy {
        sim::Strategy::Onboard => "onboard localization",
        sim::Strategy::Extension => "extension",
        sim::Strategy::ExtensionOnboard => "extension with onboard localization",
        sim::Strategy::Ground => "ground",
        sim::Strategy::Replay => "the replay",
    }
}

/// The verdict line at the top of `solsim compare`: what onboard localization and extension
/// (and the two together) buy over `ground` on this scenario's seed — drive sols gained or lost,
/// by number, metres, the study segment's sols, and any change in faults — and, with `over_runs`
/// (`--runs N`), the mean paired differences over the N runs with their 95 % bootstrap
/// intervals. One line, ending in a newline.
#[must_use]
pub fn verdict(
    scenario: &Scenario,
    outcomes: &[CampaignOutcome],
    over_runs: Option<&sweep::engine::Summary>,
) -> String {
    let Some(base) = outcomes
        .iter()
        .find(|o| o.strategy == sim::Strategy::Ground)
    else {
        return "Verdict: none — ground, the practice the strategies are measured against, is not \
                among this scenario's strategies.\n"
            .into();
    };
    let cal = &scenario.campaign.calendar;
    let clauses: Vec<String> = outcomes
        .iter()
        .filter(|o| {
            matches!(
                o.strategy,
                sim::Strategy::Onboard | sim::Strategy::Extension | sim::Strategy::ExtensionOnboard
            )
        })
        .map(|o| {
            let (gained, lost) = gained_lost(o, base);
            let d_m = o.totals.distance_m - base.totals.distance_m;
            // "gains 2 drive sols (403, 406) and 416 m", "loses 1 drive sol (405) and 120 m";
            // metres that go the other way, or with no sol or both ways, are said on their own.
            let one_way = gained.is_empty() != lost.is_empty();
            let along = one_way && (d_m > 0.0) == lost.is_empty() && d_m.abs() >= 0.5;
            let mut parts = vec![match (gained.len(), lost.len()) {
                (0, 0) => "gains no drive sol".to_string(),
                (g, 0) => format!("gains {} ({})", count(g, "drive sol"), sol_ranges(&gained)),
                (0, l) => format!("loses {} ({})", count(l, "drive sol"), sol_ranges(&lost)),
                (g, l) => format!(
                    "gains {} ({}) but loses {} ({})",
                    count(g, "drive sol"),
                    sol_ranges(&gained),
                    l,
                    sol_ranges(&lost)
                ),
            }];
            if along {
                parts[0].push_str(&format!(" and {:.0} m", d_m.abs()));
            } else if d_m.abs() < 0.5 {
                parts.push("drives the same metres".into());
            } else if d_m > 0.0 {
                parts.push(format!("drives {d_m:.0} m more"));
            } else {
                parts.push(format!("drives {:.0} m less", -d_m));
            }
            match (o.totals.sols_to_goal, base.totals.sols_to_goal) {
                (Some(m), Some(b)) if m < b => parts.push(format!(
                    "reaches the goal {} sooner (in {m} sols against {b})",
                    count((b - m) as usize, "sol")
                )),
                (Some(m), Some(b)) if m > b => parts.push(format!(
                    "reaches the goal {} later (in {m} sols against {b})",
                    count((m - b) as usize, "sol")
                )),
                (Some(m), None) => parts.push(format!(
                    "reaches the goal in {m} sols, which ground does not within the calendar"
                )),
                (None, Some(b)) => parts.push(format!(
                    "does not reach the goal within the calendar, which ground does in {b} sols"
                )),
                _ => {}
            }
            if let Some(g) = scenario.study_segment {
                let mine = o.sols_to_cover(g.from_sol, g.distance_m);
                let theirs = base.sols_to_cover(g.from_sol, g.distance_m);
                let left = cal.sols_from(g.from_sol);
                parts.push(match (mine, theirs) {
                    (Some(m), Some(b)) if m < b => format!(
                        "covers the study segment {} sooner (in {m} sols)",
                        count((b - m) as usize, "sol")
                    ),
                    (Some(m), Some(b)) if m > b => format!(
                        "covers the study segment {} later (in {m} sols)",
                        count((m - b) as usize, "sol")
                    ),
                    (Some(m), Some(_)) => format!("covers the study segment in the same {m} sols"),
                    (Some(m), None) => format!(
                        "covers the study segment at least {} sooner (in {m} sols)",
                        count((left + 1).saturating_sub(m) as usize, "sol")
                    ),
                    (None, _) => "does not cover the study segment within the calendar".into(),
                });
            }
            let (f, bf) = (o.totals.faults, base.totals.faults);
            if f != bf {
                parts.push(format!(
                    "meets {} against ground's {bf}",
                    count(f as usize, "fault")
                ));
            }
            let last = parts.pop().unwrap_or_default();
            let mut clause = match parts.len() {
                0 => format!("{} {last}", plain_name(o.strategy)),
                1 => format!("{} {} and {last}", plain_name(o.strategy), parts[0]),
                _ => format!(
                    "{} {}, and {last}",
                    plain_name(o.strategy),
                    parts.join(", ")
                ),
            };
            if let Some(runs) = over_runs.and_then(|summary| {
                crate::report_runs::verdict_over_runs(summary, o.strategy.name())
            }) {
                clause.push_str(&format!(" — {runs}"));
            }
            clause
        })
        .collect();
    if clauses.is_empty() {
        return "Verdict: none — neither onboard localization nor extension is among this \
                scenario's strategies.\n"
            .into();
    }
    // Ground's own sols for the study segment, once, after the clauses that compare with it.
    let ground_segment = scenario.study_segment.map_or(String::new(), |g| {
        match base.sols_to_cover(g.from_sol, g.distance_m) {
            Some(b) => format!("; ground covers the study segment in {b} sols"),
            None => format!(
                "; ground does not cover the study segment within the {} sols left",
                cal.sols_from(g.from_sol)
            ),
        }
    });
    format!(
        "Verdict against ground (same seed and calendar): {}{ground_segment}.\n",
        clauses.join("; ")
    )
}

/// Under the compare table: each strategy against `ground` on the same seed and calendar —
/// sols to cover the study segment, drive sols gained (each counted once, under the first of
/// [`GAINED_SOL_KINDS`] that applies) and lost, by number, metres,
/// faults avoided, peak uncertainty, uplinks that needed a drive plan, drive time. Empty when
/// `ground` is not among the outcomes.
#[must_use]
pub fn against_ground(scenario: &Scenario, outcomes: &[CampaignOutcome]) -> String {
    let Some(base) = outcomes
        .iter()
        .find(|o| o.strategy == sim::Strategy::Ground)
    else {
        return String::new();
    };
    let cal = &scenario.campaign.calendar;
    // A run that did not cover the segment needs more than the sols left in the calendar, so
    // "k fewer than ground" is still a bound when ground did not cover it.
    let segment = |o: &CampaignOutcome| {
        scenario.study_segment.map(|g| {
            let left = cal.sols_from(g.from_sol);
            let mine = o.sols_to_cover(g.from_sol, g.distance_m);
            let against = if o.strategy == sim::Strategy::Ground {
                String::new()
            } else {
                match (mine, base.sols_to_cover(g.from_sol, g.distance_m)) {
                    (Some(m), Some(b)) => {
                        format!(" against {b} ({:+})", i64::from(m) - i64::from(b))
                    }
                    (Some(m), None) => format!(
                        " against more than {left}: at least {} fewer",
                        i64::from(left) + 1 - i64::from(m)
                    ),
                    _ => String::new(),
                }
            };
            mine.map_or(
                format!("not covered within the calendar (more than {left} sols)"),
                |n| format!("covered in {n} sols{against}"),
            )
        })
    };
    let mut s = String::new();
    let _ = writeln!(
        s,
        "\nAgainst ground (same seed, same calendar; one run — `--runs N` gives rates and intervals):"
    );
    let _ = writeln!(
        s,
        "  (each gained drive sol is counted once, by the first that applies: {}; lost: sols \
         ground drove and the strategy did not, before it reached the goal)",
        GAINED_SOL_KINDS.join(", ")
    );
    if let (Some(g), Some(b)) = (scenario.study_segment, segment(base)) {
        let _ = writeln!(
            s,
            "  study segment ({:.0} m from sol {}): ground: {b}",
            g.distance_m, g.from_sol
        );
    }
    for o in outcomes
        .iter()
        .filter(|o| o.strategy != sim::Strategy::Ground)
    {
        let t = &o.totals;
        let bt = &base.totals;
        let (gained, lost) = gained_lost(o, base);
        let _ = writeln!(s, "  {}:", o.strategy);
        if let Some(seg) = segment(o) {
            let _ = writeln!(s, "    study segment: {seg}");
        }
        let _ = writeln!(
            s,
            "    drive sols: {} against {} ({:+}); gained {}; lost {}",
            t.drive_sols,
            bt.drive_sols,
            i64::from(t.drive_sols) - i64::from(bt.drive_sols),
            gained_text(&gained, cal),
            lost_text(&lost)
        );
        let _ = writeln!(
            s,
            "    distance: {:.1} m against {:.1} m ({:+.1} m); drive time {:.1} h against {:.1} h",
            t.distance_m,
            bt.distance_m,
            t.distance_m - bt.distance_m,
            drive_hours(o),
            drive_hours(base)
        );
        let _ = writeln!(
            s,
            "    NO_PATH {} against {}, all faults {} against {}; peak r {:.2} m against {:.2} m",
            t.no_path_faults,
            bt.no_path_faults,
            t.faults,
            bt.faults,
            t.max_uncertainty_m,
            bt.max_uncertainty_m
        );
        let _ = writeln!(
            s,
            "    uplinks that needed a drive plan: {} against {}",
            uplinks_with_drive_plans(o),
            uplinks_with_drive_plans(base)
        );
    }
    s
}
