//! Expected outcomes in scenario files (`[[expect]]`), checked by `solsim regress`.
//!
//! ```toml
//! [[expect]]
//! what = "sol 385 faults NO_PATH after ~14 m at r ≈ 26.9 m"   # printed on failure
//! strategy = "replay"
//! sol = 385                        # per-sol checks below need a sol
//! fault = "NO_PATH"                # or "none"
//! fault_after_m = [12.0, 16.0]     # closed ranges [low, high]
//! fault_uncertainty_m = [26.8, 27.0]
//! distance_m = [240.0, 250.0]
//! end_uncertainty_m = [32.82, 33.02]
//! drove = true
//!
//! [[expect]]                       # totals of a run
//! strategy = "onboard"
//! no_path_faults = [0, 0]
//! sols_to_goal = [1, 3]
//! goal_sooner_than = { strategy = "replay", by_at_least_sols = 1 }
//! covers = { from_sol = 402, distance_m = 1411.0, sols = [6, 6] }
//!
//! [[expect]]                       # over a sweep: runs 0..200 of each strategy named
//! what = "onboard rarely faults; it reaches the goal sooner than ground"
//! strategy = "onboard"
//! runs = 200                       # statistical checks below need runs
//! no_path_rate = [0.0, 0.10]       # the rate over the runs within [low, high]; also
//!                                  # fault_rate, truth_outside_disc_rate, goal_reached_rate
//! paired = { baseline = "ground", figure = "sols_to_goal", mean = [-2.0, -0.5] }
//!                                  # or the share of runs with a difference ≤ at_most:
//!                                  # paired = { …, at_most = -1, share = [0.95, 1.0] }
//!
//! [[expect]]                       # the disc's coverage: drive sols ending with the truth
//! strategy = "ground"              # inside it, pooled over the runs
//! runs = 200
//! errors = "stress"                # under another error model than the scenario's
//! disc_coverage = [0.0, 0.99]
//!
//! [[expect]]                       # what-if: ground without paper 000 §2's pre-emptive
//! strategy = "ground"              # shortening (the scenario's [operations] otherwise)
//! runs = 200
//! preemptive_shortening = false
//! no_path_rate = [0.05, 1.0]
//! ```
//!
//! A statistical entry checks the point estimate (a rate, or the mean paired difference over
//! the run indices where both strategies have the figure) against its range; `solsim regress`
//! prints the 95 % interval beside it. The figures are the columns of a sweep's `runs.parquet`
//! ([`crate::figure::Figure`]).

use std::path::Path;

use serde::Deserialize;

use crate::error::ScenarioError;
use crate::figure::{Figure, RateKind};
use sim::calendar::Calendar;
use sim::{CampaignOutcome, FaultKind, Strategy};

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

/// Most runs a statistical expectation may ask for.
pub const MAX_EXPECT_RUNS: u64 = 100_000;

/// One check of a statistical expectation.
#[derive(Debug, Clone, PartialEq)]
pub enum StatCheck {
    /// The rate of runs with the outcome within `[lo, hi]`.
    Rate {
        /// Which rate.
        rate: RateKind,
        /// Bounds (fractions).
        lo: f64,
        /// Bounds (fractions).
        hi: f64,
    },
    /// The disc's coverage within `[lo, hi]`: the fraction of drive sols, pooled over the
    /// runs, that ended with the truth inside the uncertainty disc.
    DiscCoverage {
        /// Bounds (fractions).
        lo: f64,
        /// Bounds (fractions).
        hi: f64,
    },
    /// The mean over runs of (strategy − baseline) on `figure` within `[lo, hi]`.
    Paired {
        /// The other strategy.
        baseline: Strategy,
        /// The figure.
        figure: Figure,
        /// Bounds.
        lo: f64,
        /// Bounds.
        hi: f64,
    },
    /// The share of paired runs with (strategy − baseline) on `figure` at most `at_most`
    /// within `[lo, hi]` (for instance the goal at least one sol sooner in ≥ 95 % of runs).
    PairedShare {
        /// The other strategy.
        baseline: Strategy,
        /// The figure.
        figure: Figure,
        /// The difference counted.
        at_most: f64,
        /// Bounds (fractions).
        lo: f64,
        /// Bounds (fractions).
        hi: f64,
    },
}

