//! Issue 12, item 3: the co-processor chain as flown. The onboard localization's inputs — the
//! post-drive NavCam images, the orbital map chip and the input file — cross the serial link
//! to the Helicopter Base Station in about 30 minutes at the flown 10 KB/s (paper 000 §4), a
//! quarter of that at the 40 KB/s the paper names as possible (§6). The transfer, the runs and
//! the reboot hold the planner's HBS-link timeline, so the sol's other activities run during
//! the transfer; every sol plan still validates. A link rate that is not a serial link's is
//! refused with one line naming the file and the field.

use crate::common;

use common::{assert_bad_input, scenario_copy, solsim};
use sim::Strategy;
use sim::operations::sol_plan::{SolPlan, TimelineStep};
use study::Scenario;

/// A bundled scenario under `onboard`, with the link rate `kb_per_s` if given. The
/// self-reliant campaign runs the census localizer through the co-processor model and has a
/// relay pass at 16:00 and science every sol; the rapid traverse uses the statistical one.
fn onboard_run(scenario: &str, kb_per_s: Option<f64>) -> sim::CampaignOutcome {
    let (path, _dir) = scenario_copy(scenario, |t| match kb_per_s {
        Some(r) if t.contains("[onboard_localization]") => t.replace(
            "[onboard_localization]",
            &format!("[onboard_localization]\nhbs_link_rate_kb_per_s = {r}"),
        ),
        Some(r) => format!("{t}\n[onboard_localization]\nhbs_link_rate_kb_per_s = {r}\n"),
        None => t,
    });
    let s = Scenario::load(&path).unwrap_or_else(|e| panic!("{e}"));
    s.compare(&[Strategy::Onboard], s.seeds())
        .pop()
        .expect("one outcome")
}

/// Each drive sol's plan and its transfer row.
fn transfers(o: &sim::CampaignOutcome) -> Vec<(u32, &SolPlan, &TimelineStep)> {
    o.sols
        .iter()
        .filter(|r| r.drove)
        .map(|r| {
            let plan = r
                .activity_plan
                .as_ref()
                .unwrap_or_else(|| panic!("sol {}: no plan", r.sol));
            assert!(
                plan.violations.is_empty(),
                "sol {}: {:?}",
                r.sol,
                plan.violations
            );
            let t = plan
                .timeline
                .iter()
                .find(|t| t.activity == "hbs_transfer")
                .unwrap_or_else(|| panic!("sol {}: no transfer", r.sol));
            (r.sol, plan, t)
        })
        .collect()
}

fn minutes(t: &TimelineStep) -> f64 {
    (t.end_s - t.start_s) as f64 / 60.0
}

fn overlap(a: &TimelineStep, b: &TimelineStep) -> bool {
    a.start_s < b.end_s && b.start_s < a.end_s
}

#[test]
fn the_transfer_takes_about_30_minutes_in_parallel_with_the_sol() {
    let o = onboard_run("self-reliant-campaign.toml", None);
    let rows = transfers(&o);
    assert!(rows.len() >= 3, "{} drive sols", rows.len());
    let mut overlapped = 0;
    for (sol, plan, t) in &rows {
        let m = minutes(t);
        assert!((25.0..=35.0).contains(&m), "sol {sol}: transfer {m:.1} min");
        assert_eq!(t.timeline, planner::Timeline::HbsLink, "sol {sol}");
        // The co-processor log's transfer step says the same.
        let event = o
            .sols
            .iter()
            .find(|r| r.sol == *sol)
            .and_then(|r| r.onboard_localization.as_ref())
            .expect("localization");
        let logged = event
            .steps
            .iter()
            .find(|e| {
                e.step
                    == sim::run::outcome::LocalizationStep::Onboard(
                        localization::hbs::HbsStep::TransferToHbs,
                    )
            })
            .map(|e| e.t_s / 60.0)
            .expect("transfer step");
        assert!(
            (m - logged).abs() <= 1.0 / 60.0 + 1e-9,
            "sol {sol}: {m} vs {logged} min"
        );
        // The chain keeps its order; the main timeline runs something during the transfer.
        let others: Vec<&TimelineStep> = plan
            .timeline
            .iter()
            .filter(|o| o.timeline == planner::Timeline::Main && overlap(o, t))
            .collect();
        overlapped += usize::from(!others.is_empty());
        let at = |id: &str| plan.timeline.iter().find(|r| r.activity == id);
        let run1 = at("hbs_run_1").expect("run 1");
        assert!(
            run1.start_s >= t.end_s,
            "sol {sol}: run before the transfer ended"
        );
        let compare = at("compare_apply").expect("compare");
        assert!(compare.start_s >= at("hbs_run_2").expect("run 2").end_s);
        // No two link rows overlap; no two main rows do.
        for (i, a) in plan.timeline.iter().enumerate() {
            for b in &plan.timeline[i + 1..] {
                if a.timeline.shares(b.timeline) {
                    assert!(
                        !overlap(a, b),
                        "sol {sol}: {} and {}",
                        a.activity,
                        b.activity
                    );
                }
            }
        }
    }
    // The relay pass at 16:00 falls inside the transfer on every drive sol.
    assert_eq!(
        overlapped,
        rows.len(),
        "{overlapped} of {} sols",
        rows.len()
    );
}

