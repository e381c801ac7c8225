//! `[operations]`: the daily drive window (the calendar's), the post-drive
//! imaging (the sol plan's [`SolPlanSettings::imaging_s`], checked by
//! [`SolPlanSettings::validate`]) and the planners' rules ([`OperationsRules`], checked by
//! [`OperationsRules::validate`]).

use sim::operations::calendar::Calendar;
use sim::operations::policy::OperationsRules;
use sim::operations::sol_plan::SolPlanSettings;
use sim::time::SolSeconds;

use super::raw::RawOperations;
use crate::check::FieldCheck;
use crate::error::ScenarioError;

/// The daily drive window when the file gives none, LMST.
const DEFAULT_DRIVE_WINDOW: (&str, &str) = ("11:00", "15:00");

/// The file's name of a calendar field `[operations]` sets: the drive window's start or end.
pub(crate) fn drive_window_path(field: &str) -> Option<String> {
    match field {
        "drive_start" | "drive_end" => Some(format!("operations.{field}_lmst")),
        _ => None,
    }
}

/// The daily drive window, start and end: the calendar's, checked by
/// [`Calendar::validate_drive_window`].
///
/// # Errors
/// A [`ScenarioError`] naming `operations.drive_start_lmst` or `drive_end_lmst` when it is
/// not a time of the sol, or the end when it is not after the start.
pub(crate) fn drive_window(
    c: &FieldCheck<'_>,
    ops: &RawOperations,
) -> Result<(SolSeconds, SolSeconds), ScenarioError> {
    let (start, end) = DEFAULT_DRIVE_WINDOW;
    let start = c.lmst(
        "operations.drive_start_lmst",
        ops.drive_start_lmst.as_deref().unwrap_or(start),
    )?;
    let end = c.lmst(
        "operations.drive_end_lmst",
        ops.drive_end_lmst.as_deref().unwrap_or(end),
    )?;
    Calendar::validate_drive_window(start, end).map_err(|e| {
        c.setting(e, |f| {
            drive_window_path(f).unwrap_or_else(|| format!("operations.{f}"))
        })
    })?;
    Ok((start, end))
}

/// Each drive sol's plan settings: the post-drive imaging `post_drive_imaging_s` sets, the
/// defaults otherwise.
///
/// # Errors
/// A [`ScenarioError`] naming `operations.post_drive_imaging_s` when it lasts more than a sol.
pub(crate) fn sol_plan(
    c: &FieldCheck<'_>,
    ops: &RawOperations,
) -> Result<SolPlanSettings, ScenarioError> {
    let d = SolPlanSettings::default();
    let sol_plan = SolPlanSettings {
        imaging_s: ops.post_drive_imaging_s.map_or(d.imaging_s, i64::from),
        ..d
    };
    sol_plan.validate().map_err(|e| {
        // The file sets only the imaging; the other durations keep their defaults.
        c.setting(e, |f| match f {
            "imaging_s" => "operations.post_drive_imaging_s".to_owned(),
            other => format!("sol_plan.{other}"),
        })
    })?;
    Ok(sol_plan)
}

/// The operations rules every strategy plans under.
///
/// # Errors
/// A [`ScenarioError`] naming the first `operations.…` rule at fault.
pub(crate) fn rules(
    c: &FieldCheck<'_>,
    ops: &RawOperations,
) -> Result<OperationsRules, ScenarioError> {
    let d = OperationsRules::default();
    let rules = OperationsRules {
        max_extension_sols: ops.max_extension_sols,
        max_drive_sols_per_plan: ops
            .max_drive_sols_per_plan
            .unwrap_or(d.max_drive_sols_per_plan),
        extension_plan_sols: ops.extension_plan_sols.unwrap_or(d.extension_plan_sols),
        passage_margin_m: ops.passage_margin_m.unwrap_or(d.passage_margin_m),
        preemptive_shortening: ops.preemptive_shortening.unwrap_or(d.preemptive_shortening),
        ground_extension_sols: ops.ground_extension_sols.unwrap_or(d.ground_extension_sols),
        ground_lookahead_plans: ops
            .ground_lookahead_plans
            .unwrap_or(d.ground_lookahead_plans),
    };
    rules
        .validate()
        .map_err(|e| c.setting(e, |f| format!("operations.{f}")))?;
    Ok(rules)
}
