//! The one error type of the planner: a malformed [`Problem`](crate::Problem) or start
//! [`State`](crate::State).
//!
//! A goal that does not fit is not an error: it is reported as data in
//! [`PlanStatus`](crate::PlanStatus).

use thiserror::Error;

/// Why a problem (or a replanning state) was rejected before any search ran.
///
/// Every variant names the activity, campaign or field at fault, the value found and what was
/// expected, so the operator can fix the input.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum PlanError {
    /// A problem-level number is out of range (NaN, negative, or inconsistent).
    #[error("problem field `{field}` = {value}: expected {expected}")]
    InvalidProblem {
        /// Field name, e.g. `battery_capacity_wh`.
        field: &'static str,
        /// The value found.
        value: f64,
        /// What a valid value looks like.
        expected: &'static str,
    },
    /// An activity field is out of range (a negative duration, a NaN power, a tier of 0, ...).
    #[error("activity `{activity}` field `{field}` = {value}: expected {expected}")]
    InvalidActivity {
        /// The activity id.
        activity: String,
        /// Field name, e.g. `duration_s`.
        field: &'static str,
        /// The value found.
        value: f64,
        /// What a valid value looks like.
        expected: &'static str,
    },
    /// An activity on the `hbs_link` timeline alone has a field only main-timeline activities
    /// may have (see [`Timeline`](crate::Timeline)): a drive, data, a downlink or a
    /// state-based window. `main_and_hbs_link` allows them.
    #[error(
        "activity `{activity}` is on the hbs_link timeline: field `{field}` must be {expected} (or use timeline main_and_hbs_link)"
    )]
    InvalidLinkActivity {
        /// The activity id.
        activity: String,
        /// Field at fault, e.g. `data_mb`.
        field: &'static str,
        /// What a link activity has instead.
        expected: &'static str,
    },
    /// `latest_start_s` is before `earliest_start_s`.
    #[error(
        "activity `{activity}`: latest_start_s = {latest_start_s} is before earliest_start_s = {earliest_start_s}"
    )]
    ImpossibleWindow {
        /// The activity id.
        activity: String,
        /// The earliest start found (s after midnight).
        earliest_start_s: i64,
        /// The latest start found (s after midnight).
        latest_start_s: i64,
    },
    /// An activity cannot run inside the sol window `[start_s, end_s]`.
    #[error(
        "activity `{activity}` field `{field}` = {value_s} s puts it outside the sol window [{start_s}, {end_s}] s"
    )]
    OutsideSol {
        /// The activity id.
        activity: String,
        /// Field at fault, `earliest_start_s` or `latest_start_s`.
        field: &'static str,
        /// The value found (s after midnight; for `latest_start_s` the start plus the duration
        /// must also end by `end_s`).
        value_s: i64,
        /// Sol window start (s after midnight).
        start_s: i64,
        /// Sol window end (s after midnight).
        end_s: i64,
    },
    /// Two activities (or two campaigns) share one id.
    #[error("duplicate id `{id}` in `{field}`")]
    DuplicateId {
        /// The repeated id.
        id: String,
        /// `activities` or `campaigns`.
        field: &'static str,
    },
    /// A precondition names an activity that does not exist.
    #[error("activity `{activity}` field `preconditions` names unknown activity `{precondition}`")]
    UnknownPrecondition {
        /// The activity whose precondition is wrong.
        activity: String,
        /// The unknown id.
        precondition: String,
    },
    /// The preconditions form a cycle through this activity.
    #[error(
        "activity `{activity}` field `preconditions`: precondition cycle through this activity"
    )]
    PreconditionCycle {
        /// One activity on the cycle.
        activity: String,
    },
    /// An activity names a campaign that does not exist.
    #[error("activity `{activity}` field `campaign` names unknown campaign `{campaign}`")]
    UnknownCampaign {
        /// The activity id.
        activity: String,
        /// The unknown campaign id.
        campaign: String,
    },
    /// A campaign field is out of range.
    #[error("campaign `{campaign}` field `{field}` = {value}: expected {expected}")]
    InvalidCampaign {
        /// The campaign id.
        campaign: String,
        /// Field name, e.g. `max_count`.
        field: &'static str,
        /// The value found.
        value: f64,
        /// What a valid value looks like.
        expected: &'static str,
    },
    /// After drives are split, the problem has more tasks than the planner supports.
    #[error("the problem expands to {count} tasks; at most {max} are supported")]
    TooManyTasks {
        /// Number of tasks after splitting drives.
        count: usize,
        /// The supported maximum ([`MAX_TASKS`](crate::MAX_TASKS)).
        max: usize,
    },
    /// A replanning [`State`](crate::State) is malformed.
    #[error("state field `{field}` = {value}: expected {expected}")]
    InvalidState {
        /// Field name, e.g. `energy_wh`.
        field: &'static str,
        /// The value found.
        value: f64,
        /// What a valid value looks like.
        expected: &'static str,
    },
}