#[test]
fn at_40_kb_per_s_the_transfer_takes_a_quarter_of_the_time() {
    let slow = onboard_run("self-reliant-campaign.toml", Some(10.0));
    let fast = onboard_run("self-reliant-campaign.toml", Some(40.0));
    let slow_min: f64 = transfers(&slow).iter().map(|r| minutes(r.2)).sum();
    let fast_rows = transfers(&fast);
    for (sol, _, t) in &fast_rows {
        let m = minutes(t);
        assert!(
            (25.0 / 4.0..=35.0 / 4.0).contains(&m),
            "sol {sol}: {m:.1} min"
        );
    }
    let fast_min: f64 = fast_rows.iter().map(|r| minutes(r.2)).sum();
    let (n_slow, n_fast) = (transfers(&slow).len(), fast_rows.len());
    let ratio = (fast_min / n_fast as f64) / (slow_min / n_slow as f64);
    assert!((ratio - 0.25).abs() < 0.01, "ratio {ratio}");
    // The default is the flown 10 KB/s: the same run as setting it.
    let default = onboard_run("self-reliant-campaign.toml", None);
    assert_eq!(
        serde_json::to_string(&default.sols).expect("json"),
        serde_json::to_string(&slow.sols).expect("json")
    );
}

/// Under the statistical localizer (no co-processor log) the plan holds the flight-size
/// transfer at the link rate: exactly 30 min at 10 KB/s, 7.5 min at 40.
#[test]
fn the_statistical_localizer_plans_the_flight_size_transfer() {
    for (rate, expected_s) in [(10.0, 1_800), (40.0, 450)] {
        let o = onboard_run("rapid-traverse-379-409.toml", Some(rate));
        let rows = transfers(&o);
        assert!(!rows.is_empty());
        for (sol, _, t) in rows {
            assert_eq!(t.end_s - t.start_s, expected_s, "sol {sol} at {rate} KB/s");
        }
    }
}

#[test]
fn a_link_rate_that_is_not_a_serial_links_is_refused() {
    for bad in ["0", "-10", "nan", "inf", "1e9", "0.5"] {
        let (path, _dir) = scenario_copy("crater-floor-passage.toml", |t| {
            t.replace(
                "[onboard_localization]",
                &format!("[onboard_localization]\nhbs_link_rate_kb_per_s = {bad}"),
            )
        });
        let o = solsim().arg("validate").arg(&path).output().expect("runs");
        assert_bad_input(
            &o,
            &[
                "case.toml",
                "onboard_localization.hbs_link_rate_kb_per_s",
                "expected 1 ..= 1000 KB/s",
            ],
        );
    }
    let (path, _dir) = scenario_copy("crater-floor-passage.toml", |t| {
        t.replace(
            "[onboard_localization]",
            "[onboard_localization]\nhbs_link_rate_kb_per_s = \"fast\"",
        )
    });
    let o = solsim().arg("validate").arg(&path).output().expect("runs");
    assert_bad_input(&o, &["hbs_link_rate_kb_per_s"]);
    let (path, _dir) = scenario_copy("crater-floor-passage.toml", |t| {
        t.replace(
            "[onboard_localization]",
            "[onboard_localization]\nhbs_link_rate_kb_per_s = 40",
        )
    });
    let o = solsim().arg("validate").arg(&path).output().expect("runs");
    assert_eq!(o.status.code(), Some(0), "{}", common::stderr(&o));
}
