//! Builders for the instance activities of periodic and state-based campaigns (paper 003
//! §3, Fig. 2).
//!
//! The planner sees a campaign as the activities that count towards it. A temporally
//! periodic campaign becomes one candidate instance per due time `first_due + k·period`,
//! each with the window `due ± tolerance` (absolute due times, not relative to when the
//! previous instance ran: that keeps left-shifted schedules complete, see
//! [`State`](crate::State)). A state-based campaign becomes one instance per `k·every_m`
//! metres, each with a [`driven_window_m`](crate::Activity::driven_window_m) of
//! `k·every_m ± tolerance_m`; split the drive at those distances
//! ([`Drive::split_at_m`](crate::Drive::split_at_m)) so the survey can run between segments.
//!
//! ## References
//! Paper 003 §3 (campaign intent), Fig. 3 (a drive split by opacity and survey instances).

use crate::problem::Activity;

/// Instances of a temporally periodic campaign: copies of `template` named
/// `"{id}-{k}"`, due at `first_due_s + k × period_s` for every due time up to `until_s`, each
/// startable within `± tolerance_s` of it and counting towards `campaign_id`.
///
/// # Panics
/// If `period_s ≤ 0`.
#[must_use]
pub fn periodic_instances(
    template: &Activity,
    campaign_id: &str,
    first_due_s: i64,
    period_s: i64,
    tolerance_s: i64,
    until_s: i64,
) -> Vec<Activity> {
    assert!(period_s > 0, "period_s must be positive");
    let mut out = Vec::new();
    let mut due = first_due_s;
    let mut k = 0;
    while due <= until_s {
        let mut a = template.clone();
        a.id = format!("{}-{k}", template.id);
        a.earliest_start_s = due - tolerance_s;
        a.latest_start_s = due + tolerance_s;
        a.campaign = Some(campaign_id.to_string());
        out.push(a);
        due += period_s;
        k += 1;
    }
    out
}

/// Instances of a state-based campaign: copies of `template` named `"{id}-{k}"` for
/// `k = 1 ..= floor(total_m / every_m)`, each startable only while the metres driven lie in
/// `k × every_m ± tolerance_m`, counting towards `campaign_id`.
///
/// # Panics
/// If `every_m` is not positive.
#[must_use]
pub fn state_based_instances(
    template: &Activity,
    campaign_id: &str,
    every_m: f64,
    tolerance_m: f64,
    total_m: f64,
) -> Vec<Activity> {
    assert!(every_m > 0.0, "every_m must be positive");
    let n = (total_m / every_m + 1e-9).floor().max(0.0) as u32;
    (1..=n)
        .map(|k| {
            let at = f64::from(k) * every_m;
            let mut a = template.clone();
            a.id = format!("{}-{k}", template.id);
            a.driven_window_m = Some([(at - tolerance_m).max(0.0), at + tolerance_m]);
            a.campaign = Some(campaign_id.to_string());
            a
        })
        .collect()
}

/// Clip each activity's start window to a sol window `[start_s, end_s]` (it must start at or
/// after `start_s` and end by `end_s`); drop those left with no start time. Use it on
/// [`periodic_instances`], whose `± tolerance` windows may reach outside the sol.
#[must_use]
pub fn clip_to_window(activities: Vec<Activity>, start_s: i64, end_s: i64) -> Vec<Activity> {
    activities
        .into_iter()
        .filter_map(|mut a| {
            a.earliest_start_s = a.earliest_start_s.max(start_s);
            a.latest_start_s = a.latest_start_s.min(end_s - a.duration_s());
            (a.latest_start_s >= a.earliest_start_s).then_some(a)
        })
        .collect()
}
