//! One sol planned from a campaign file with the branch-and-bound planner (paper 003 §3.1),
//! what `solsim plan` prints: the timeline with the resources after each step, the utility
//! per campaign and per tier, and the independent validator's findings ([`plan_file`]).
//!
//! The campaign file format lives in [`study::campaign_file`]; [`crate::plan_table`] renders
//! a [`PlanReport`] as a table or as JSON (the same content).
//!
//! ## References
//! Paper 003 §3 (campaign intents: goal set, temporally periodic, state-based), §3.1
//! (anytime branch and bound), §5 (the illustrative scenario).

use std::path::Path;
use std::time::Duration;

use planner::{
    Instance, MICRO_PER_POINT, PlanOutcome, SearchSettings, State, TaskId, Timeline, Violation,
    step_resources, validate_plan,
};

use study::campaign_file::{CampaignFile, PlanFileError};

/// Node budget when `--nodes` is not given: with no time budget the plan is a deterministic
/// function of the file.
pub const DEFAULT_NODE_BUDGET: u64 = 100_000;

/// How long the search may go on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PlanBudget {
    /// Most search nodes to expand (default: [`DEFAULT_NODE_BUDGET`]). Under a node budget
    /// alone the plan is a deterministic function of the file.
    pub nodes: u64,
    /// Also stop after this many milliseconds of search; when it binds, the plan, bound and
    /// node count depend on the machine.
    pub time_budget_ms: Option<u64>,
}

impl Default for PlanBudget {
    fn default() -> Self {
        PlanBudget {
            nodes: DEFAULT_NODE_BUDGET,
            time_budget_ms: None,
        }
    }
}

/// One row of the timeline.
#[derive(Debug, Clone, PartialEq)]
pub struct TimelineRow {
    /// Start, s after local midnight.
    pub start_s: i64,
    /// End, s after local midnight.
    pub end_s: i64,
    /// The activity id.
    pub activity: String,
    /// The activity's human-readable name (may be empty).
    pub name: String,
    /// For a drive segment: `(k, n, from_m, to_m)`, `k` 1-based, metres from the drive start.
    pub segment: Option<(u32, u32, f64, f64)>,
    /// Campaign the task counts towards (a drive counts on its last segment only).
    pub campaign: Option<String>,
    /// Mandatory activity.
    pub mandatory: bool,
    /// The timeline(s) it holds (`hbs_link` steps run in parallel with `main` ones).
    pub timeline: Timeline,
    /// Metres driven (all drives) when the step starts.
    pub driven_at_start_m: f64,
    /// Battery energy after the step, Wh.
    pub energy_wh: f64,
    /// Stored data after the step (after its downlink), MB.
    pub data_mb: f64,
}

/// Utility earned by one campaign.
#[derive(Debug, Clone, PartialEq)]
pub struct CampaignUtility {
    /// Campaign id.
    pub id: String,
    /// `goal_set`, `periodic` or `state_based`.
    pub intent: &'static str,
    /// Priority tier (1 is highest).
    pub tier: usize,
    /// Members in the plan.
    pub scheduled: u32,
    /// Candidate members in the file (instances, for periodic and state-based campaigns).
    pub candidates: u32,
    /// Utility points earned.
    pub points: f64,
    /// Utility points at `max_count` members.
    pub max_points: f64,
}

/// Everything `solsim plan` prints.
#[derive(Debug, Clone)]
pub struct PlanReport {
    /// The campaign file.
    pub file: CampaignFile,
    /// The search result.
    pub outcome: PlanOutcome,
    /// The timeline.
    pub rows: Vec<TimelineRow>,
    /// Utility per campaign, in file order.
    pub campaigns: Vec<CampaignUtility>,
    /// Utility of activities' own `utility` (outside campaigns) per tier, points.
    pub own_points: [f64; planner::MAX_TIERS],
    /// The validator's findings, described with task names; empty means valid.
    pub violations: Vec<String>,
    /// Node budget used.
    pub node_budget: u64,
    /// Time budget, if any (then the output may vary).
    pub time_budget_ms: Option<u64>,
}

use sim::time::lmst_of as lmst;

fn points(micro: i64) -> f64 {
    micro as f64 / MICRO_PER_POINT
}

/// Load, plan and check a campaign file.
///
/// # Errors
/// A [`PlanFileError`] when the file is unreadable or malformed (exit 2 in the binary). A
/// sol with no feasible plan is not an error: it is reported in the outcome's status.
pub fn plan_file(campaign: &Path, budget: PlanBudget) -> Result<PlanReport, PlanFileError> {
    let file = CampaignFile::load(campaign)?;
    let settings = SearchSettings {
        node_budget: Some(budget.nodes),
        time_budget: budget.time_budget_ms.map(Duration::from_millis),
        ..SearchSettings::default()
    };
    let instance = Instance::new(&file.problem).map_err(|e| file.planner_error(e))?;
    let state = State::initial(&instance);
    let outcome =
        planner::plan_from(&instance, &state, &settings).map_err(|e| file.planner_error(e))?;
    let violations = validate_plan(&instance, &state, &outcome.plan)
        .iter()
        .map(|v| describe(&instance, &outcome, v))
        .collect();
    let rows = timeline(&instance, &state, &outcome);
    let (campaigns, own_points) = utilities(&instance, &outcome);
    Ok(PlanReport {
        file,
        outcome,
        rows,
        campaigns,
        own_points,
        violations,
        node_budget: budget.nodes,
        time_budget_ms: budget.time_budget_ms,
    })
}

