//! Executing a sol's plan step by step: small slips are repaired, big disruptions and new
//! goals replan from the current state, every plan is validated.

use planner::{
    Activity, Campaign, Instance, Plan, PlanStatus, PlanStep, RepairOutcome, SearchSettings, State,
    TaskId, plan_from, repair, step_resources, validate_plan,
};

use super::record::SolPlanStatus;
use super::{SolPlan, SolPlanRequest, SolPlanSettings, TimelineStep, sol_problem};
use crate::time::SolSeconds;

/// The next step of the sol's plan, as the simulator executes it.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    /// The activity id (`drive` for every drive segment).
    pub activity: String,
    /// `(j, k)`: drive segment `j` (0-based) of `k`.
    pub segment: Option<(u32, u32)>,
    /// Planned start.
    pub start_s: SolSeconds,
    /// Planned end.
    pub end_s: SolSeconds,
    /// Metres a drive segment covers (0 for other activities).
    pub drive_m: f64,
}

/// A big disruption reported with a step's end: the activities it cancels, and a full replan
/// from the state after the step (paper 003 §3.1: "major disruptions … invoke a full
/// replanning cycle").
#[derive(Clone, Debug, PartialEq)]
pub struct Disruption {
    /// What happened, for the sol log (`NO_PATH after 14.0 m`, `localization lost: …`).
    pub reason: String,
    /// Activity ids whose undone tasks are dropped (the rest of a faulted drive, the rest of
    /// an aborted localization chain).
    pub cancel: Vec<String>,
    /// Metres actually driven this sol, when it differs from the plan's.
    pub driven_m: Option<f64>,
}

/// One sol's plan being executed: the simulator takes [`SolExecution::next_step`], runs it,
/// and reports its actual end with [`SolExecution::complete`]; small slips are repaired
/// ([`planner::repair`]: later activities shift within their windows), big disruptions and new
/// goals ([`SolExecution::inject`]) replan from the current state ([`planner::plan_from`]).
/// Every plan the sol uses is checked by [`planner::validate_plan`].
#[derive(Clone, Debug)]
pub struct SolExecution {
    /// The sol's instance; its problem grows when a new goal is injected.
    inst: Instance,
    settings: SearchSettings,
    status: SolPlanStatus,
    /// The state before `remaining`.
    state: State,
    remaining: Plan,
    /// The state the sol's plan started from.
    initial: State,
    /// The executed steps as run (actual ends), one per row.
    executed: Vec<PlanStep>,
    rows: Vec<TimelineStep>,
    changes: Vec<String>,
    violations: Vec<String>,
}

use crate::time::lmst_of as lmst;

/// `"4 min 10 s late (planned 14:05)"`.
fn slip(actual: SolSeconds, planned: SolSeconds) -> String {
    let d = (actual - planned).abs();
    format!(
        "{} min {} s {} (planned {})",
        d / 60,
        d % 60,
        if actual > planned { "late" } else { "early" },
        planned.lmst()
    )
}

impl SolExecution {
    /// Plan the sol.
    ///
    /// # Errors
    /// The planner's error if the problem is malformed (a bug in [`sol_problem`] or settings
    /// that leave no room, e.g. a drive window past the end of the sol).
    pub fn new(p: &SolPlanSettings, req: &SolPlanRequest) -> Result<Self, planner::PlanError> {
        let problem = sol_problem(p, req);
        let inst = Instance::new(&problem)?;
        let settings = SearchSettings {
            node_budget: Some(p.node_budget),
            ..SearchSettings::default()
        };
        let state = State::initial(&inst);
        let outcome = plan_from(&inst, &state, &settings)?;
        let mut exec = Self {
            inst,
            settings,
            status: outcome.status.into(),
            initial: state.clone(),
            executed: Vec::new(),
            state,
            remaining: outcome.plan,
            rows: Vec::new(),
            changes: Vec::new(),
            violations: Vec::new(),
        };
        exec.validate("planned");
        Ok(exec)
    }

    fn validate(&mut self, which: &str) {
        let v = validate_plan(&self.inst, &self.state, &self.remaining);
        self.violations.extend(v.iter().map(|v| {
            format!(
                "{which} at {}: {v}; plan: {}",
                lmst(self.state.time_s),
                self.remaining.describe(&self.inst).join(", ")
            )
        }));
    }

