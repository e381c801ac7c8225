//! The `solsim plan` output: the terminal table and the JSON document (the same content).

use planner::{PlanOutcome, PlanStatus};
use serde_json::{Value, json};

use sim::time::lmst_of as lmst;

use crate::plan_report::{PlanReport, TimelineRow};

/// The status line: `PROVEN OPTIMAL`, `FEASIBLE gap …`, `INFEASIBLE` or `NO PLAN FOUND`.
#[must_use]
pub fn status_text(outcome: &PlanOutcome) -> String {
    match outcome.status {
        PlanStatus::Optimal => "PROVEN OPTIMAL".into(),
        PlanStatus::Feasible => {
            let gap = outcome.gap_points();
            let tier = gap.iter().position(|&g| g > 0.0).unwrap_or(0);
            format!(
                "FEASIBLE gap {:.2} points in tier {} (not proven optimal: the budget ran out)",
                gap[tier],
                tier + 1
            )
        }
        PlanStatus::Infeasible => "INFEASIBLE: no plan holds every mandatory activity".into(),
        PlanStatus::NoPlanFound => {
            "NO PLAN FOUND: the budget ran out before a plan held every mandatory activity".into()
        }
    }
}

fn tiers_used(r: &PlanReport) -> usize {
    let p = &r.file.problem;
    let a = p.activities.iter().map(|a| usize::from(a.tier));
    let c = p.campaigns.iter().map(|c| usize::from(c.tier));
    a.chain(c).max().unwrap_or(1).max(1)
}

fn activity_label(row: &TimelineRow) -> String {
    let label = match row.segment {
        Some((k, n, from, to)) => format!("{} {k}/{n} ({from:.0}–{to:.0} m)", row.activity),
        None => row.activity.clone(),
    };
    if row.timeline.is_main() {
        label
    } else {
        format!("{label} [{}]", row.timeline.name())
    }
}

/// The terminal table.
#[must_use]
pub fn report_table(r: &PlanReport) -> String {
    use std::fmt::Write as _;
    let p = &r.file.problem;
    let mut s = String::new();
    match r.file.description.trim() {
        "" => writeln!(s, "{}", r.file.name),
        d => writeln!(s, "{} — {d}", r.file.name),
    }
    .ok();
    let _ = writeln!(
        s,
        "sol window {}–{} LMST; battery {:.0}/{:.0} Wh, net recharge {:.0} W; data {:.0}/{:.0} MB\n",
        lmst(p.start_s),
        lmst(p.end_s),
        p.initial_energy_wh,
        p.battery_capacity_wh,
        p.recharge_w,
        p.initial_data_mb,
        p.data_capacity_mb
    );
    let w = r
        .rows
        .iter()
        .map(|row| activity_label(row).chars().count() + usize::from(row.mandatory) * 2)
        .max()
        .unwrap_or(8)
        .max(8);
    let _ = writeln!(
        s,
        "{:<5}  {:<5}  {:<w$}  {:<14}  {:>9}  {:>9}  {:>8}",
        "start", "end", "activity", "campaign", "driven m", "energy Wh", "data MB"
    );
    for row in &r.rows {
        let mut label = activity_label(row);
        if row.mandatory {
            label.push_str(" *");
        }
        let _ = writeln!(
            s,
            "{:<5}  {:<5}  {:<w$}  {:<14}  {:>9.1}  {:>9.1}  {:>8.1}",
            lmst(row.start_s),
            lmst(row.end_s),
            label,
            row.campaign.as_deref().unwrap_or("-"),
            row.driven_at_start_m,
            row.energy_wh,
            row.data_mb
        );
    }
    let _ = writeln!(
        s,
        "(times LMST; * mandatory; driven m = metres driven when the step starts; energy and data after the step)"
    );
    if r.rows.iter().any(|row| !row.timeline.is_main()) {
        let _ = writeln!(
            s,
            "([hbs_link] runs in parallel with the main timeline; energy counts every step that overlaps)"
        );
    }
    let _ = writeln!(s);
    let _ = writeln!(
        s,
        "{:<22}  {:<11}  {:>4}  {:>9}  {:>13}",
        "campaign", "intent", "tier", "scheduled", "utility/max"
    );
    if r.campaigns.is_empty() {
        let _ = writeln!(s, "(no campaigns)");
    }
    for c in &r.campaigns {
        let _ = writeln!(
            s,
            "{:<22}  {:<11}  {:>4}  {:>9}  {:>13}",
            c.id,
            c.intent,
            c.tier,
            format!("{}/{}", c.scheduled, c.candidates),
            format!("{:.2}/{:.2}", c.points, c.max_points)
        );
    }
    let n = tiers_used(r);
    let _ = writeln!(s);
    let v = r.outcome.value.to_points();
    let b = r.outcome.best_bound.to_points();
    let g = r.outcome.gap_points();
    let _ = writeln!(
        s,
        "{:<4}  {:>9}  {:>10}  {:>9}  {:>10}  {:>8}",
        "tier", "campaigns", "activities", "utility", "best bound", "gap"
    );
    for t in 0..n {
        let _ = writeln!(
            s,
            "{:<4}  {:>9.2}  {:>10.2}  {:>9.2}  {:>10.2}  {:>8.2}",
            t + 1,
            v[t] - r.own_points[t],
            r.own_points[t],
            v[t],
            b[t],
            g[t]
        );
    }
    let _ = writeln!(
        s,
        "(activities = the activities' own utility, e.g. the part of a drive's utility earned by the metres driven)"
    );
    let _ = writeln!(s, "\nstatus: {}", status_text(&r.outcome));
    let _ = write!(
        s,
        "search: {} nodes expanded (budget {})",
        r.outcome.stats.nodes_expanded, r.node_budget
    );
    match r.time_budget_ms {
        None => {
            let _ = writeln!(s, ", deterministic");
        }
        Some(ms) => {
            let _ = writeln!(s, ", time budget {ms} ms: output may vary between runs");
        }
    }
    if r.violations.is_empty() {
        let _ = writeln!(s, "validator: 0 violations");
    } else {
        let n = r.violations.len();
        let plural = if n == 1 { "" } else { "s" };
        let why = if r.outcome.plan.steps.is_empty() {
            " (there is no plan: the mandatory activities are missing)"
        } else {
            ""
        };
        let _ = writeln!(s, "validator: {n} violation{plural}{why}");
        for v in &r.violations {
            let _ = writeln!(s, "  - {v}");
        }
    }
    s
}

