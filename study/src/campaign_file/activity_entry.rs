//! `[[activities]]` entries (tasks and drives) → [`planner::Activity`].

use planner::{Activity, ActivityKind, Drive, Timeline};
use sim::rover::autonav::RoverSettings;

use super::raw::{RawActivity, RawDrive};
use crate::check::{FieldCheck, lmst_of};
use crate::error::ScenarioError;
use crate::ranges;

/// Default shortest drive segment when a drive gives no `min_segment_min`, minutes.
pub const DEFAULT_MIN_SEGMENT_MIN: f64 = 10.0;
/// Default most segments of a drive without explicit or state-based split points.
pub const DEFAULT_MAX_SEGMENTS: u32 = 4;
pub(crate) fn drive(
    c: &FieldCheck<'_>,
    f: &str,
    d: &RawDrive,
    state_every_m: &[f64],
) -> Result<Drive, ScenarioError> {
    let length_m = c.range(ranges::DRIVE_LENGTH_M, &format!("{f}.length_m"), d.length_m)?;
    // A drive's rate is a rover's: AutoNav's range.
    let rate_m_per_h = c.range(
        RoverSettings::DRIVE_RATE_RANGE_M_PER_H,
        &format!("{f}.rate_m_per_h"),
        d.rate_m_per_h,
    )?;
    // The planner takes drives of at most 3 sols (259 200 s).
    let drive_s = 3600.0 * length_m / rate_m_per_h;
    if drive_s > 259_200.0 {
        return Err(c.err(
            &format!("{f}.rate_m_per_h"),
            format!("a rate that drives length_m = {length_m} m within 3 sols (259 200 s)"),
            rate_m_per_h,
        ));
    }
    let min_segment_s = c.minutes(
        &format!("{f}.min_segment_min"),
        d.min_segment_min.unwrap_or(DEFAULT_MIN_SEGMENT_MIN),
    )?;
    let max_segments = match d.max_segments {
        None => DEFAULT_MAX_SEGMENTS,
        Some(k) if (1..=64).contains(&k) => k as u32,
        Some(k) => return Err(c.err(&format!("{f}.max_segments"), "1 ..= 64 segments", k)),
    };
    let split_at_m = match &d.split_at_m {
        Some(v) => {
            let mut prev = 0.0;
            for (k, &m) in v.iter().enumerate() {
                if !(m.is_finite() && m > prev && m < length_m) {
                    return Err(c.err(
                        &format!("{f}.split_at_m[{k}]"),
                        format!("increasing distances inside (0, {length_m}) m"),
                        m,
                    ));
                }
                prev = m;
            }
            v.clone()
        }
        None => {
            // Every multiple of a state-based cadence inside the drive, measured from its
            // own start (exact when the drive is the sol's only one).
            let mut v: Vec<f64> = Vec::new();
            for &every in state_every_m {
                let mut k = 1.0;
                while k * every < length_m - 1e-9 && v.len() < 63 {
                    v.push(k * every);
                    k += 1.0;
                }
            }
            v.sort_by(f64::total_cmp);
            v.dedup_by(|a, b| (*a - *b).abs() < 1e-6);
            v
        }
    };
    let latest_end_s = d
        .latest_end_lmst
        .as_deref()
        .map(|t| c.lmst_s(&format!("{f}.latest_end_lmst"), t))
        .transpose()?;
    Ok(Drive {
        length_m,
        rate_m_per_h,
        min_segment_s,
        max_segments,
        split_at_m,
        latest_end_s,
    })
}

/// The first segment's duration as the planner splits the drive, plus 1 s for its rounding.
fn first_segment_s(d: &Drive) -> i64 {
    let first_m = d.boundaries_m().get(1).copied().unwrap_or(d.length_m);
    (3600.0 * first_m / d.rate_m_per_h).ceil() as i64 + 1
}

