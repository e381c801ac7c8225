//! `[[expect]]` entries as written ([`RawExpectation`]) and their validation against the
//! scenario's calendar and science campaigns ([`RawExpectation::resolve`]): one error naming the
//! file, the entry's field and what was expected.

use std::path::Path;

use serde::Deserialize;

use crate::error::ScenarioError;
use crate::expect::{
    Check, Expectation, MAX_EXPECT_RUNS, Resolved, StatCheck, StatisticalExpectation,
};
use crate::metric::{Metric, RateKind};
use sim::operations::calendar::Calendar;
use sim::{FaultKind, Strategy};

/// `[[expect]]` as written.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RawExpectation {
    #[serde(default)]
    what: String,
    strategy: String,
    sol: Option<u32>,
    fault: Option<String>,
    fault_after_m: Option<[f64; 2]>,
    fault_uncertainty_m: Option<[f64; 2]>,
    distance_m: Option<[f64; 2]>,
    end_uncertainty_m: Option<[f64; 2]>,
    drove: Option<bool>,
    no_path_faults: Option<[u32; 2]>,
    faults: Option<[u32; 2]>,
    sols_to_goal: Option<[u32; 2]>,
    total_distance_m: Option<[f64; 2]>,
    max_uncertainty_m: Option<[f64; 2]>,
    goal_sooner_than: Option<RawSooner>,
    covers: Option<RawCovers>,
    plan_violations: Option<[u32; 2]>,
    science: Option<RawScience>,
    runs: Option<u64>,
    no_path_rate: Option<[f64; 2]>,
    fault_rate: Option<[f64; 2]>,
    truth_outside_disc_rate: Option<[f64; 2]>,
    goal_reached_rate: Option<[f64; 2]>,
    disc_coverage: Option<[f64; 2]>,
    errors: Option<String>,
    preemptive_shortening: Option<bool>,
    paired: Option<RawPaired>,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
