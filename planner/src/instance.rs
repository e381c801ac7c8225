//! A validated [`Problem`] with drives split into segments: the form the search, the
//! validator and repair work on.
//!
//! Every activity becomes one [`Task`], except a drive, which becomes a chain of segment
//! tasks (each a precondition of the next). Tasks are named by [`TaskId`] handles.

use crate::curve::CampaignCurve;
use crate::error::PlanError;
use crate::instance_checks::{campaign_curve, check_activity, check_problem, find_cycle};
use crate::problem::{ActivityKind, Problem, Timeline};
use crate::value::{MAX_TASKS, micro};

/// Handle of a [`Task`] in an [`Instance`] (its index).
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize, serde::Deserialize,
)]
pub struct TaskId(pub u32);

impl TaskId {
    /// The index into [`Instance::tasks`].
    #[must_use]
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// One schedulable unit: an activity, or one segment of a drive.
#[derive(Debug, Clone, PartialEq)]
pub struct Task {
    /// Activity id, with `#j/k` appended for segment `j` (1-based) of a `k`-segment drive.
    pub name: String,
    /// Index of the source activity in [`Problem::activities`].
    pub activity: usize,
    /// `(j, k)`: segment `j` (0-based) of `k`, for drives.
    pub segment: Option<(u32, u32)>,
    /// Duration, s (> 0).
    pub duration_s: i64,
    /// Earliest start, s after midnight.
    pub earliest_start_s: i64,
    /// Latest start, s after midnight.
    pub latest_start_s: i64,
    /// Power above idle, W.
    pub power_w: f64,
    /// Data produced at the end, MB.
    pub data_mb: f64,
    /// Data downlinked at the end (after `data_mb` is added), MB.
    pub downlink_mb: f64,
    /// Tasks that must end before this one starts.
    pub preconditions: Vec<TaskId>,
    /// Must be in every plan.
    pub mandatory: bool,
    /// Tier index of `utility_micro` (0 is tier 1).
    pub tier: usize,
    /// Own utility, micro-points.
    pub utility_micro: i64,
    /// Index into [`Instance::campaigns`] of the campaign this task counts towards.
    pub campaign: Option<usize>,
    /// Metres driven by this task (drive segments only).
    pub drive_m: f64,
    /// State-based window on metres driven at the start.
    pub driven_window_m: Option<[f64; 2]>,
    /// The timeline(s) it holds.
    pub timeline: Timeline,
}

impl Task {
    /// Energy drawn above idle, `power_w × duration_s / 3600`.
    ///
    /// # Units
    /// Wh.
    #[must_use]
    pub fn energy_wh(&self) -> f64 {
        self.power_w * self.duration_s as f64 / 3600.0
    }
}

/// A validated, drive-split problem.
#[derive(Debug, Clone, PartialEq)]
pub struct Instance {
    problem: Problem,
    tasks: Vec<Task>,
    campaigns: Vec<CampaignCurve>,
    /// `activity_tasks[a]` = the tasks of activity `a`, in order.
    activity_tasks: Vec<Vec<TaskId>>,
    /// The mandatory tasks.
    mandatory: Vec<TaskId>,
    /// Whether any task holds the HBS link (otherwise every task is on the main timeline and
    /// the single-timeline rules apply unchanged).
    uses_link: bool,
    /// Every task, each after its preconditions.
    topo: Vec<TaskId>,
}

impl Instance {
    /// Validate `problem` and split its drives.
    ///
    /// # Errors
    /// A [`PlanError`] naming the first activity, campaign or field that is malformed.
    pub fn new(problem: &Problem) -> Result<Self, PlanError> {
        check_problem(problem)?;
        let mut campaigns = Vec::with_capacity(problem.campaigns.len());
        for (i, c) in problem.campaigns.iter().enumerate() {
            if problem.campaigns[..i].iter().any(|o| o.id == c.id) {
                return Err(PlanError::DuplicateId {
                    id: c.id.clone(),
                    field: "campaigns",
                });
            }
            campaigns.push(campaign_curve(c)?);
        }
        for (i, a) in problem.activities.iter().enumerate() {
            if problem.activities[..i].iter().any(|o| o.id == a.id) {
                return Err(PlanError::DuplicateId {
                    id: a.id.clone(),
                    field: "activities",
                });
            }
            check_activity(problem, a)?;
        }
        let index_of = |id: &str| problem.activities.iter().position(|a| a.id == id);
        // Preconditions must name known activities and form no cycle.
        let mut pre_idx: Vec<Vec<usize>> = Vec::with_capacity(problem.activities.len());
        for a in &problem.activities {
            let mut v = Vec::with_capacity(a.preconditions.len());
            for p in &a.preconditions {
                match index_of(p) {
                    Some(j) if problem.activities[j].id != a.id => v.push(j),
                    Some(_) => {
                        return Err(PlanError::PreconditionCycle {
                            activity: a.id.clone(),
                        });
                    }
                    None => {
                        return Err(PlanError::UnknownPrecondition {
                            activity: a.id.clone(),
                            precondition: p.clone(),
                        });
                    }
                }
            }
            pre_idx.push(v);
        }
        if let Some(a) = find_cycle(&pre_idx) {
            return Err(PlanError::PreconditionCycle {
                activity: problem.activities[a].id.clone(),
            });
        }
        let mut campaign_idx = Vec::with_capacity(problem.activities.len());
        for a in &problem.activities {
            campaign_idx.push(match &a.campaign {
                None => None,
                Some(c) => Some(
                    problem
                        .campaigns
                        .iter()
                        .position(|x| &x.id == c)
                        .ok_or_else(|| PlanError::UnknownCampaign {
                            activity: a.id.clone(),
                            campaign: c.clone(),
                        })?,
                ),
            });
        }

        // Split drives. Ids are assigned first so preconditions can refer forward.
        let mut activity_tasks = Vec::with_capacity(problem.activities.len());
        let mut next = 0u32;
        for a in &problem.activities {
            let k = match &a.kind {
                ActivityKind::Task { .. } => 1,
                ActivityKind::Drive(d) => d.boundaries_m().len() as u32 - 1,
            };
            activity_tasks.push((next..next + k).map(TaskId).collect::<Vec<_>>());
            next += k;
        }
        if next as usize > MAX_TASKS {
            return Err(PlanError::TooManyTasks {
                count: next as usize,
                max: MAX_TASKS,
            });
        }
        let mut tasks = Vec::with_capacity(next as usize);
        for (ai, a) in problem.activities.iter().enumerate() {
            let pre: Vec<TaskId> = pre_idx[ai]
                .iter()
                .filter_map(|&j| activity_tasks[j].last().copied())
                .collect();
            let base = Task {
                name: a.id.clone(),
                activity: ai,
                segment: None,
                duration_s: a.duration_s(),
                earliest_start_s: a.earliest_start_s,
                latest_start_s: a.latest_start_s,
                power_w: a.power_w,
                data_mb: a.data_mb,
                downlink_mb: a.downlink_mb,
                preconditions: pre,
                mandatory: a.mandatory,
                tier: usize::from(a.tier - 1),
                utility_micro: micro(a.utility),
                campaign: campaign_idx[ai],
                drive_m: 0.0,
                driven_window_m: a.driven_window_m,
                timeline: a.timeline,
            };
            match &a.kind {
                ActivityKind::Task { .. } => tasks.push(base),
                ActivityKind::Drive(d) => {
                    let b = d.boundaries_m();
                    let k = b.len() - 1;
                    let total_s = d.duration_s() as f64;
                    let total_u = base.utility_micro as f64;
                    let at_s = |m: f64| (total_s * m / d.length_m).round() as i64;
                    let at_u = |m: f64| (total_u * m / d.length_m).round() as i64;
                    for j in 0..k {
                        let mut t = base.clone();
                        t.name = format!("{}#{}/{}", a.id, j + 1, k);
                        t.segment = Some((j as u32, k as u32));
                        t.duration_s = (at_s(b[j + 1]) - at_s(b[j])).max(1);
                        t.utility_micro = at_u(b[j + 1]) - at_u(b[j]);
                        let frac = (b[j + 1] - b[j]) / d.length_m;
                        t.data_mb = a.data_mb * frac;
                        t.downlink_mb = a.downlink_mb * frac;
                        t.drive_m = b[j + 1] - b[j];
                        let end_by = d.latest_end_s.unwrap_or(problem.end_s).min(problem.end_s);
                        if j > 0 {
                            t.preconditions = vec![activity_tasks[ai][j - 1]];
                            t.latest_start_s = (end_by - t.duration_s).max(a.earliest_start_s);
                            t.driven_window_m = None;
                        } else {
                            t.latest_start_s = t
                                .latest_start_s
                                .min(end_by - t.duration_s)
                                .max(a.earliest_start_s);
                        }
                        // The drive counts once towards its campaign, when it completes.
                        if j + 1 < k {
                            t.campaign = None;
                        }
                        tasks.push(t);
                    }
                }
            }
        }
        let mandatory = (0..tasks.len() as u32)
            .map(TaskId)
            .filter(|t| tasks[t.index()].mandatory)
            .collect();
        let uses_link = tasks.iter().any(|t| t.timeline.uses_link());
        let topo = topological_order(&tasks);
        Ok(Self {
            problem: problem.clone(),
            tasks,
            campaigns,
            activity_tasks,
            mandatory,
            uses_link,
            topo,
        })
    }

