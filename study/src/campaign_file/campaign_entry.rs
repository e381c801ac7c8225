//! `[[campaigns]]` entries → [`planner::Campaign`] plus the instance activities of periodic and
//! state-based campaigns ([`planner::periodic_instances`], [`planner::state_based_instances`]).

use planner::{Activity, Campaign, CampaignIntent};

use super::raw::{RawCampaign, RawTemplate};
use crate::check::{FieldCheck, lmst_of};
use crate::error::ScenarioError;
use crate::ranges;

fn template(
    c: &FieldCheck<'_>,
    f: &str,
    t: Option<&RawTemplate>,
    campaign_id: &str,
    activities: &[Activity],
) -> Result<Activity, ScenarioError> {
    let Some(t) = t else {
        return Err(c.err(
            &format!("{f}.template"),
            "a [campaigns.template] table (duration_min, power_w, ...) for the instances",
            "none",
        ));
    };
    let f = format!("{f}.template");
    let id = t.id.clone().unwrap_or_else(|| campaign_id.to_string());
    c.id(&format!("{f}.id"), &id)?;
    for (k, p) in t.preconditions.iter().enumerate() {
        if !activities.iter().any(|a| a.id == *p) {
            return Err(c.err(
                &format!("{f}.preconditions[{k}]"),
                "the id of an activity in [[activities]]",
                format!("{p:?}"),
            ));
        }
    }
    let mut a = task(c, &f, id, &t.name, t.duration_min, t.power_w, t.data_mb)?;
    a.preconditions = t.preconditions.clone();
    Ok(a)
}

/// A task activity from its fields at `{f}.duration_min`, `{f}.power_w` and `{f}.data_mb`
/// (checked; windows left at 0 for the caller to set).
pub(crate) fn task(
    c: &FieldCheck<'_>,
    f: &str,
    id: String,
    name: &str,
    duration_min: f64,
    power_w: f64,
    data_mb: Option<f64>,
) -> Result<Activity, ScenarioError> {
    c.text(&format!("{f}.name"), name)?;
    let mut a = Activity::task(
        id,
        c.minutes(&format!("{f}.duration_min"), duration_min)?,
        [0, 0],
        c.non_negative(&format!("{f}.power_w"), power_w, "watts")?,
        0.0,
    );
    a.name = name.to_string();
    a.data_mb = c.non_negative(&format!("{f}.data_mb"), data_mb.unwrap_or(0.0), "megabytes")?;
    Ok(a)
}

fn only_for(
    c: &FieldCheck<'_>,
    f: &str,
    intent: &str,
    fields: &[(&str, bool)],
) -> Result<(), ScenarioError> {
    for (name, present) in fields {
        if *present {
            return Err(c.err(
                &format!("{f}.{name}"),
                format!("no {name} in a {intent} campaign"),
                "a value",
            ));
        }
    }
    Ok(())
}