struct RawPaired {
    baseline: String,
    figure: String,
    mean: Option<[f64; 2]>,
    at_most: Option<f64>,
    share: Option<[f64; 2]>,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
struct RawScience {
    campaign: String,
    done: Option<[u32; 2]>,
    failed: Option<[u32; 2]>,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
struct RawSooner {
    strategy: String,
    by_at_least_sols: u32,
}

#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
struct RawCovers {
    from_sol: u32,
    distance_m: f64,
    sols: [u32; 2],
}

impl RawExpectation {
    /// Validate against the scenario's calendar.
    pub fn resolve(
        self,
        path: &Path,
        index: usize,
        calendar: &Calendar,
        campaign_ids: &[&str],
    ) -> Result<Resolved, ScenarioError> {
        let f = |name: &str| format!("expect[{index}].{name}");
        // `what` is printed by `solsim regress` and written into its JUnit XML: a control
        // character would drive the terminal or break the XML.
        if maps::input_file::first_unsafe_char(&self.what).is_some() {
            return Err(ScenarioError::field(
                path,
                f("what"),
                "text without control characters",
                format!("{:?}", self.what),
            ));
        }
        let names = Strategy::ALL.map(Strategy::name).join(", ");
        let strategy = Strategy::from_name(&self.strategy).ok_or_else(|| {
            ScenarioError::field(
                path,
                f("strategy"),
                format!("one of {names}"),
                format!("{:?}", self.strategy),
            )
        })?;
        let rates = [
            (RateKind::NoPath, self.no_path_rate),
            (RateKind::Fault, self.fault_rate),
            (RateKind::TruthOutsideDisc, self.truth_outside_disc_rate),
            (RateKind::GoalReached, self.goal_reached_rate),
        ];
        let statistical = rates.iter().any(|(_, r)| r.is_some())
            || self.disc_coverage.is_some()
            || self.paired.is_some()
            || self.errors.is_some()
            || self.preemptive_shortening.is_some();
        match (self.runs, statistical) {
            (None, false) => {}
            (None, true) => {
                return Err(ScenarioError::field(
                    path,
                    f("runs"),
                    "a number of runs for the statistical checks (no_path_rate, paired, …)",
                    "nothing",
                ));
            }
            (Some(runs), _) => {
                let mut checks = Vec::new();
                if !(1..=MAX_EXPECT_RUNS).contains(&runs) {
                    return Err(ScenarioError::field(
                        path,
                        f("runs"),
                        format!("1 to {MAX_EXPECT_RUNS} runs"),
                        runs,
                    ));
                }
                let per_run = self.sol.is_some()
                    || self.fault.is_some()
                    || self.fault_after_m.is_some()
                    || self.fault_uncertainty_m.is_some()
                    || self.distance_m.is_some()
                    || self.end_uncertainty_m.is_some()
                    || self.drove.is_some()
                    || self.no_path_faults.is_some()
                    || self.faults.is_some()
                    || self.sols_to_goal.is_some()
                    || self.total_distance_m.is_some()
                    || self.max_uncertainty_m.is_some()
                    || self.goal_sooner_than.is_some()
                    || self.covers.is_some()
                    || self.plan_violations.is_some()
                    || self.science.is_some();
                if per_run {
                    return Err(ScenarioError::field(
                        path,
                        f("runs"),
                        "only statistical checks (no_path_rate, fault_rate, truth_outside_disc_rate, goal_reached_rate, disc_coverage, paired) beside runs: put checks of one run in their own [[expect]]",
                        runs,
                    ));
                }
                for (rate, r) in rates {
                    if let Some([lo, hi]) = r {
                        if !(lo.is_finite() && hi.is_finite() && 0.0 <= lo && lo <= hi && hi <= 1.0)
                        {
                            return Err(ScenarioError::field(
                                path,
                                f(rate.name()),
                                "a range [low, high] of fractions, 0 ≤ low ≤ high ≤ 1",
                                format!("[{lo}, {hi}]"),
                            ));
                        }
                        checks.push(StatCheck::Rate { rate, lo, hi });
                    }
                }
                if let Some([lo, hi]) = self.disc_coverage {
                    if !(lo.is_finite() && hi.is_finite() && 0.0 <= lo && lo <= hi && hi <= 1.0) {
                        return Err(ScenarioError::field(
                            path,
                            f("disc_coverage"),
                            "a range [low, high] of fractions, 0 ≤ low ≤ high ≤ 1",
                            format!("[{lo}, {hi}]"),
                        ));
                    }
                    checks.push(StatCheck::DiscCoverage { lo, hi });
                }
                if let Some(p) = self.paired {
                    let baseline = Strategy::from_name(&p.baseline).ok_or_else(|| {
                        ScenarioError::field(
                            path,
                            f("paired.baseline"),
                            format!("one of {names}"),
                            format!("{:?}", p.baseline),
                        )
                    })?;
                    if baseline == strategy {
                        return Err(ScenarioError::field(
                            path,
                            f("paired.baseline"),
                            "a strategy other than the entry's own",
                            format!("{:?}", p.baseline),
                        ));
                    }
                    let figure = Metric::from_name(&p.figure).ok_or_else(|| {
                        ScenarioError::field(
                            path,
                            f("paired.figure"),
                            format!("one of {}", Metric::ALL.map(Metric::name).join(", ")),
                            format!("{:?}", p.figure),
                        )
                    })?;
                    if p.at_most.is_some() != p.share.is_some() {
                        return Err(ScenarioError::field(
                            path,
                            f("paired.share"),
                            "at_most = a difference together with share = [low, high]",
                            given_share(p.at_most, p.share),
                        ));
                    }
                    if p.mean.is_none() && p.share.is_none() {
                        return Err(ScenarioError::field(
                            path,
                            f("paired"),
                            "mean = [low, high], or at_most = D with share = [low, high]",
                            "neither",
                        ));
                    }
                    if let Some([lo, hi]) = p.mean {
                        if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
                            return Err(ScenarioError::field(
                                path,
                                f("paired.mean"),
                                "a range [low, high] with low ≤ high",
                                format!("[{lo}, {hi}]"),
                            ));
                        }
                        checks.push(StatCheck::Paired {
                            baseline,
                            figure,
                            lo,
                            hi,
                        });
                    }
                    match (p.at_most, p.share) {
                        (None, None) => {}
                        (Some(at_most), Some([lo, hi]))
                            if at_most.is_finite()
                                && lo.is_finite()
                                && hi.is_finite()
                                && 0.0 <= lo
                                && lo <= hi
                                && hi <= 1.0 =>
                        {
                            checks.push(StatCheck::PairedShare {
                                baseline,
                                figure,
                                at_most,
                                lo,
                                hi,
                            });
                        }
                        (at_most, share) => {
                            return Err(ScenarioError::field(
                                path,
                                f("paired.share"),
                                "at_most = a finite difference together with share = [low, high], fractions with 0 ≤ low ≤ high ≤ 1",
                                given_share(at_most, share),
                            ));
                        }
                    }
                }
                if checks.is_empty() {
                    return Err(ScenarioError::field(
                        path,
                        f("(checks)"),
                        "at least one statistical check beside runs (no_path_rate, paired, …)",
                        "none",
                    ));
                }
                let errors = match self.errors.as_deref() {
                    None => None,
                    Some(name) => Some(
                        sim::rover::errors::ErrorPreset::from_name(name).ok_or_else(|| {
                            ScenarioError::field(
                                path,
                                f("errors"),
                                "\"calibrated\" or \"stress\"",
                                format!("{name:?}"),
                            )
                        })?,
                    ),
                };
                return Ok(Resolved::Sweep(StatisticalExpectation {
                    index,
                    what: self.what,
                    strategy,
                    runs,
                    errors,
                    preemptive_shortening: self.preemptive_shortening,
                    checks,
                }));
            }
        }
        if let Some(sol) = self.sol
            && !calendar.sols.iter().any(|s| s.sol == sol)
        {
            return Err(ScenarioError::field(
                path,
                f("sol"),
                "a sol of the calendar",
                sol,
            ));
        }
        let mut checks = Vec::new();
        let per_sol = self.fault.is_some()
            || self.fault_after_m.is_some()
            || self.fault_uncertainty_m.is_some()
            || self.distance_m.is_some()
            || self.end_uncertainty_m.is_some()
            || self.drove.is_some();
        if per_sol && self.sol.is_none() {
            return Err(ScenarioError::field(
                path,
                f("sol"),
                "a sol number for per-sol checks (fault, distance_m, …)",
                "nothing",
            ));
        }
        if let Some(fault) = self.fault {
            let kind = match (fault.as_str(), FaultKind::from_name(&fault)) {
                ("none", _) => None,
                (_, Some(kind)) => Some(kind),
                (other, None) => {
                    return Err(ScenarioError::field(
                        path,
                        f("fault"),
                        "\"NO_PATH\", \"KEEP_OUT\", \"KEEP_IN\" or \"none\"",
                        format!("{other:?}"),
                    ));
                }
            };
            checks.push(Check::Fault(kind));
        }
        let ranges: [(&'static str, Option<[f64; 2]>); 6] = [
            ("fault_after_m", self.fault_after_m),
            ("fault_uncertainty_m", self.fault_uncertainty_m),
            ("distance_m", self.distance_m),
            ("end_uncertainty_m", self.end_uncertainty_m),
            ("total_distance_m", self.total_distance_m),
            ("max_uncertainty_m", self.max_uncertainty_m),
        ];
        let int_ranges: [(&'static str, Option<[u32; 2]>); 4] = [
            ("no_path_faults", self.no_path_faults),
            ("faults", self.faults),
            ("sols_to_goal", self.sols_to_goal),
            ("plan_violations", self.plan_violations),
        ];
        for (quantity, r) in ranges.into_iter().chain(
            int_ranges
                .into_iter()
                .map(|(q, r)| (q, r.map(|[a, b]| [f64::from(a), f64::from(b)]))),
        ) {
            if let Some([lo, hi]) = r {
                if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
                    return Err(ScenarioError::field(
                        path,
                        f(quantity),
                        "a range [low, high] with low ≤ high",
                        format!("[{lo}, {hi}]"),
                    ));
                }
                checks.push(Check::Range { quantity, lo, hi });
            }
        }
        if let Some(d) = self.drove {
            checks.push(Check::Drove(d));
        }
        if let Some(s) = self.goal_sooner_than {
            let than = Strategy::from_name(&s.strategy).ok_or_else(|| {
                ScenarioError::field(
                    path,
                    f("goal_sooner_than.strategy"),
                    format!("one of {names}"),
                    format!("{:?}", s.strategy),
                )
            })?;
            checks.push(Check::Sooner {
                than,
                by: s.by_at_least_sols,
            });
        }
        if let Some(cv) = self.covers {
            if !(cv.distance_m.is_finite() && cv.distance_m > 0.0) {
                return Err(ScenarioError::field(
                    path,
                    f("covers.distance_m"),
                    "a positive number of metres",
                    cv.distance_m,
                ));
            }
            checks.push(Check::Covers {
                from_sol: cv.from_sol,
                distance_m: cv.distance_m,
                lo: cv.sols[0],
                hi: cv.sols[1],
            });
        }
        if let Some(sc) = self.science {
            if !campaign_ids.contains(&sc.campaign.as_str()) {
                return Err(ScenarioError::field(
                    path,
                    f("science.campaign"),
                    format!(
                        "the id of a [[science.campaigns]] entry ({})",
                        campaign_ids.join(", ")
                    ),
                    format!("{:?}", sc.campaign),
                ));
            }
            for (failed, r) in [(false, sc.done), (true, sc.failed)] {
                let what = if failed { "failed" } else { "done" };
                if let Some([lo, hi]) = r {
                    if lo > hi {
                        return Err(ScenarioError::field(
                            path,
                            f(&format!("science.{what}")),
                            "a range [low, high] with low ≤ high",
                            format!("[{lo}, {hi}]"),
                        ));
                    }
                    checks.push(Check::Science {
                        campaign: sc.campaign.clone(),
                        failed,
                        lo,
                        hi,
                    });
                }
            }
        }
        if checks.is_empty() {
            return Err(ScenarioError::field(
                path,
                f("(checks)"),
                "at least one check (fault, distance_m, sols_to_goal, …)",
                "none",
            ));
        }
        Ok(Resolved::Run(Expectation {
            index,
            what: self.what,
            strategy,
            sol: self.sol,
            checks,
        }))
    }
}

/// `at_most` and `share` as written, for an error message (`at_most -1, share none`).
fn given_share(at_most: Option<f64>, share: Option<[f64; 2]>) -> String {
    format!(
        "at_most {}, share {}",
        at_most.map_or("none".into(), |a| a.to_string()),
        share.map_or("none".into(), |[lo, hi]| format!("[{lo}, {hi}]"))
    )
}