/// A validated `[[expect]]` entry that holds over a sweep (`runs = N`).
#[derive(Debug, Clone, PartialEq)]
pub struct StatisticalExpectation {
    /// Index in the file.
    pub index: usize,
    /// Human description.
    pub what: String,
    /// Strategy run.
    pub strategy: Strategy,
    /// Run indices `0..runs`.
    pub runs: u64,
    /// The error model the sweep runs under, when not the scenario's own (`errors = "stress"`).
    pub errors: Option<sim::errors::ErrorPreset>,
    /// `[operations] preemptive_shortening` for the sweep, when not the scenario's
    /// (`preemptive_shortening = false`).
    pub preemptive_shortening: Option<bool>,
    /// The checks.
    pub checks: Vec<StatCheck>,
}

impl StatisticalExpectation {
    /// The strategies this expectation needs swept.
    #[must_use]
    pub fn strategies(&self) -> Vec<Strategy> {
        let mut v = vec![self.strategy];
        for c in &self.checks {
            if let StatCheck::Paired { baseline, .. } | StatCheck::PairedShare { baseline, .. } = c
            {
                v.push(*baseline);
            }
        }
        v
    }
}

/// An `[[expect]]` entry: of one seeded run, or over a sweep.
#[derive(Debug, Clone, PartialEq)]
pub enum Resolved {
    /// Checks of one run per strategy under the scenario's seed.
    Run(Expectation),
    /// Checks over runs `0..runs`.
    Sweep(StatisticalExpectation),
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

/// One check on one quantity of a run.
#[derive(Debug, Clone, PartialEq)]
pub enum Check {
    /// The sol's fault kind (`None` = no fault).
    Fault(Option<FaultKind>),
    /// A real quantity of the sol or the run within `[lo, hi]`.
    Range {
        /// Name of the quantity as printed.
        quantity: &'static str,
        /// Bounds.
        lo: f64,
        /// Bounds.
        hi: f64,
    },
    /// Whether the sol drove.
    Drove(bool),
    /// The goal is reached at least `by` sols sooner than under `than`.
    Sooner {
        /// The other strategy.
        than: Strategy,
        /// Sols.
        by: u32,
    },
    /// Sols needed to drive `distance_m` from `from_sol`, within `[lo, hi]`.
    Covers {
        /// First sol counted.
        from_sol: u32,
        /// Metres.
        distance_m: f64,
        /// Bounds.
        lo: u32,
        /// Bounds.
        hi: u32,
    },
    /// A science campaign's members done (or failed) over the run, within `[lo, hi]`.
    Science {
        /// Campaign id.
        campaign: String,
        /// Count the members that failed rather than those done.
        failed: bool,
        /// Bounds.
        lo: u32,
        /// Bounds.
        hi: u32,
    },
}

/// A validated `[[expect]]` entry.
#[derive(Debug, Clone, PartialEq)]
pub struct Expectation {
    /// Index in the file.
    pub index: usize,
    /// Human description.
    pub what: String,
    /// Strategy run.
    pub strategy: Strategy,
    /// Sol for per-sol checks.
    pub sol: Option<u32>,
    /// The checks.
    pub checks: Vec<Check>,
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
                    let figure = Figure::from_name(&p.figure).ok_or_else(|| {
                        ScenarioError::field(
                            path,
                            f("paired.figure"),
                            format!("one of {}", Figure::ALL.map(Figure::name).join(", ")),
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
                    Some(name) => {
                        Some(sim::errors::ErrorPreset::from_name(name).ok_or_else(|| {
                            ScenarioError::field(
                                path,
                                f("errors"),
                                "\"calibrated\" or \"stress\"",
                                format!("{name:?}"),
                            )
                        })?)
                    }
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

/// One failed check.
#[derive(Debug, Clone, PartialEq)]
pub struct Mismatch {
    /// What was checked, e.g. `replay sol 385 fault_after_m`.
    pub check: String,
    /// What the file expects.
    pub expected: String,
    /// What the run gave.
    pub got: String,
}

fn fmt_opt(v: Option<f64>) -> String {
    v.map_or_else(|| "nothing".into(), |v| format!("{v:.3}"))
}

impl Expectation {
    /// The strategies this expectation needs run.
    #[must_use]
    pub fn strategies(&self) -> Vec<Strategy> {
        let mut v = vec![self.strategy];
        for c in &self.checks {
            if let Check::Sooner { than, .. } = c {
                v.push(*than);
            }
        }
        v
    }

    /// Check against the runs (`outcome(strategy)` gives each strategy's run).
    pub fn check<'a>(&self, outcome: impl Fn(Strategy) -> &'a CampaignOutcome) -> Vec<Mismatch> {
        let run = outcome(self.strategy);
        let rec = self.sol.and_then(|s| run.sol(s));
        let label = |q: &str| match self.sol {
            Some(s) => format!("{} sol {s} {q}", self.strategy.name()),
            None => format!("{} {q}", self.strategy.name()),
        };
        let mut out = Vec::new();
        for c in &self.checks {
            match c {
                Check::Fault(kind) => {
                    let got = rec.and_then(|r| r.fault.as_ref()).map(|f| f.kind);
                    if got != *kind {
                        let name = |k: Option<FaultKind>| k.map_or("none", FaultKind::name).into();
                        out.push(Mismatch {
                            check: label("fault"),
                            expected: name(*kind),
                            got: name(got),
                        });
                    }
                }
                Check::Range { quantity, lo, hi } => {
                    let got: Option<f64> = match *quantity {
                        "fault_after_m" => rec.and_then(|r| r.fault.as_ref()).map(|f| f.after_m),
                        "fault_uncertainty_m" => {
                            rec.and_then(|r| r.fault.as_ref()).map(|f| f.uncertainty_m)
                        }
                        "distance_m" => rec.map(|r| r.distance_m),
                        "end_uncertainty_m" => rec.map(|r| r.end_uncertainty_m),
                        "total_distance_m" => Some(run.totals.distance_m),
                        "max_uncertainty_m" => Some(run.totals.max_uncertainty_m),
                        "no_path_faults" => Some(f64::from(run.totals.no_path_faults)),
                        "faults" => Some(f64::from(run.totals.faults)),
                        "sols_to_goal" => run.totals.sols_to_goal.map(f64::from),
                        // The sol's plan with `sol`, every sol's otherwise.
                        "plan_violations" => Some(
                            run.sols
                                .iter()
                                .filter(|r| self.sol.is_none_or(|s| r.sol == s))
                                .filter_map(|r| r.activity_plan.as_ref())
                                .map(|p| p.violations.len() as f64)
                                .sum(),
                        ),
                        _ => None,
                    };
                    if !got.is_some_and(|g| g >= *lo - 1e-9 && g <= *hi + 1e-9) {
                        out.push(Mismatch {
                            check: label(quantity),
                            expected: format!("[{lo}, {hi}]"),
                            got: fmt_opt(got),
                        });
                    }
                }
                Check::Drove(d) => {
                    let got = rec.map(|r| r.drove);
                    if got != Some(*d) {
                        out.push(Mismatch {
                            check: label("drove"),
                            expected: d.to_string(),
                            got: got.map_or("nothing".into(), |g| g.to_string()),
                        });
                    }
                }
                Check::Sooner { than, by } => {
                    let mine = run.totals.sols_to_goal;
                    let theirs = outcome(*than).totals.sols_to_goal;
                    let ok = match (mine, theirs) {
                        (Some(m), Some(t)) => m + by <= t,
                        (Some(_), None) => true,
                        _ => false,
                    };
                    if !ok {
                        out.push(Mismatch {
                            check: label(&format!("sols_to_goal vs {}", than.name())),
                            expected: format!(
                                "at least {by} fewer than {}",
                                theirs.map_or("never".into(), |t| t.to_string())
                            ),
                            got: mine.map_or("goal not reached".into(), |m| m.to_string()),
                        });
                    }
                }
                Check::Science {
                    campaign,
                    failed,
                    lo,
                    hi,
                } => {
                    let got = run
                        .totals
                        .science
                        .get(campaign)
                        .map(|t| if *failed { t.failed } else { t.done });
                    let what = if *failed { "failed" } else { "done" };
                    if !got.is_some_and(|g| g >= *lo && g <= *hi) {
                        out.push(Mismatch {
                            check: label(&format!("science {campaign} {what}")),
                            expected: format!("[{lo}, {hi}]"),
                            got: got.map_or("no such campaign".into(), |g| g.to_string()),
                        });
                    }
                }
                Check::Covers {
                    from_sol,
                    distance_m,
                    lo,
                    hi,
                } => {
                    let got = run.sols_to_cover(*from_sol, *distance_m);
                    if !got.is_some_and(|g| g >= *lo && g <= *hi) {
                        out.push(Mismatch {
                            check: label(&format!(
                                "sols to cover {distance_m} m from sol {from_sol}"
                            )),
                            expected: format!("[{lo}, {hi}]"),
                            got: got.map_or("never".into(), |g| g.to_string()),
                        });
                    }
                }
            }
        }
        out
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