    /// The next step to execute (`None` when the sol's plan is done).
    #[must_use]
    pub fn next_step(&self) -> Option<Step> {
        let s = self.remaining.steps.first()?;
        let task = self.inst.task(s.task);
        Some(Step {
            activity: self.inst.problem().activities[task.activity].id.clone(),
            segment: task.segment,
            start_s: SolSeconds::from_planner_s(s.start_s),
            end_s: SolSeconds::from_planner_s(s.end_s),
            drive_m: task.drive_m,
        })
    }

    /// The planning window `[start, end]`.
    #[must_use]
    pub fn window(&self) -> [SolSeconds; 2] {
        let p = self.inst.problem();
        [p.start_s, p.end_s].map(SolSeconds::from_planner_s)
    }

    /// Metres of driving still in the plan.
    #[must_use]
    pub fn drive_left_m(&self) -> f64 {
        self.remaining
            .steps
            .iter()
            .map(|s| self.inst.task(s.task).drive_m)
            .sum()
    }

    /// Whether an activity id is in the current problem.
    #[must_use]
    pub fn has_activity(&self, id: &str) -> bool {
        self.inst.problem().activities.iter().any(|a| a.id == id)
    }

    /// The next step ran and ended at `actual_end`; `outcome` goes into its timeline row.
    /// Without a disruption the rest of the plan is repaired (or, if a later activity no
    /// longer fits, replanned); with one, its activities are cancelled and the rest replanned.
    pub fn complete(
        &mut self,
        actual_end: SolSeconds,
        outcome: Option<String>,
        disruption: Option<Disruption>,
    ) {
        let Some(first) = self.remaining.steps.first().copied() else {
            return;
        };
        let start = SolSeconds::from_planner_s(first.start_s);
        let planned_end = SolSeconds::from_planner_s(first.end_s);
        let window_end = SolSeconds::from_planner_s(self.inst.problem().end_s);
        let end = actual_end.max(start + 1).min(window_end.max(start + 1));
        let end_s = end.planner_s();
        let name = self.inst.task(first.task).name.clone();
        let (state, repaired) = match repair(&self.inst, &self.state, &self.remaining, 0, end_s) {
            Ok(RepairOutcome::Repaired {
                state,
                plan,
                shifted,
            }) => {
                if shifted > 0 && disruption.is_none() {
                    self.changes.push(format!(
                        "{}: {name} ended {}: {shifted} later activities shifted",
                        end.lmst(),
                        slip(end, planned_end)
                    ));
                }
                (state, Some(plan))
            }
            Ok(RepairOutcome::ReplanNeeded {
                state,
                task,
                reason,
                ..
            }) => {
                if disruption.is_none() {
                    let reason = match reason {
                        planner::Blocker::MandatoryLost(t) => format!(
                            "it would make mandatory {} miss its window",
                            self.inst.task(t).name
                        ),
                        other => other.to_string(),
                    };
                    self.changes.push(format!(
                        "{}: {name} ended {}: {} no longer fits ({reason}): replanned",
                        end.lmst(),
                        slip(end, planned_end),
                        self.inst.task(task).name
                    ));
                }
                (state, None)
            }
            Err(e) => {
                // The step ran all the same: count it done at its end and replan from there.
                self.violations.push(format!("repair after {name}: {e}"));
                let mut state = self.state.clone();
                state.done.push(first.task);
                state.time_s = end_s;
                state.driven_m += self.inst.task(first.task).drive_m;
                (state, None)
            }
        };
        self.executed.push(PlanStep {
            task: first.task,
            start_s: first.start_s,
            end_s,
        });
        self.rows.push(TimelineStep {
            activity: name,
            start_lmst: start.lmst(),
            end_lmst: end.lmst(),
            start_s: start,
            end_s: end,
            timeline: self.inst.task(first.task).timeline,
            energy_wh_after: state.energy_wh,
            data_mb_after: state.data_mb,
            outcome,
        });
        self.state = state;
        match (disruption, repaired) {
            (None, Some(plan)) => {
                self.remaining = plan;
                self.validate("repaired");
            }
            (None, None) => self.replan(),
            (Some(d), _) => {
                let cancelled = self.cancel(&d.cancel);
                if let Some(m) = d.driven_m {
                    self.state.driven_m = m;
                }
                self.changes.push(format!(
                    "{}: {}{}: replanned",
                    end.lmst(),
                    d.reason,
                    if cancelled.is_empty() {
                        String::new()
                    } else {
                        format!(" (cancelled {})", cancelled.join(", "))
                    }
                ));
                self.replan();
            }
        }
    }

