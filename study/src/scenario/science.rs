//! A simulator scenario's `[science]` section → [`sim::operations::science::Science`].
//!
//! Targets are goal-set observations at map positions; `[[science.campaigns]]` use the
//! campaign-file schema (`intent = "goal_set" | "periodic" | "state_based"`) and are checked
//! by the same code as `solsim plan` files. The simulator builds each sol's instances itself,
//! so a periodic campaign needs `first_due_lmst` (the first due time of every sol) and takes
//! no `until_lmst` (each sol's window bounds it), and the goal set lists no `members`: every
//! target counts towards it.

use std::path::Path;

use planner::{Activity, CampaignIntent};
use sim::operations::science::{Periodic, Science, StateBased, Target};
use sim::operations::sol_plan::SOL_ACTIVITIES;
use sim::time::SolSeconds;

use crate::campaign_file::raw::{RawCampaign, RawScience};
use crate::campaign_file::{campaign, task};
use crate::check::FieldCheck;
use crate::error::ScenarioError;
use crate::ranges;

/// Validate `[science]`; `on_map(p)` says whether a position is on the map, `extent` how to
/// say where the map is.
///
/// # Errors
/// A [`ScenarioError`] naming the file and the first `science.…` field at fault.
pub(crate) fn resolve_science(
    path: &Path,
    raw: &RawScience,
    on_map: &dyn Fn([f64; 2]) -> bool,
    extent: &str,
) -> Result<Science, ScenarioError> {
    let c = FieldCheck { path };
    let mut science = Science::default();
    for (i, t) in raw.targets.iter().enumerate() {
        let f = format!("science.targets[{i}]");
        c.id(&format!("{f}.id"), &t.id)?;
        if raw.targets[..i].iter().any(|o| o.id == t.id) {
            return Err(c.err(
                &format!("{f}.id"),
                "an id no other target uses",
                format!("{:?}", t.id),
            ));
        }
        not_reserved(&c, &format!("{f}.id"), &t.id)?;
        let [x, y] = t.position_m.0;
        if !(x.is_finite() && y.is_finite() && on_map(t.position_m.0)) {
            return Err(c.err(
                &format!("{f}.position_m"),
                format!("a point on the map ({extent})"),
                format!("[{x}, {y}]"),
            ));
        }
        let a = task(
            &c,
            &f,
            t.id.clone(),
            &t.name,
            t.duration_min,
            t.power_w,
            t.data_mb,
        )?;
        let revealed = match (t.revealed_sol, &t.revealed_lmst) {
            (None, None) => None,
            (Some(sol), Some(lmst)) => Some((sol, c.lmst(&format!("{f}.revealed_lmst"), lmst)?)),
            (Some(_), None) => {
                return Err(c.err(
                    &format!("{f}.revealed_lmst"),
                    "the time of the reveal, \"HH:MM\" LMST (with revealed_sol)",
                    "none",
                ));
            }
            (None, Some(_)) => {
                return Err(c.err(
                    &format!("{f}.revealed_sol"),
                    "the sol of the reveal (with revealed_lmst)",
                    "none",
                ));
            }
        };
        science.targets.push(Target {
            activity: a,
            position_m: t.position_m.0,
            within_m: c.range(ranges::WITHIN_M, &format!("{f}.within_m"), t.within_m)?,
            revealed,
        });
    }
    let targets: Vec<Activity> = science.targets.iter().map(|t| t.activity.clone()).collect();
    for (j, rc) in raw.campaigns.iter().enumerate() {
        let f = format!("science.campaigns[{j}]");
        c.id(&format!("{f}.id"), &rc.id)?;
        if raw.campaigns[..j].iter().any(|o| o.id == rc.id) {
            return Err(c.err(
                &format!("{f}.id"),
                "an id no other campaign uses",
                format!("{:?}", rc.id),
            ));
        }
        if rc.members.is_some() {
            return Err(c.err(
                &format!("{f}.members"),
                "no members: every [[science.targets]] counts towards the goal set",
                "a list",
            ));
        }
        if rc.until_lmst.is_some() {
            return Err(c.err(
                &format!("{f}.until_lmst"),
                "no until_lmst: each sol's planning window bounds a periodic campaign",
                "a value",
            ));
        }
        if let Some(t) = &rc.template
            && !t.preconditions.is_empty()
        {
            return Err(c.err(
                &format!("{f}.template.preconditions"),
                "none: a science instance may run whenever its window allows",
                format!("{:?}", t.preconditions),
            ));
        }
        if matches!(rc.intent.as_str(), "periodic" | "state_based") {
            for (name, given) in [
                ("min_count", rc.min_count.is_some()),
                ("max_count", rc.max_count.is_some()),
            ] {
                if given {
                    return Err(c.err(
                        &format!("{f}.{name}"),
                        "none: a periodic or state-based campaign counts every instance a sol offers",
                        "a value",
                    ));
                }
            }
        }
        if rc.intent == "periodic" && rc.first_due_lmst.is_none() {
            return Err(c.err(
                &format!("{f}.first_due_lmst"),
                "the first due time of every sol, \"HH:MM\" LMST",
                "none",
            ));
        }
        // The campaign-file checks, over a whole sol and one cadence of driving.
        let one_cadence_m = rc.every_m.unwrap_or(1.0);
        let whole_sol = (
            SolSeconds::MIDNIGHT.planner_s(),
            SolSeconds::END_OF_SOL.planner_s(),
        );
        let (mut campaign, instances) = campaign(&c, &f, rc, whole_sol, one_cadence_m, &targets)?;
        match campaign.intent {
            CampaignIntent::GoalSet => {
                if science.goal_set.is_some() {
                    return Err(c.err(
                        &format!("{f}.intent"),
                        "at most one goal_set campaign (the targets' campaign)",
                        "a second goal_set",
                    ));
                }
                if rc.max_count.is_none() {
                    campaign.max_count = science.targets.len().max(1) as u32;
                }
                science.goal_set = Some(campaign);
            }
            CampaignIntent::Periodic { .. } => {
                let first_due = rc
                    .first_due_lmst
                    .as_deref()
                    .map_or(Ok(SolSeconds::MIDNIGHT), |t| {
                        c.lmst(&format!("{f}.first_due_lmst"), t)
                    })?;
                if let Some(template) = template_of(&c, &f, rc, instances)? {
                    science.periodic.push(Periodic {
                        campaign,
                        first_due,
                        template,
                    });
                }
            }
            CampaignIntent::StateBased { .. } => {
                if let Some(template) = template_of(&c, &f, rc, instances)? {
                    science.state_based.push(StateBased { campaign, template });
                }
            }
        }
    }
    if !science.targets.is_empty() && science.goal_set.is_none() {
        return Err(c.err(
            "science.campaigns",
            "a goal_set campaign for the [[science.targets]] (tier, utility, counts)",
            "none",
        ));
    }
    Ok(science)
}

/// The instance template back from the first checked instance: its own id, no campaign and no
/// window (the simulator sets those each sol).
fn template_of(
    c: &FieldCheck<'_>,
    f: &str,
    rc: &RawCampaign,
    instances: Vec<Activity>,
) -> Result<Option<Activity>, ScenarioError> {
    let Some(mut template) = instances.into_iter().next() else {
        return Ok(None);
    };
    template.id = rc
        .template
        .as_ref()
        .and_then(|t| t.id.clone())
        .unwrap_or_else(|| rc.id.clone());
    template.campaign = None;
    template.driven_window_m = None;
    not_reserved(c, &format!("{f}.template.id"), &template.id)?;
    Ok(Some(template))
}

/// `id` is not one of the sol plan's own activity ids ([`SOL_ACTIVITIES`]).
fn not_reserved(c: &FieldCheck<'_>, field: &str, id: &str) -> Result<(), ScenarioError> {
    if SOL_ACTIVITIES.contains(&id) {
        return Err(c.err(
            field,
            format!(
                "an id not used by the sol's own activities ({})",
                SOL_ACTIVITIES.join(", ")
            ),
            format!("{id:?}"),
        ));
    }
    Ok(())
}