pub(crate) fn activity(
    c: &FieldCheck<'_>,
    f: &str,
    a: &RawActivity,
    (start_s, end_s): (i64, i64),
    state_every_m: &[f64],
    all_ids: &[&str],
) -> Result<Activity, ScenarioError> {
    c.id(&format!("{f}.id"), &a.id)?;
    c.text(&format!("{f}.name"), &a.name)?;
    let kind = match (&a.drive, a.duration_min) {
        (Some(_), Some(_)) | (None, None) => {
            return Err(c.err(
                f,
                "exactly one of duration_min (a task) or drive (a traverse)",
                if a.drive.is_some() { "both" } else { "neither" },
            ));
        }
        (None, Some(m)) => ActivityKind::Task {
            duration_s: c.minutes(&format!("{f}.duration_min"), m)?,
        },
        (Some(d), None) => ActivityKind::Drive(drive(c, &format!("{f}.drive"), d, state_every_m)?),
    };
    // A drive's window constrains its first segment only (later ones just end by the sol end).
    let duration_s = match &kind {
        ActivityKind::Task { duration_s } => *duration_s,
        ActivityKind::Drive(d) => first_segment_s(d),
    };
    let earliest = match &a.earliest_start_lmst {
        Some(t) => c.lmst_s(&format!("{f}.earliest_start_lmst"), t)?,
        None => start_s,
    };
    if earliest < start_s || earliest >= end_s {
        return Err(c.err(
            &format!("{f}.earliest_start_lmst"),
            format!(
                "a time within the sol window {}..{}",
                lmst_of(start_s),
                lmst_of(end_s)
            ),
            format!("{:?}", lmst_of(earliest)),
        ));
    }
    let latest = match &a.latest_start_lmst {
        Some(t) => c.lmst_s(&format!("{f}.latest_start_lmst"), t)?,
        None => end_s - duration_s,
    };
    if latest < earliest {
        let field = if a.latest_start_lmst.is_some() {
            format!("{f}.latest_start_lmst")
        } else {
            format!("{f}.duration_min")
        };
        return Err(c.err(
            &field,
            format!(
                "a latest start no earlier than the earliest start {} (and room to end by {})",
                lmst_of(earliest),
                lmst_of(end_s)
            ),
            format!("{:?}", lmst_of(latest)),
        ));
    }
    if latest + duration_s > end_s {
        return Err(c.err(
            &format!("{f}.latest_start_lmst"),
            format!(
                "a start that lets the {} min {} end by the sol end {}",
                duration_s / 60,
                if a.drive.is_some() {
                    "first drive segment"
                } else {
                    "activity"
                },
                lmst_of(end_s)
            ),
            format!("{:?}", lmst_of(latest)),
        ));
    }
    let power_w = c.non_negative(&format!("{f}.power_w"), a.power_w, "watts")?;
    let data_mb = c.non_negative(
        &format!("{f}.data_mb"),
        a.data_mb.unwrap_or(0.0),
        "megabytes",
    )?;
    let downlink_mb = c.non_negative(
        &format!("{f}.downlink_mb"),
        a.downlink_mb.unwrap_or(0.0),
        "megabytes",
    )?;
    let timeline = match a.timeline.as_deref() {
        None | Some("main") => Timeline::Main,
        Some("hbs_link") => Timeline::HbsLink,
        Some("main_and_hbs_link") => Timeline::MainAndHbsLink,
        Some(other) => {
            return Err(c.err(
                &format!("{f}.timeline"),
                "\"main\", \"hbs_link\" or \"main_and_hbs_link\"",
                format!("{other:?}"),
            ));
        }
    };
    for (k, p) in a.preconditions.iter().enumerate() {
        if !all_ids.contains(&p.as_str()) || *p == a.id {
            return Err(c.err(
                &format!("{f}.preconditions[{k}]"),
                "the id of another activity in [[activities]]",
                format!("{p:?}"),
            ));
        }
    }
    Ok(Activity {
        id: a.id.clone(),
        name: a.name.clone(),
        kind,
        earliest_start_s: earliest,
        latest_start_s: latest,
        power_w,
        data_mb,
        downlink_mb,
        preconditions: a.preconditions.clone(),
        mandatory: a.mandatory,
        campaign: a.campaign.clone(),
        tier: c.tier(&format!("{f}.tier"), a.tier)?,
        utility: c.utility(&format!("{f}.utility"), a.utility.unwrap_or(0.0))?,
        driven_window_m: None,
        timeline,
    })
}