/// The JSON document (the same content as the table).
#[must_use]
pub fn report_json(r: &PlanReport) -> Value {
    let p = &r.file.problem;
    let n = tiers_used(r);
    let tiers: Vec<Value> = (0..n)
        .map(|t| {
            json!({
                "tier": t + 1,
                "utility": r.outcome.value.to_points()[t],
                "best_bound": r.outcome.best_bound.to_points()[t],
                "gap": r.outcome.gap_points()[t],
                "activity_utility": r.own_points[t],
            })
        })
        .collect();
    let steps: Vec<Value> = r
        .rows
        .iter()
        .map(|row| {
            let mut step = json!({
                "start_lmst": lmst(row.start_s),
                "end_lmst": lmst(row.end_s),
                "start_s": row.start_s,
                "end_s": row.end_s,
                "activity": row.activity,
                "name": row.name,
                "segment": row.segment.map(|(k, n, from, to)| json!({
                    "k": k, "n": n, "from_m": from, "to_m": to,
                })),
                "campaign": row.campaign,
                "mandatory": row.mandatory,
                "driven_at_start_m": row.driven_at_start_m,
                "energy_wh": row.energy_wh,
                "data_mb": row.data_mb,
            });
            if !row.timeline.is_main() {
                step["timeline"] = json!(row.timeline.name());
            }
            step
        })
        .collect();
    let campaigns: Vec<Value> = r
        .campaigns
        .iter()
        .map(|c| {
            json!({
                "id": c.id,
                "intent": c.intent,
                "tier": c.tier,
                "scheduled": c.scheduled,
                "candidates": c.candidates,
                "utility": c.points,
                "max_utility": c.max_points,
            })
        })
        .collect();
    json!({
        "provenance": {
            "campaign_file": r.file.path.display().to_string(),
            "campaign_sha256": r.file.sha256,
            "solsim_version": env!("CARGO_PKG_VERSION"),
        },
        "name": r.file.name,
        "sol": {
            "start_lmst": lmst(p.start_s),
            "end_lmst": lmst(p.end_s),
            "start_s": p.start_s,
            "end_s": p.end_s,
            "battery_capacity_wh": p.battery_capacity_wh,
            "initial_energy_wh": p.initial_energy_wh,
            "net_recharge_w": p.recharge_w,
            "data_capacity_mb": p.data_capacity_mb,
            "initial_data_mb": p.initial_data_mb,
        },
        "steps": steps,
        "campaigns": campaigns,
        "tiers": tiers,
        "status": match r.outcome.status {
            PlanStatus::Optimal => "optimal",
            PlanStatus::Feasible => "feasible",
            PlanStatus::Infeasible => "infeasible",
            PlanStatus::NoPlanFound => "no_plan_found",
        },
        "status_text": status_text(&r.outcome),
        "proven_optimal": r.outcome.is_proven_optimal(),
        "search": {
            "nodes_expanded": r.outcome.stats.nodes_expanded,
            "node_budget": r.node_budget,
            "time_budget_ms": r.time_budget_ms,
            "deterministic": r.time_budget_ms.is_none(),
        },
        "validator": {
            "violations": r.violations,
        },
    })
}