    /// The problem this instance was built from.
    #[must_use]
    pub fn problem(&self) -> &Problem {
        &self.problem
    }

    /// All tasks; a [`TaskId`] indexes this slice.
    #[must_use]
    pub fn tasks(&self) -> &[Task] {
        &self.tasks
    }

    /// One task.
    ///
    /// # Panics
    /// If `id` is not a task of this instance.
    #[must_use]
    pub fn task(&self, id: TaskId) -> &Task {
        &self.tasks[id.index()]
    }

    /// The campaigns' resolved utility curves, in [`Problem::campaigns`] order.
    #[must_use]
    pub fn campaigns(&self) -> &[CampaignCurve] {
        &self.campaigns
    }

    /// The tasks of activity `activity` (one, or a drive's segments in order).
    ///
    /// # Panics
    /// If `activity` is out of range.
    #[must_use]
    pub fn activity_tasks(&self, activity: usize) -> &[TaskId] {
        &self.activity_tasks[activity]
    }

    /// Whether any task holds the HBS link ([`Timeline::HbsLink`] or
    /// [`Timeline::MainAndHbsLink`]). When none does, every rule is the single timeline's.
    #[must_use]
    pub fn uses_link(&self) -> bool {
        self.uses_link
    }

    /// Every task, each after its preconditions (the precondition graph is acyclic).
    pub(crate) fn topological_order(&self) -> &[TaskId] {
        &self.topo
    }