pub(crate) fn campaign(
    c: &FieldCheck<'_>,
    f: &str,
    rc: &RawCampaign,
    (start_s, end_s): (i64, i64),
    total_drive_m: f64,
    activities: &[Activity],
) -> Result<(Campaign, Vec<Activity>), ScenarioError> {
    let tier = c.tier(&format!("{f}.tier"), rc.tier)?;
    let utility = c.utility(&format!("{f}.utility"), rc.utility)?;
    let decay = rc.decay.unwrap_or(1.0);
    if !(decay.is_finite() && decay > 0.0 && decay <= 1.0) {
        return Err(c.err(&format!("{f}.decay"), "a factor 0 < decay <= 1", decay));
    }
    let count = |field: &str, v: Option<i64>| -> Result<Option<u32>, ScenarioError> {
        match v {
            None => Ok(None),
            Some(n) if (0..=i64::from(u32::MAX)).contains(&n) => Ok(Some(n as u32)),
            Some(n) => Err(c.err(&format!("{f}.{field}"), "a count >= 0", n)),
        }
    };
    let min_count = count("min_count", rc.min_count)?.unwrap_or(0);
    let max_count = count("max_count", rc.max_count)?;
    let periodic_fields = [
        ("period_min", rc.period_min.is_some()),
        ("tolerance_min", rc.tolerance_min.is_some()),
        ("first_due_lmst", rc.first_due_lmst.is_some()),
        ("until_lmst", rc.until_lmst.is_some()),
    ];
    let state_fields = [
        ("every_m", rc.every_m.is_some()),
        ("tolerance_m", rc.tolerance_m.is_some()),
    ];
    let (intent, instances) = match rc.intent.as_str() {
        "goal_set" => {
            only_for(c, f, "goal_set", &periodic_fields)?;
            only_for(c, f, "goal_set", &state_fields)?;
            only_for(c, f, "goal_set", &[("template", rc.template.is_some())])?;
            (CampaignIntent::GoalSet, Vec::new())
        }
        "periodic" => {
            only_for(c, f, "periodic", &state_fields)?;
            only_for(c, f, "periodic", &[("members", rc.members.is_some())])?;
            let need = |name: &str, v: Option<f64>| {
                v.ok_or_else(|| {
                    c.err(
                        &format!("{f}.{name}"),
                        "a value for a periodic campaign",
                        "none",
                    )
                })
            };
            let period_s = c.minutes(
                &format!("{f}.period_min"),
                need("period_min", rc.period_min)?,
            )?;
            let tol_min = need("tolerance_min", rc.tolerance_min)?;
            c.non_negative(&format!("{f}.tolerance_min"), tol_min, "minutes")?;
            let tolerance_s = (tol_min * 60.0).round() as i64;
            // Saturating: a tolerance of 1e300 min converts to i64::MAX seconds.
            if tolerance_s.saturating_mul(2) >= period_s {
                return Err(c.err(
                    &format!("{f}.tolerance_min"),
                    "less than half of period_min, so instances do not overlap",
                    tol_min,
                ));
            }
            let first_due = match &rc.first_due_lmst {
                Some(t) => c.lmst_s(&format!("{f}.first_due_lmst"), t)?,
                None => start_s + tolerance_s,
            };
            let until = match &rc.until_lmst {
                Some(t) => c.lmst_s(&format!("{f}.until_lmst"), t)?,
                None => end_s,
            };
            let tpl = template(c, f, rc.template.as_ref(), &rc.id, activities)?;
            // Clip each instance's window to the sol; drop instances left with none.
            let inst = planner::clip_to_window(
                planner::periodic_instances(&tpl, &rc.id, first_due, period_s, tolerance_s, until),
                start_s,
                end_s,
            );
            if inst.is_empty() {
                return Err(c.err(
                    &format!("{f}.first_due_lmst"),
                    format!(
                        "a due time whose ± tolerance window fits in the sol window {}..{}",
                        lmst_of(start_s),
                        lmst_of(end_s)
                    ),
                    format!("{:?}", lmst_of(first_due)),
                ));
            }
            (
                CampaignIntent::Periodic {
                    period_s,
                    tolerance_s,
                },
                inst,
            )
        }
        "state_based" => {
            only_for(c, f, "state_based", &periodic_fields)?;
            only_for(c, f, "state_based", &[("members", rc.members.is_some())])?;
            let every_m = c.range(
                ranges::CADENCE_M,
                &format!("{f}.every_m"),
                rc.every_m.ok_or_else(|| {
                    c.err(
                        &format!("{f}.every_m"),
                        "a value for a state_based campaign",
                        "none",
                    )
                })?,
            )?;
            let tolerance_m = c.range(
                ranges::CADENCE_TOLERANCE_M,
                &format!("{f}.tolerance_m"),
                rc.tolerance_m.unwrap_or(0.0),
            )?;
            let mut tpl = template(c, f, rc.template.as_ref(), &rc.id, activities)?;
            tpl.earliest_start_s = start_s;
            tpl.latest_start_s = end_s - tpl.duration_s();
            if tpl.latest_start_s < start_s {
                return Err(c.err(
                    &format!("{f}.template.duration_min"),
                    "a duration that fits in the sol window",
                    tpl.duration_s() as f64 / 60.0,
                ));
            }
            // Bound the instance count before building them (a planner instance holds at most
            // MAX_TASKS tasks anyway).
            if total_drive_m / every_m > planner::MAX_TASKS as f64 {
                return Err(c.err(
                    &format!("{f}.every_m"),
                    format!(
                        "a cadence giving at most {} instances over the {total_drive_m} m of drives",
                        planner::MAX_TASKS
                    ),
                    every_m,
                ));
            }
            let inst =
                planner::state_based_instances(&tpl, &rc.id, every_m, tolerance_m, total_drive_m);
            (
                CampaignIntent::StateBased {
                    every_m,
                    tolerance_m,
                },
                inst,
            )
        }
        other => {
            return Err(c.err(
                &format!("{f}.intent"),
                "one of \"goal_set\", \"periodic\", \"state_based\"",
                format!("{other:?}"),
            ));
        }
    };
    let max_count = match max_count {
        Some(0) => return Err(c.err(&format!("{f}.max_count"), "a count >= 1", 0)),
        Some(m) => m,
        None => match &intent {
            CampaignIntent::GoalSet => {
                let listed = rc.members.as_ref().map_or(0, Vec::len);
                let named = activities
                    .iter()
                    .filter(|a| a.campaign.as_deref() == Some(rc.id.as_str()))
                    .count();
                listed.max(named).max(1) as u32
            }
            _ => instances.len().max(1) as u32,
        },
    };
    if min_count > max_count {
        return Err(c.err(
            &format!("{f}.min_count"),
            format!("at most max_count = {max_count}"),
            min_count,
        ));
    }
    Ok((
        Campaign {
            id: rc.id.clone(),
            intent,
            tier,
            min_count,
            max_count,
            utility,
            decay,
        },
        instances,
    ))
}
