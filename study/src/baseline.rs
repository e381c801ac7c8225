//! The `ground` baseline set beside the record (`solsim record baseline`): which sols both drove,
//! which only the record, which only the model, each with the rule that decided it, and metres
//! per sol.
//!
//! A baseline more cautious than reality inflates every gain credited to onboard localization
//! (docs/design.md, "Operations strategies, precisely"): `ground` must be able to drive every sol the team drove. Two views of `ground`
//! are set beside the record: the **calendar's rule** ([`sim::operations::policy::Policy::calendar_schedule`],
//! every commanded drive assumed to happen: what the calendar alone decides) and the
//! **simulated** strategy over `runs` seeded worlds (where faults, the route's end and the
//! planners' passage limits may also stop it), run 0 in full and the share of runs it drove.

use std::fmt::Write as _;
use std::path::Path;

use sim::Strategy;
use sim::operations::policy::Policy;

use crate::{Scenario, ScenarioError};

/// Who drove a sol.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Agreement {
    /// The record and the simulated ground both drove.
    Both,
    /// Only the record drove.
    RecordOnly,
    /// Only the simulated ground drove.
    ModelOnly,
    /// Neither drove.
    Neither,
}

impl Agreement {
    /// Short name, as the table prints it.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Agreement::Both => "both",
            Agreement::RecordOnly => "record only",
            Agreement::ModelOnly => "model only",
            Agreement::Neither => "neither",
        }
    }
}

/// One sol of the baseline report.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct BaselineRow {
    /// Mission sol.
    pub sol: u32,
    /// The Pasadena day its plan is built on (`YYYY-MM-DD Www`), with a computed calendar.
    pub planning_day: Option<String>,
    /// A plan is uplinked this sol.
    pub uplink: bool,
    /// Its plan is restricted (the previous sol's data arrives too late).
    pub restricted: bool,
    /// Metres the record drove (historic input).
    pub record_m: f64,
    /// What the calendar's rule decides for ground: `None` drives, else why not.
    pub calendar_rule: Option<String>,
    /// Metres the simulated ground drove in run 0.
    pub ground_m: f64,
    /// Why the simulated ground did not drive in run 0.
    pub ground_reason: Option<String>,
    /// Share of the runs in which the simulated ground drove this sol.
    pub ground_drove_share: f64,
    /// Who drove, in run 0.
    pub agreement: Agreement,
    /// The scenario's note for the sol (a science stop, a missing pass …).
    pub note: String,
}

/// The baseline report.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Baseline {
    /// The scenario's name.
    pub scenario: String,
    /// Runs of the simulated ground.
    pub runs: u64,
    /// Per sol.
    pub rows: Vec<BaselineRow>,
}

impl Baseline {
    /// Sols with the given agreement.
    #[must_use]
    pub fn sols(&self, a: Agreement) -> Vec<u32> {
        self.rows
            .iter()
            .filter(|r| r.agreement == a)
            .map(|r| r.sol)
            .collect()
    }

