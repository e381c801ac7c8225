//! Each strategy against `ground` on the same seed and calendar: the drive sols gained and lost
//! (each gained sol counted once, under the first of [`GAINED_SOL_KINDS`] that applies), the
//! metres, drive hours and uplinks that needed a drive plan — in words under the compare table
//! ([`against_ground`]) and as the pieces the report's table and the verdict reuse.

use std::fmt::Write as _;

use sim::CampaignOutcome;
use study::Scenario;

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
    let cal = &scenario.settings.calendar;
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
