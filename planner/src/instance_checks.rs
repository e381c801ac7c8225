//! Input checks behind [`Instance::new`](crate::Instance::new): every range, window and
//! reference of a [`Problem`], each failure a [`PlanError`] naming what to fix.

use crate::curve::CampaignCurve;
use crate::error::PlanError;
use crate::problem::{ActivityKind, Problem, Timeline};
use crate::value::{MAX_TASKS, MAX_TIERS, MAX_UTILITY, micro};

pub(crate) fn check_problem(p: &Problem) -> Result<(), PlanError> {
    let bad = |field, value: f64, expected| {
        Err(PlanError::InvalidProblem {
            field,
            value,
            expected,
        })
    };
    if p.start_s < 0 || p.start_s > 3 * 86_400 {
        return bad("start_s", p.start_s as f64, "0 ..= 259200 s after midnight");
    }
    if p.end_s <= p.start_s || p.end_s > 3 * 86_400 {
        return bad("end_s", p.end_s as f64, "start_s < end_s <= 259200");
    }
    if !(p.battery_capacity_wh.is_finite() && p.battery_capacity_wh > 0.0) {
        return bad(
            "battery_capacity_wh",
            p.battery_capacity_wh,
            "a finite value > 0 Wh",
        );
    }
    if !(p.initial_energy_wh.is_finite()
        && (0.0..=p.battery_capacity_wh).contains(&p.initial_energy_wh))
    {
        return bad(
            "initial_energy_wh",
            p.initial_energy_wh,
            "0 ..= battery_capacity_wh",
        );
    }
    if !(p.recharge_w.is_finite() && p.recharge_w >= 0.0) {
        return bad("recharge_w", p.recharge_w, "a finite value >= 0 W");
    }
    if !(p.data_capacity_mb.is_finite() && p.data_capacity_mb > 0.0) {
        return bad(
            "data_capacity_mb",
            p.data_capacity_mb,
            "a finite value > 0 MB",
        );
    }
    if !(p.initial_data_mb.is_finite() && (0.0..=p.data_capacity_mb).contains(&p.initial_data_mb)) {
        return bad(
            "initial_data_mb",
            p.initial_data_mb,
            "0 ..= data_capacity_mb",
        );
    }
    Ok(())
}

pub(crate) fn check_activity(p: &Problem, a: &crate::problem::Activity) -> Result<(), PlanError> {
    let bad = |field, value: f64, expected| {
        Err(PlanError::InvalidActivity {
            activity: a.id.clone(),
            field,
            value,
            expected,
        })
    };
    let first_s = match &a.kind {
        ActivityKind::Task { duration_s } => {
            if *duration_s <= 0 {
                return bad("duration_s", *duration_s as f64, "a duration > 0 s");
            }
            *duration_s
        }
        ActivityKind::Drive(d) => {
            if !(d.length_m.is_finite() && d.length_m > 0.0) {
                return bad("kind.length_m", d.length_m, "a finite length > 0 m");
            }
            if !(d.rate_m_per_h.is_finite() && d.rate_m_per_h > 0.0) {
                return bad("kind.rate_m_per_h", d.rate_m_per_h, "a finite rate > 0 m/h");
            }
            let total = d.duration_s();
            if total <= 0 || total > 3 * 86_400 {
                return bad(
                    "kind.rate_m_per_h",
                    d.rate_m_per_h,
                    "a drive lasting 1 ..= 259200 s",
                );
            }
            if d.min_segment_s <= 0 {
                return bad(
                    "kind.min_segment_s",
                    d.min_segment_s as f64,
                    "a duration > 0 s",
                );
            }
            if d.max_segments == 0 || d.max_segments > 64 {
                return bad("kind.max_segments", f64::from(d.max_segments), "1 ..= 64");
            }
            let mut prev = 0.0;
            for &m in &d.split_at_m {
                if !(m.is_finite() && m > prev && m < d.length_m) {
                    return bad(
                        "kind.split_at_m",
                        m,
                        "increasing distances inside (0, length_m)",
                    );
                }
                prev = m;
            }
            if let Some(e) = d.latest_end_s
                && e < a.earliest_start_s + d.duration_s()
            {
                return bad(
                    "kind.latest_end_s",
                    e as f64,
                    "a time leaving room for the whole drive after earliest_start_s",
                );
            }
            if d.split_at_m.len() > 63 {
                return bad(
                    "kind.split_at_m",
                    d.split_at_m.len() as f64,
                    "at most 63 splits",
                );
            }
            let b = d.boundaries_m();
            ((total as f64 * b[1] / d.length_m).round() as i64).max(1)
        }
    };
    if a.earliest_start_s < p.start_s || a.earliest_start_s > p.end_s {
        return Err(PlanError::OutsideSol {
            activity: a.id.clone(),
            field: "earliest_start_s",
            value_s: a.earliest_start_s,
            start_s: p.start_s,
            end_s: p.end_s,
        });
    }
    if a.latest_start_s < a.earliest_start_s {
        return Err(PlanError::ImpossibleWindow {
            activity: a.id.clone(),
            earliest_start_s: a.earliest_start_s,
            latest_start_s: a.latest_start_s,
        });
    }
    if a.latest_start_s + first_s > p.end_s {
        return Err(PlanError::OutsideSol {
            activity: a.id.clone(),
            field: "latest_start_s",
            value_s: a.latest_start_s,
            start_s: p.start_s,
            end_s: p.end_s,
        });
    }
    if !(a.power_w.is_finite() && a.power_w >= 0.0) {
        return bad("power_w", a.power_w, "a finite power >= 0 W");
    }
    if !(a.data_mb.is_finite() && a.data_mb >= 0.0) {
        return bad("data_mb", a.data_mb, "a finite volume >= 0 MB");
    }
    if !(a.downlink_mb.is_finite() && a.downlink_mb >= 0.0) {
        return bad("downlink_mb", a.downlink_mb, "a finite volume >= 0 MB");
    }
    if a.tier == 0 || usize::from(a.tier) > MAX_TIERS {
        return bad("tier", f64::from(a.tier), "a tier in 1 ..= 4");
    }
    if !(a.utility.is_finite() && (0.0..=MAX_UTILITY).contains(&a.utility)) {
        return bad("utility", a.utility, "0 ..= 10000 points");
    }
    if let Some([lo, hi]) = a.driven_window_m
        && !(lo.is_finite() && hi.is_finite() && lo >= 0.0 && hi >= lo)
    {
        return bad(
            "driven_window_m",
            lo,
            "finite [lo, hi] with 0 <= lo <= hi m",
        );
    }
    if a.timeline == Timeline::HbsLink {
        // A link activity overlaps main-timeline ones: keeping data, distance and state-based
        // windows on the main timeline keeps them in time order (see `Timeline`).
        let bad_link = |field, expected| {
            Err(PlanError::InvalidLinkActivity {
                activity: a.id.clone(),
                field,
                expected,
            })
        };
        if matches!(a.kind, ActivityKind::Drive(_)) {
            return bad_link("kind", "a task: a drive holds the main timeline");
        }
        if a.data_mb != 0.0 {
            return bad_link("data_mb", "0: data products belong on the main timeline");
        }
        if a.downlink_mb != 0.0 {
            return bad_link("downlink_mb", "0: downlinks belong on the main timeline");
        }
        if a.driven_window_m.is_some() {
            return bad_link(
                "driven_window_m",
                "absent: state-based windows belong on the main timeline",
            );
        }
    }
    Ok(())
}