    /// A new goal is known now (autonomous science flagged a target): add it, and its
    /// campaign if the sol's problem lacks it, and replan from the current state.
    pub fn inject(&mut self, activity: Activity, campaign: Option<Campaign>, reason: &str) {
        let mut problem = self.inst.problem().clone();
        if let Some(c) = campaign
            && !problem.campaigns.iter().any(|o| o.id == c.id)
        {
            problem.campaigns.push(c);
        }
        let id = activity.id.clone();
        problem.activities.push(activity);
        // Appending keeps every existing task id, so the current state stays valid.
        match Instance::new(&problem) {
            Ok(inst) => {
                // On two timelines the state may lag behind the step about to run (a task of
                // the other timeline could still have started earlier): the goal is known at
                // that step's start, so nothing is planned before it.
                if inst.uses_link()
                    && let Some(next) = self.remaining.steps.first()
                    && let Ok(now) = self.state.advanced_to(&inst, next.start_s)
                {
                    self.state = now;
                }
                self.inst = inst;
                self.changes.push(format!(
                    "{}: {reason}: {id} added: replanned",
                    lmst(self.state.time_s)
                ));
                self.replan();
            }
            Err(e) => self.violations.push(format!("new goal {id}: {e}")),
        }
    }

    /// Mark every undone task of the activities `cancel` as done (dropped); their names.
    fn cancel(&mut self, cancel: &[String]) -> Vec<String> {
        let mut cancelled = Vec::new();
        for (i, t) in self.inst.tasks().iter().enumerate() {
            let id = TaskId(i as u32);
            if cancel.contains(&self.inst.problem().activities[t.activity].id)
                && !self.state.done.contains(&id)
            {
                self.state.done.push(id);
                cancelled.push(t.name.clone());
            }
        }
        cancelled
    }

    /// Replan from the current state. If nothing holding every mandatory activity fits, the
    /// drive window has closed on the rest of the drive (AutoNav stops at the window's end):
    /// cancel its remaining segments and replan once more.
    fn replan(&mut self) {
        let mut outcome = plan_from(&self.inst, &self.state, &self.settings);
        if let Ok(o) = &outcome
            && matches!(o.status, PlanStatus::Infeasible | PlanStatus::NoPlanFound)
        {
            let cancelled = self.cancel(&["drive".to_string()]);
            if !cancelled.is_empty() {
                self.changes.push(format!(
                    "{}: no plan fits the rest of the drive: cancelled {} and planned again",
                    lmst(self.state.time_s),
                    cancelled.join(", ")
                ));
                outcome = plan_from(&self.inst, &self.state, &self.settings);
            }
        }
        match outcome {
            Ok(o) => {
                if matches!(o.status, PlanStatus::Infeasible | PlanStatus::NoPlanFound) {
                    self.violations.push(format!(
                        "replan at {}: {}",
                        lmst(self.state.time_s),
                        SolPlanStatus::from(o.status)
                    ));
                }
                self.remaining = o.plan;
                self.validate("replanned");
            }
            Err(e) => {
                self.violations.push(format!("replan: {e}"));
                self.remaining = Plan::default();
            }
        }
    }

