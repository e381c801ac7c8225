//! The tables of a compare run's report that have no terminal twin to copy: each strategy's
//! sol log with headers a reader knows ("Distance (m)", not `distance_m`; the CSV beside the
//! run keeps every column under its machine name), and the verdict against ground as a table,
//! one row per strategy, each figure with its difference from ground in brackets.

use std::fmt::Write as _;

use sim::{CampaignOutcome, SolRecord, Strategy};
use study::Scenario;

use crate::against_ground::{
    drive_hours, gained_lost, gained_text, lost_text, uplinks_with_drive_plans,
};
use crate::html::markup::{escape, table_aligned};

/// One sol's localizations as text: the ground's with the uplink, the rover's after the drive.
fn localization_cell(r: &SolRecord) -> String {
    let mut parts = Vec::new();
    if r.ground_localization.is_some() {
        parts.push("ground, with the uplink".to_string());
    }
    if let Some(l) = &r.onboard_localization {
        parts.push(if l.applied {
            format!(
                "onboard ({}): r to {:.2} m",
                l.localizer, l.uncertainty_after_m
            )
        } else {
            format!(
                "onboard ({}) rejected: {}",
                l.localizer,
                l.reason
                    .as_ref()
                    .map(ToString::to_string)
                    .unwrap_or_default()
            )
        });
    }
    parts.join("; ")
}

/// One strategy's sol log.
pub(crate) fn sol_log_table(s: &mut String, o: &CampaignOutcome) {
    let yes_no = |b: bool| if b { "yes" } else { "no" }.to_string();
    let mut rows = vec![
        [
            "Sol",
            "Plan uplinked on sol",
            "Drove",
            "Distance (m)",
            "Without VO (m)",
            "Drive time (min)",
            "r at start (m)",
            "r at end of drive (m)",
            "Passage clearance (m)",
            "Fault",
            "Localization",
            "Truth error (m)",
            "Truth in disc",
            "End position x, y (m)",
            "Note",
        ]
        .map(String::from)
        .to_vec(),
    ];
    for r in &o.sols {
        let mut note: Vec<String> = Vec::new();
        if let Some(why) = r.skip_reason {
            note.push(format!("not driven: {why}"));
        }
        if r.reached_goal {
            note.push("goal reached".into());
        }
        rows.push(vec![
            r.sol.to_string(),
            r.plan_uplink_sol.to_string(),
            yes_no(r.drove),
            format!("{:.1}", r.distance_m),
            format!("{:.1}", r.d_novo_m),
            format!("{:.0}", r.drive_time_s / 60.0),
            format!("{:.2}", r.start_uncertainty_m),
            format!("{:.2}", r.end_uncertainty_m),
            r.passage_clearance_m
                .map_or(String::new(), |c| format!("{c:.2}")),
            r.fault.as_ref().map_or(String::new(), |f| {
                format!(
                    "{} after {:.1} m at r = {:.2} m",
                    f.kind.name(),
                    f.after_m,
                    f.uncertainty_m
                )
            }),
            localization_cell(r),
            format!("{:.2}", r.truth_error_m),
            r.truth_inside_disc.map_or(String::new(), yes_no),
            format!("{:.0}, {:.0}", r.end_position_m[0], r.end_position_m[1]),
            note.join("; "),
        ]);
    }
    table_aligned(s, "sols", &rows, &[2, 9, 10, 12, 14]);
}

/// `value (+difference)` against ground's, or the value alone on ground's own row.
fn against(value: String, difference: Option<String>) -> String {
    match difference {
        Some(d) => format!("{value} ({d})"),
        None => value,
    }
}