pub(crate) fn campaign_curve(c: &crate::problem::Campaign) -> Result<CampaignCurve, PlanError> {
    let bad = |field, value: f64, expected| {
        Err(PlanError::InvalidCampaign {
            campaign: c.id.clone(),
            field,
            value,
            expected,
        })
    };
    if c.tier == 0 || usize::from(c.tier) > MAX_TIERS {
        return bad("tier", f64::from(c.tier), "a tier in 1 ..= 4");
    }
    if c.max_count == 0 || c.max_count as usize > MAX_TASKS {
        return bad("max_count", f64::from(c.max_count), "1 ..= 4096");
    }
    if c.min_count > c.max_count {
        return bad(
            "min_count",
            f64::from(c.min_count),
            "min_count <= max_count",
        );
    }
    if !(c.utility.is_finite() && (0.0..=MAX_UTILITY).contains(&c.utility)) {
        return bad("utility", c.utility, "0 ..= 10000 points");
    }
    if !(c.decay.is_finite() && c.decay > 0.0 && c.decay <= 1.0) {
        return bad("decay", c.decay, "0 < decay <= 1");
    }
    let mut utility_micro = Vec::with_capacity(c.max_count as usize + 1);
    let mut sum = 0.0;
    let mut term = c.utility;
    utility_micro.push(0);
    for n in 1..=c.max_count {
        sum += term;
        term *= c.decay;
        utility_micro.push(if n < c.min_count { 0 } else { micro(sum) });
    }
    Ok(CampaignCurve {
        id: c.id.clone(),
        tier: usize::from(c.tier - 1),
        utility_micro,
    })
}

/// An activity on a precondition cycle, if any (iterative three-colour DFS).
pub(crate) fn find_cycle(pre: &[Vec<usize>]) -> Option<usize> {
    let mut colour = vec![0u8; pre.len()];
    for root in 0..pre.len() {
        if colour[root] != 0 {
            continue;
        }
        let mut stack = vec![(root, 0usize)];
        colour[root] = 1;
        while let Some(&mut (v, ref mut i)) = stack.last_mut() {
            if *i < pre[v].len() {
                let w = pre[v][*i];
                *i += 1;
                match colour[w] {
                    0 => {
                        colour[w] = 1;
                        stack.push((w, 0));
                    }
                    1 => return Some(w),
                    _ => {}
                }
            } else {
                colour[v] = 2;
                stack.pop();
            }
        }
    }
    None
}