    /// The printed table: per sol, the planning day, the record's metres, what ground drove
    /// (run 0) and how often, who drove and the rule; then the sols by agreement and each
    /// disagreement.
    #[must_use]
    pub fn text(&self) -> String {
        let mut t = String::new();
        let _ = writeln!(
            t,
            "ground beside the record: {} ({} runs of ground; run 0 in the table)",
            self.scenario, self.runs
        );
        let _ = writeln!(
            t,
            "{:>5}  {:<14}  {:>6}  {:>8}  {:>8}  {:>6}  {:<11}  rule",
            "sol", "planned (PT)", "plan", "record m", "ground m", "drove", "who"
        );
        for r in &self.rows {
            let plan = match (r.uplink, r.restricted) {
                (true, true) => "restr",
                (true, false) => "uplink",
                (false, _) => "",
            };
            let rule = r
                .ground_reason
                .clone()
                .or_else(|| r.calendar_rule.clone())
                .unwrap_or_else(|| "drives".to_owned());
            let _ = writeln!(
                t,
                "{:>5}  {:<14}  {plan:>6}  {:>8.1}  {:>8.1}  {:>5.0}%  {:<11}  {rule}",
                r.sol,
                r.planning_day.as_deref().unwrap_or(""),
                r.record_m,
                r.ground_m,
                100.0 * r.ground_drove_share,
                r.agreement.name()
            );
        }
        let list = |v: Vec<u32>| {
            if v.is_empty() {
                "none".to_owned()
            } else {
                v.iter()
                    .map(ToString::to_string)
                    .collect::<Vec<_>>()
                    .join(", ")
            }
        };
        let _ = writeln!(t, "both drove: {}", list(self.sols(Agreement::Both)));
        let _ = writeln!(t, "record only: {}", list(self.sols(Agreement::RecordOnly)));
        let _ = writeln!(t, "model only: {}", list(self.sols(Agreement::ModelOnly)));
        for r in self
            .rows
            .iter()
            .filter(|r| matches!(r.agreement, Agreement::RecordOnly | Agreement::ModelOnly))
        {
            let _ = writeln!(
                t,
                "disagreement on sol {}: {} (record {:.1} m, ground {:.1} m): {}",
                r.sol,
                r.agreement.name(),
                r.record_m,
                r.ground_m,
                r.ground_reason.as_deref().unwrap_or("ground drove")
            );
        }
        t
    }
}

/// Checks that `scenario` (read from `path`) has a record to set ground beside.
///
/// # Errors
/// A scenario without `historic_distance_m` per sol, named by `path`.
pub fn require_record(scenario: &Scenario, path: &Path) -> Result<(), ScenarioError> {
    if scenario.has_history {
        Ok(())
    } else {
        Err(ScenarioError::field(
            path,
            "sols",
            "a scenario with a record (historic_distance_m per sol)",
            "none",
        ))
    }
}

/// Set `ground` beside the scenario's record over run indices `0..runs`.
#[must_use]
pub fn ground_vs_record(scenario: &Scenario, runs: u64) -> Baseline {
    let cal = &scenario.settings.calendar;
    let policy = Policy::new(Strategy::Ground, scenario.settings.rules);
    let rule = policy.calendar_schedule(cal);
    let outcomes: Vec<_> = (0..runs.max(1))
        .map(|run| scenario.run_index(Strategy::Ground, run))
        .collect();
    let run0 = &outcomes[0];
    let rows = cal
        .sols
        .iter()
        .enumerate()
        .map(|(i, e)| {
            let record_m = e.historic.map_or(0.0, |h| h.distance_m);
            let ground = &run0.sols[i];
            let drove_share =
                outcomes.iter().filter(|o| o.sols[i].drove).count() as f64 / outcomes.len() as f64;
            let agreement = match (record_m > 0.0, ground.drove) {
                (true, true) => Agreement::Both,
                (true, false) => Agreement::RecordOnly,
                (false, true) => Agreement::ModelOnly,
                (false, false) => Agreement::Neither,
            };
            let computed = scenario
                .computed_calendar
                .as_ref()
                .and_then(|c| c.sols.get(i));
            BaselineRow {
                sol: e.sol,
                planning_day: computed
                    .map(sim::operations::ops_calendar::ComputedSol::planning_day_text),
                uplink: e.uplink,
                restricted: e.restricted,
                record_m,
                calendar_rule: rule[i].map(|r| r.to_string()),
                ground_m: ground.distance_m,
                ground_reason: ground.skip_reason.map(|r| r.to_string()),
                ground_drove_share: drove_share,
                agreement,
                note: scenario
                    .notes
                    .iter()
                    .find(|(s, _)| *s == e.sol)
                    .map_or_else(String::new, |(_, n)| n.clone()),
            }
        })
        .collect();
    Baseline {
        scenario: scenario.name.clone(),
        runs: runs.max(1),
        rows,
    }
}