fn timeline(instance: &Instance, state: &State, outcome: &PlanOutcome) -> Vec<TimelineRow> {
    let p = instance.problem();
    let mut rows = Vec::with_capacity(outcome.plan.steps.len());
    // The validator's re-simulation: battery and data after each step, metres at its start.
    let resources = step_resources(instance, state, &outcome.plan);
    for (s, r) in outcome.plan.steps.iter().zip(resources) {
        let task = instance.task(s.task);
        let activity = &p.activities[task.activity];
        let segment = task.segment.map(|(j, k)| {
            // fold from +0.0: an empty f64 `sum` is -0.0, which prints as "-0".
            let from_m = instance.activity_tasks(task.activity)[..j as usize]
                .iter()
                .fold(0.0, |m, &t| m + instance.task(t).drive_m);
            (j + 1, k, from_m, from_m + task.drive_m)
        });
        rows.push(TimelineRow {
            start_s: s.start_s,
            end_s: s.end_s,
            activity: activity.id.clone(),
            name: activity.name.clone(),
            segment,
            campaign: task
                .campaign
                .map(|c| instance.problem().campaigns[c].id.clone()),
            mandatory: task.mandatory,
            timeline: task.timeline,
            driven_at_start_m: r.driven_at_start_m,
            energy_wh: r.energy_wh_after,
            data_mb: r.data_mb_after,
        });
    }
    rows
}

fn utilities(
    instance: &Instance,
    outcome: &PlanOutcome,
) -> (Vec<CampaignUtility>, [f64; planner::MAX_TIERS]) {
    let p = instance.problem();
    let mut counts = vec![0u32; instance.campaigns().len()];
    let mut own = [0i64; planner::MAX_TIERS];
    for s in &outcome.plan.steps {
        let t = instance.task(s.task);
        if let Some(c) = t.campaign {
            counts[c] += 1;
        }
        own[t.tier] += t.utility_micro;
    }
    let campaigns = instance
        .campaigns()
        .iter()
        .zip(&p.campaigns)
        .enumerate()
        .map(|(i, (curve, c))| CampaignUtility {
            id: c.id.clone(),
            intent: match c.intent {
                planner::CampaignIntent::GoalSet => "goal_set",
                planner::CampaignIntent::Periodic { .. } => "periodic",
                planner::CampaignIntent::StateBased { .. } => "state_based",
            },
            tier: curve.tier + 1,
            scheduled: counts[i],
            candidates: instance
                .tasks()
                .iter()
                .filter(|t| t.campaign == Some(i))
                .count() as u32,
            points: points(curve.utility(counts[i])),
            max_points: points(curve.utility(c.max_count)),
        })
        .collect();
    (campaigns, own.map(points))
}

fn task_name(instance: &Instance, t: TaskId) -> String {
    instance
        .tasks()
        .get(t.index())
        .map_or_else(|| format!("task {}", t.0), |t| t.name.clone())
}

fn describe(instance: &Instance, outcome: &PlanOutcome, v: &Violation) -> String {
    let step = |i: usize| {
        outcome.plan.steps.get(i).map_or_else(
            || format!("step {i}"),
            |s| format!("step {i} ({})", task_name(instance, s.task)),
        )
    };
    match v {
        Violation::UnknownTask { step: i } => format!("{}: unknown task", step(*i)),
        Violation::Repeated { step: i } => format!("{}: repeated", step(*i)),
        Violation::WrongDuration {
            step: i,
            expected_s,
            found_s,
        } => format!("{}: lasts {found_s} s, expected {expected_s} s", step(*i)),
        Violation::OutsideWindow { step: i, start_s } => {
            format!(
                "{}: starts at {} outside its window",
                step(*i),
                lmst(*start_s)
            )
        }
        Violation::Overlap { step: i } => format!("{}: overlaps the previous step", step(*i)),
        Violation::LinkOverlap { step: i, other } => format!(
            "{}: overlaps {} on the HBS link",
            step(*i),
            task_name(instance, *other)
        ),
        Violation::PastEndOfSol { step: i } => format!("{}: ends after the sol window", step(*i)),
        Violation::MissingPrecondition {
            step: i,
            precondition,
        } => format!(
            "{}: precondition {} has not ended",
            step(*i),
            task_name(instance, *precondition)
        ),
        Violation::OutsideDrivenWindow { step: i, driven_m } => format!(
            "{}: starts at {driven_m:.1} m driven, outside its state-based window",
            step(*i)
        ),
        Violation::BatteryEmpty { step: i, energy_wh } => {
            format!("{}: battery empty ({energy_wh:.2} Wh)", step(*i))
        }
        Violation::DataFull { step: i, data_mb } => {
            format!("{}: data store full ({data_mb:.1} MB)", step(*i))
        }
        Violation::MissingMandatory { task } => {
            format!(
                "mandatory {} is not in the plan",
                task_name(instance, *task)
            )
        }
    }
}