/// Each strategy against `ground` on the same seed and calendar, as `report::against_ground`
/// prints it under the compare table: sols to cover the study segment, drive sols and which
/// were gained (on which kind of sol) or lost, metres, drive time, faults, peak uncertainty and
/// the uplinks that needed a drive plan. Nothing when `ground` is not among the outcomes.
pub(crate) fn against_ground_table(
    s: &mut String,
    scenario: &Scenario,
    outcomes: &[CampaignOutcome],
) {
    let Some(base) = outcomes.iter().find(|o| o.strategy == Strategy::Ground) else {
        return;
    };
    let cal = &scenario.settings.calendar;
    let segment = scenario.study_segment;
    let mut header: Vec<String> = vec!["Strategy".into()];
    if let Some(g) = segment {
        header.push(format!(
            "Sols to cover the study segment ({:.0} m from sol {})",
            g.distance_m, g.from_sol
        ));
    }
    header.extend(
        [
            "Drive sols",
            "Drive sols gained (kind of sol)",
            "Drive sols lost",
            "Distance (m)",
            "Drive time (h)",
            "NO_PATH faults",
            "All faults",
            "Peak r (m)",
            "Uplinks that needed a drive plan",
        ]
        .map(String::from),
    );
    let mut rows = vec![header];
    let bt = &base.totals;
    // Ground first: the row the others are measured against.
    let order =
        std::iter::once(base).chain(outcomes.iter().filter(|o| o.strategy != Strategy::Ground));
    for o in order {
        let is_base = o.strategy == Strategy::Ground;
        let t = &o.totals;
        let diff = |d: String| (!is_base).then_some(d);
        let mut row = vec![o.strategy.name().to_string()];
        if let Some(g) = segment {
            let left = cal.sols_from(g.from_sol);
            let mine = o.sols_to_cover(g.from_sol, g.distance_m);
            let theirs = base.sols_to_cover(g.from_sol, g.distance_m);
            row.push(match (mine, theirs) {
                (None, _) => format!("not covered (more than {left})"),
                (Some(m), _) if is_base => m.to_string(),
                (Some(m), Some(b)) => format!("{m} ({:+})", i64::from(m) - i64::from(b)),
                (Some(m), None) => format!(
                    "{m} (at least {} fewer)",
                    i64::from(left) + 1 - i64::from(m)
                ),
            });
        }
        let (gained, lost) = gained_lost(o, base);
        let gained_text = if is_base {
            "—".to_string()
        } else {
            gained_text(&gained, cal)
        };
        row.extend([
            against(
                t.drive_sols.to_string(),
                diff(format!(
                    "{:+}",
                    i64::from(t.drive_sols) - i64::from(bt.drive_sols)
                )),
            ),
            gained_text,
            if is_base {
                "—".to_string()
            } else {
                lost_text(&lost)
            },
            against(
                format!("{:.1}", t.distance_m),
                diff(format!("{:+.1}", t.distance_m - bt.distance_m)),
            ),
            against(
                format!("{:.1}", drive_hours(o)),
                diff(format!("{:+.1}", drive_hours(o) - drive_hours(base))),
            ),
            against(
                t.no_path_faults.to_string(),
                diff(format!(
                    "{:+}",
                    i64::from(t.no_path_faults) - i64::from(bt.no_path_faults)
                )),
            ),
            against(
                t.faults.to_string(),
                diff(format!("{:+}", i64::from(t.faults) - i64::from(bt.faults))),
            ),
            against(
                format!("{:.2}", t.max_uncertainty_m),
                diff(format!(
                    "{:+.2}",
                    t.max_uncertainty_m - bt.max_uncertainty_m
                )),
            ),
            against(
                uplinks_with_drive_plans(o).to_string(),
                diff(format!(
                    "{:+}",
                    uplinks_with_drive_plans(o) as i64 - uplinks_with_drive_plans(base) as i64
                )),
            ),
        ]);
        rows.push(row);
    }
    s.push_str("<h2 id=\"verdict\">Against ground-in-the-loop</h2>\n");
    let _ = writeln!(
        s,
        "<p>{}</p>",
        escape(
            "Each strategy on the same seed and calendar as ground, one run; in brackets the \
             difference from ground. compare --runs N gives rates with intervals over many \
             seeded worlds."
        )
    );
    let gained_column = 2 + usize::from(segment.is_some());
    table_aligned(s, "verdict", &rows, &[gained_column]);
}