    /// The mandatory tasks, in id order.
    #[must_use]
    pub fn mandatory_tasks(&self) -> &[TaskId] {
        &self.mandatory
    }
}

/// Every task, each after its preconditions (Kahn's algorithm; ties by id). Preconditions
/// form no cycle (checked before the drives are split; a split drive is a chain).
fn topological_order(tasks: &[Task]) -> Vec<TaskId> {
    let n = tasks.len();
    let mut waiting: Vec<usize> = tasks.iter().map(|t| t.preconditions.len()).collect();
    let mut successors: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (i, t) in tasks.iter().enumerate() {
        for q in &t.preconditions {
            successors[q.index()].push(i);
        }
    }
    let mut ready: std::collections::BTreeSet<usize> =
        (0..n).filter(|&i| waiting[i] == 0).collect();
    let mut out = Vec::with_capacity(n);
    while let Some(i) = ready.pop_first() {
        out.push(TaskId(i as u32));
        for &j in &successors[i] {
            waiting[j] -= 1;
            if waiting[j] == 0 {
                ready.insert(j);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use crate::instance_checks::campaign_curve;
    use crate::problem::{Activity, Campaign, CampaignIntent, Drive};

    fn problem(activities: Vec<Activity>) -> Problem {
        Problem {
            start_s: 0,
            end_s: 36_000,
            battery_capacity_wh: 100.0,
            initial_energy_wh: 50.0,
            recharge_w: 10.0,
            data_capacity_mb: 100.0,
            initial_data_mb: 0.0,
            activities,
            campaigns: Vec::new(),
        }
    }

    #[test]
    fn empty_problem_is_valid() {
        let inst = Instance::new(&problem(Vec::new())).unwrap();
        assert!(inst.tasks().is_empty() && inst.mandatory_tasks().is_empty());
    }

    #[test]
    fn drive_split_preserves_duration_distance_and_utility() {
        let mut d = Activity::task("d", 0, [0, 1000], 40.0, 7.0);
        d.kind = ActivityKind::Drive(Drive {
            length_m: 100.0,
            rate_m_per_h: 70.0,
            min_segment_s: 1000,
            max_segments: 4,
            split_at_m: Vec::new(),
            latest_end_s: None,
        });
        let mut after = Activity::task("after", 60, [0, 30_000], 1.0, 1.0);
        after.preconditions = vec!["d".into()];
        let inst = Instance::new(&problem(vec![d, after])).unwrap();
        let segs = inst.activity_tasks(0);
        assert_eq!(segs.len(), 4);
        let total_s: i64 = segs.iter().map(|&t| inst.task(t).duration_s).sum();
        assert_eq!(total_s, (3600.0f64 * 100.0 / 70.0).ceil() as i64);
        let total_m: f64 = segs.iter().map(|&t| inst.task(t).drive_m).sum();
        assert!((total_m - 100.0).abs() < 1e-9);
        let total_u: i64 = segs.iter().map(|&t| inst.task(t).utility_micro).sum();
        assert_eq!(total_u, 7_000_000);
        // Segments chain, and a successor waits for the last one.
        assert_eq!(inst.task(segs[2]).preconditions, vec![segs[1]]);
        assert_eq!(inst.task(TaskId(4)).preconditions, vec![segs[3]]);
    }

    #[test]
    fn a_drive_window_end_bounds_every_segment() {
        let drive = |latest_end_s| {
            let mut d = Activity::task("d", 0, [1000, 5000], 40.0, 7.0);
            d.kind = ActivityKind::Drive(Drive {
                length_m: 100.0,
                rate_m_per_h: 100.0,
                min_segment_s: 1,
                max_segments: 4,
                split_at_m: vec![25.0, 50.0, 75.0],
                latest_end_s,
            });
            d
        };
        let inst = Instance::new(&problem(vec![drive(Some(8000))])).unwrap();
        let segs = inst.activity_tasks(0);
        // The first segment keeps its own window; the later ones end by 8000 s.
        assert_eq!(inst.task(segs[0]).latest_start_s, 5000);
        for &t in &segs[1..] {
            let t = inst.task(t);
            assert_eq!(t.latest_start_s + t.duration_s, 8000, "{}", t.name);
        }
        // ... unless the window end is tighter than the first segment's own window.
        let inst = Instance::new(&problem(vec![drive(Some(5500))])).unwrap();
        assert_eq!(inst.task(inst.activity_tasks(0)[0]).latest_start_s, 4600);
        // 3600 s of driving cannot end by 4000 s when it starts at 1000 s at the earliest.
        let e = Instance::new(&problem(vec![drive(Some(4000))])).unwrap_err();
        assert!(e.to_string().contains("latest_end_s"), "{e}");
    }

    #[test]
    fn campaign_curve_saturates_and_its_slope_is_admissible() {
        let c = Campaign {
            id: "c".into(),
            intent: CampaignIntent::GoalSet,
            tier: 1,
            min_count: 2,
            max_count: 4,
            utility: 3.0,
            decay: 0.5,
        };
        let curve = campaign_curve(&c).unwrap();
        assert_eq!(
            curve.utility_micro,
            vec![0, 0, 4_500_000, 5_250_000, 5_625_000]
        );
        assert_eq!(curve.utility(9), 5_625_000);
        for n in 0..6 {
            let s = curve.optimistic_slope(n);
            for m in 0..6 {
                let gain = (curve.utility(n + m) - curve.utility(n)) as f64;
                assert!(gain <= s * f64::from(m) + 1e-9, "n {n} m {m}");
            }
        }
        assert_eq!(curve.remaining_cap(3), 1);
        assert_eq!(curve.remaining_cap(7), 0);
    }

    #[test]
    fn self_precondition_is_a_cycle() {
        let mut a = Activity::task("a", 60, [0, 100], 1.0, 1.0);
        a.preconditions = vec!["a".into()];
        assert_eq!(
            Instance::new(&problem(vec![a])).unwrap_err(),
            PlanError::PreconditionCycle {
                activity: "a".into()
            }
        );
    }
}