    /// The sol log's plan: the executed timeline, the repairs and replans, and any violation.
    #[must_use]
    pub fn finish(mut self) -> SolPlan {
        if self.inst.uses_link() {
            // A row's state is taken when the next activity may start, which on two
            // timelines can be before the row ends: re-simulate the executed timeline for
            // the battery when each row ended, overlaps included.
            let executed = Plan {
                steps: std::mem::take(&mut self.executed),
            };
            let energy = step_resources(&self.inst, &self.initial, &executed);
            for (row, r) in self.rows.iter_mut().zip(energy) {
                row.energy_wh_after = r.energy_wh_after;
            }
        }
        let mut violations = self.violations;
        if !self.remaining.steps.is_empty() {
            violations.push(format!(
                "not executed: {}",
                self.remaining.describe(&self.inst).join(", ")
            ));
        }
        SolPlan {
            status: self.status,
            timeline: self.rows,
            changes: self.changes,
            violations,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::operations::science::SolScience;
    use crate::operations::sol_plan::{ChainDurations, LOCALIZATION_CHAIN, planning_window};

    fn at(lmst: &str) -> SolSeconds {
        SolSeconds::parse_lmst(lmst).unwrap_or(SolSeconds::MIDNIGHT)
    }

    fn req(chain: bool) -> SolPlanRequest {
        SolPlanRequest {
            drive_start: at("11:30"),
            drive_end: at("14:05"),
            drive_rate_m_per_h: 100.0,
            downlink: Some(at("16:00")),
            panorama_on_pass: false,
            chain: chain.then_some(ChainDurations {
                transfer_s: 74,
                run_s: 32,
                reboot_s: 120,
            }),
            science: SolScience::default(),
        }
    }

    fn names(plan: &SolPlan) -> Vec<&str> {
        plan.timeline.iter().map(|s| s.activity.as_str()).collect()
    }

    /// Execute every step as planned, except `actual(step)` (a different end, a disruption).
    fn run(
        mut exec: SolExecution,
        mut actual: impl FnMut(&Step) -> Option<(SolSeconds, Option<Disruption>)>,
    ) -> SolPlan {
        let mut guard = 0;
        while let Some(step) = exec.next_step() {
            guard += 1;
            assert!(guard < 200, "runaway execution");
            let (end, d) = actual(&step).unwrap_or((step.end_s, None));
            exec.complete(end, None, d);
        }
        exec.finish()
    }

    #[test]
    fn onboard_sol_has_the_localization_chain_after_the_drive() {
        let p = SolPlanSettings::default();
        let plan = run(SolExecution::new(&p, &req(true)).expect("plans"), |_| None);
        assert_eq!(plan.status, SolPlanStatus::Optimal);
        assert!(plan.violations.is_empty(), "{:?}", plan.violations);
        let n = names(&plan);
        let pos = |name: &str| n.iter().position(|a| a.starts_with(name));
        assert!(pos("heating") < pos("drive"));
        assert!(pos("drive") < pos("post_drive_imaging"));
        for w in LOCALIZATION_CHAIN.windows(2) {
            assert!(pos(w[0]).is_some() && pos(w[0]) < pos(w[1]), "{n:?}");
        }
        assert!(pos("post_drive_imaging") < pos("sunfind"));
        assert!(n.contains(&"comm_pass"), "{n:?}");
        assert!(plan.changes.is_empty(), "{:?}", plan.changes);
    }

    #[test]
    fn an_early_drive_end_shifts_the_rest_and_stays_valid() {
        let p = SolPlanSettings::default();
        let early = at("12:10");
        let plan = run(SolExecution::new(&p, &req(true)).expect("plans"), |s| {
            (s.activity == "drive").then_some((early, None))
        });
        assert!(plan.violations.is_empty(), "{:?}", plan.violations);
        let imaging = plan
            .timeline
            .iter()
            .find(|s| s.activity == "post_drive_imaging")
            .expect("imaging");
        assert_eq!(imaging.start_s, early, "{plan:?}");
        assert_eq!(plan.changes.len(), 1, "{:?}", plan.changes);
        assert!(plan.changes[0].contains("shifted"), "{:?}", plan.changes);
        assert!(plan.timeline.iter().all(|s| s.energy_wh_after >= 0.0));
    }

    #[test]
    fn a_late_chain_step_is_fed_back_and_shifts_what_follows() {
        let p = SolPlanSettings::default();
        let mut planned_compare = SolSeconds::MIDNIGHT;
        let plan = run(SolExecution::new(&p, &req(true)).expect("plans"), |s| {
            if s.activity == "compare_apply" {
                planned_compare = s.start_s;
            }
            // The first co-processor run takes 5 minutes instead of 32 s.
            (s.activity == "hbs_run_1").then_some((s.start_s + 300, None))
        });
        assert!(plan.violations.is_empty(), "{:?}", plan.violations);
        let run1 = plan.timeline.iter().find(|s| s.activity == "hbs_run_1");
        assert_eq!(run1.map(|s| s.end_s - s.start_s), Some(300));
        let compare = plan.timeline.iter().find(|s| s.activity == "compare_apply");
        assert!(compare.is_some_and(|c| c.start_s == planned_compare));
        assert!(
            plan.changes.iter().any(|c| c.contains("hbs_run_1")),
            "{:?}",
            plan.changes
        );
    }

    #[test]
    fn a_fault_cancels_the_rest_of_the_drive_and_replans() {
        let p = SolPlanSettings::default();
        let mut r = req(true);
        r.science.split_at_m = vec![75.0, 150.0];
        let exec = SolExecution::new(&p, &r).expect("plans");
        let plan = run(exec, |s| {
            (s.segment == Some((0, 3))).then(|| {
                (
                    s.start_s + 600,
                    Some(Disruption {
                        reason: "NO_PATH after 16.7 m".into(),
                        cancel: vec!["drive".into()],
                        driven_m: Some(16.7),
                    }),
                )
            })
        });
        assert!(plan.violations.is_empty(), "{:?}", plan.violations);
        let n = names(&plan);
        assert_eq!(
            n.iter().filter(|a| a.starts_with("drive")).count(),
            1,
            "{n:?}"
        );
        assert!(
            n.contains(&"post_drive_imaging") && n.contains(&"compare_apply"),
            "{n:?}"
        );
        assert!(
            plan.changes
                .iter()
                .any(|c| c.contains("NO_PATH") && c.contains("drive#2/3")),
            "{:?}",
            plan.changes
        );
    }

    #[test]
    fn an_injected_goal_is_planned_from_the_current_state() {
        let p = SolPlanSettings::default();
        let mut exec = SolExecution::new(&p, &req(false)).expect("plans");
        // Run heating and the drive, then a target is revealed.
        for _ in 0..2 {
            let s = exec.next_step().expect("step");
            exec.complete(s.end_s, None, None);
        }
        let mut target = Activity::task("mastcam-new", 1_200, [0, 70_000], 35.0, 0.0);
        target.campaign = Some("outcrop".into());
        let campaign = Campaign {
            id: "outcrop".into(),
            intent: planner::CampaignIntent::GoalSet,
            tier: 1,
            min_count: 0,
            max_count: 1,
            utility: 10.0,
            decay: 1.0,
        };
        let window = planning_window(&p, req(false).drive_start, req(false).drive_end);
        target.earliest_start_s = window[0].planner_s();
        target.latest_start_s = window[1].planner_s() - 1_200;
        exec.inject(
            target,
            Some(campaign),
            "autonomous science flagged a target",
        );
        let plan = run(exec, |_| None);
        assert!(plan.violations.is_empty(), "{:?}", plan.violations);
        assert!(names(&plan).contains(&"mastcam-new"), "{:?}", names(&plan));
        assert!(plan.changes.iter().any(|c| c.contains("mastcam-new added")));
    }

    /// The flight-size transfer (30 min at 10 KB/s) holds the HBS link: the pass fixed inside
    /// it runs on the main timeline meanwhile, the runs wait for it, and the battery after
    /// each row counts both.
    #[test]
    fn the_transfer_runs_on_the_hbs_link_across_the_pass() {
        let p = SolPlanSettings::default();
        let mut r = req(true);
        r.chain = Some(ChainDurations {
            transfer_s: 1_800,
            run_s: 32,
            reboot_s: 120,
        });
        r.downlink = Some(at("14:50"));
        let plan = run(SolExecution::new(&p, &r).expect("plans"), |_| None);
        assert!(plan.violations.is_empty(), "{:?}", plan.violations);
        let row = |id: &str| {
            plan.timeline
                .iter()
                .find(|s| s.activity == id)
                .unwrap_or_else(|| panic!("{id}: {:?}", names(&plan)))
        };
        let (transfer, pass) = (row("hbs_transfer"), row("comm_pass"));
        assert_eq!(transfer.timeline, planner::Timeline::HbsLink);
        assert_eq!(pass.timeline, planner::Timeline::Main);
        assert_eq!(transfer.end_s - transfer.start_s, 1_800);
        assert!(pass.start_s < transfer.end_s && transfer.start_s < pass.end_s);
        assert_eq!(row("hbs_run_1").start_s, transfer.end_s);
        assert!(row("compare_apply").start_s >= row("hbs_run_2").end_s);
        // Rows in start order; the pass row's battery counts the transfer's draw too.
        assert!(
            plan.timeline
                .windows(2)
                .all(|w| w[0].start_s <= w[1].start_s)
        );
        let (e0, e1) = (row("sunfind").energy_wh_after, pass.energy_wh_after);
        let recharge_wh = p.recharge_w * (pass.end_s - row("sunfind").end_s) as f64 / 3600.0;
        let drawn_wh =
            (10.0 * 600.0 + p.hbs_power_w * (pass.end_s - transfer.start_s) as f64) / 3600.0;
        assert!(
            (e1 - (e0 + recharge_wh - drawn_wh)).abs() < 1e-6,
            "{e0} {e1}"
        );
    }

    #[test]
    fn ground_sol_has_no_chain() {
        let p = SolPlanSettings::default();
        let plan = run(SolExecution::new(&p, &req(false)).expect("plans"), |_| None);
        assert!(!names(&plan).contains(&"sunfind"));
        assert!(plan.violations.is_empty(), "{:?}", plan.violations);
    }
}
