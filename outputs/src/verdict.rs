//! The verdict at the top of `solsim compare` ([`verdict`]): what onboard localization,
//! extension and the two together buy over `ground` in plain words, one line.

use sim::CampaignOutcome;
use study::Scenario;

use crate::against_ground::gained_lost;
use crate::over_runs::verdict_over_runs;

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
    let cal = &scenario.settings.calendar;
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
            if let Some(runs) =
                over_runs.and_then(|summary| verdict_over_runs(summary, o.strategy.name()))
            {
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
