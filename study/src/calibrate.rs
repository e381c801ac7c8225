//! Calibrations against the historic record: a calibrated constant of the model is re-derived
//! here, by the command its documentation names, so anyone can check it.
//!
//! - [`calibrate_vo`] (`solsim calibrate vo SCENARIO`): the VO failure probability on soil,
//!   [`sim::rover::errors::VO_FAILURE_SOIL`], from a record's distance without VO.
//! - [`calibrate_drive_rate`] (`solsim calibrate drive-rate SCENARIO`): the AutoNav rate at
//!   which the ground strategy drives the record's metres per drive sol.

use std::fmt::Write as _;

use rayon::prelude::*;

use maps::PerTerrain;
use sim::Strategy;
use sim::rover::errors::{VO_FAILURE_RELATIVE, VO_FAILURE_SOIL};

use crate::Scenario;

/// What [`calibrate_vo`] found.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct VoCalibration {
    /// The scenario.
    pub scenario: String,
    /// Ground re-simulations the terrain shares come from.
    pub runs: u64,
    /// The record's distance over the sols with history, metres.
    pub record_distance_m: f64,
    /// Of which without VO, metres.
    pub record_novo_m: f64,
    /// Share of the re-simulated ground drives' distance on each terrain class (sums to 1).
    pub terrain_share: PerTerrain,
    /// The relative failure rates per class (judgement, [`VO_FAILURE_RELATIVE`]).
    pub relative: PerTerrain,
    /// The solved VO failure probability per step on soil.
    pub vo_failure_soil: f64,
    /// The value the code ships ([`VO_FAILURE_SOIL`]).
    pub shipped_vo_failure_soil: f64,
    /// Under the shipped value: mean metres without VO over the re-simulated drives, scaled to
    /// the record's distance.
    pub simulated_novo_m: f64,
    /// 95 % normal interval of that mean over the runs.
    pub simulated_novo_interval_m: [f64; 2],
}

/// Why a calibration cannot run.
#[derive(Debug, thiserror::Error)]
pub enum CalibrationError {
    /// The scenario has no historic distance to calibrate to.
    #[error(
        "{0}: no historic record to calibrate to (needs sols with historic_distance_m > 0 and historic_novo_m)"
    )]
    NoRecord(String),
    /// The ground re-simulations never drove.
    #[error("{0}: the ground strategy drove no distance in any run; nothing to calibrate")]
    NoDrive(String),
    /// Zero runs.
    #[error("--runs must be at least 2 (got {0})")]
    TooFewRuns(u64),
    /// The historic drive sols drive at their own speeds (their distance over their window,
    /// from the record's clock): the rover's rate sets only the sols without one.
    #[error(
        "{0}: its historic drive sols drive at their own speeds (distance over window, from the record's clock); the rover's rate sets only the sols without one, the record's mean speed, so there is nothing to calibrate against the record"
    )]
    OwnSpeeds(String),
}

/// Solve the VO failure probability on soil so that the expected distance without VO over the
/// terrain a re-simulated ground drive crosses equals the record's:
/// `p_soil · Σ_class share_class · relative_class / (1 − slip_class) = record_novo /
/// record_distance` (a failed step charges its whole commanded length, a VO step the length
/// after slip).
///
/// The shares come from `runs` ground re-simulations (run indices 0..runs, in parallel; the
/// result does not depend on the thread count). The same runs, under the shipped value, give
/// the simulated distance without VO to set against the record.
///
/// # Errors
/// [`CalibrationError`] when the scenario has no record, or nothing drove.
pub fn calibrate_vo(scenario: &Scenario, runs: u64) -> Result<VoCalibration, CalibrationError> {
    if runs < 2 {
        return Err(CalibrationError::TooFewRuns(runs));
    }
    let historic: Vec<_> = scenario
        .settings
        .calendar
        .sols
        .iter()
        .filter_map(|s| s.historic)
        .collect();
    let record_distance_m: f64 = historic.iter().map(|h| h.distance_m).sum();
    let record_novo_m: f64 = historic.iter().map(|h| h.novo_m).sum();
    if record_distance_m.is_nan() || record_distance_m <= 0.0 {
        return Err(CalibrationError::NoRecord(scenario.name.clone()));
    }
    let per_run: Vec<(PerTerrain, f64)> = (0..runs)
        .into_par_iter()
        .map(|r| {
            let o = scenario.run_index(Strategy::Ground, r);
            let mut t = PerTerrain::default();
            let mut novo = 0.0;
            for s in &o.sols {
                t += s.terrain_m;
                novo += s.d_novo_m;
            }
            (t, novo)
        })
        .collect();
    let mut terrain = PerTerrain::default();
    for (t, _) in &per_run {
        terrain += *t;
    }
    let total = terrain.total();
    if total.is_nan() || total <= 0.0 {
        return Err(CalibrationError::NoDrive(scenario.name.clone()));
    }
    let share = PerTerrain {
        sand: terrain.sand / total,
        soil: terrain.soil / total,
        bedrock: terrain.bedrock / total,
    };
    // A step without VO charges the commanded length (wheel odometry, blind to slip), a step
    // with VO about (1 − slip) of it, so per metre of odometry a class charges
    // p · relative / (1 − mean slip) metres without VO (to first order in the slip spread).
    let slip = scenario.settings.rover.errors.slip_fraction;
    let weight = share.sand * VO_FAILURE_RELATIVE.sand / (1.0 - slip.sand)
        + share.soil * VO_FAILURE_RELATIVE.soil / (1.0 - slip.soil)
        + share.bedrock * VO_FAILURE_RELATIVE.bedrock / (1.0 - slip.bedrock);
    let vo_failure_soil = record_novo_m / record_distance_m / weight;
    // Simulated metres without VO per metre driven, per run, scaled to the record's distance.
    let scaled: Vec<f64> = per_run
        .iter()
        .map(|(t, novo)| {
            let d = t.total();
            if d > 0.0 {
                novo / d * record_distance_m
            } else {
                0.0
            }
        })
        .collect();
    let n = scaled.len() as f64;
    let mean = scaled.iter().sum::<f64>() / n;
    let var = scaled.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    let half = 1.959_963_984_540_054 * (var / n).sqrt();
    Ok(VoCalibration {
        scenario: scenario.name.clone(),
        runs,
        record_distance_m,
        record_novo_m,
        terrain_share: share,
        relative: VO_FAILURE_RELATIVE,
        vo_failure_soil,
        shipped_vo_failure_soil: VO_FAILURE_SOIL,
        simulated_novo_m: mean,
        simulated_novo_interval_m: [mean - half, mean + half],
    })
}

/// What [`calibrate_drive_rate`] found.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct DriveRateCalibration {
    /// The scenario.
    pub scenario: String,
    /// Ground re-simulations per evaluated rate.
    pub runs: u64,
    /// The record's metres per drive sol (its distance over the sols it drove).
    pub record_m_per_drive_sol: f64,
    /// The scenario's own AutoNav rate, m/h.
    pub scenario_rate_m_per_h: f64,
    /// The ground strategy's mean metres per drive sol at the scenario's rate.
    pub ground_m_per_drive_sol_at_scenario_rate: f64,
    /// The rate at which the ground strategy's mean metres per drive sol equals the record's.
    pub calibrated_rate_m_per_h: f64,
    /// The ground strategy's mean metres per drive sol at the calibrated rate.
    pub ground_m_per_drive_sol_at_calibrated_rate: f64,
}

/// The ground strategy's metres per drive sol, pooled over run indices `0..runs`, at AutoNav
/// rate `rate_m_per_h`.
fn ground_m_per_drive_sol(scenario: &Scenario, rate_m_per_h: f64, runs: u64) -> f64 {
    let mut s = scenario.clone();
    s.settings.rover.drive_rate_m_per_h = rate_m_per_h;
    // The rate is AutoNav's: measured with no drive shortened before a passage (the record
    // has none; the passages of a map are placed where the record met them early in a sol).
    s.settings.rules.preemptive_shortening = false;
    // The sols the record drove to their end (a drive that faulted says nothing of the rate),
    // where ground drove to its end too.
    let cal = &scenario.settings.calendar;
    let per_run: Vec<(f64, u32)> = (0..runs)
        .into_par_iter()
        .map(|r| {
            let o = s.run_index(Strategy::Ground, r);
            o.sols
                .iter()
                .zip(&cal.sols)
                .filter(|(g, e)| {
                    g.drove
                        && g.fault.is_none()
                        && e.historic
                            .is_some_and(|h| h.distance_m > 0.0 && !h.ended_in_fault)
                })
                .fold((0.0, 0), |(d, n), (g, _)| (d + g.distance_m, n + 1))
        })
        .collect();
    let d: f64 = per_run.iter().map(|p| p.0).sum();
    let n: u32 = per_run.iter().map(|p| p.1).sum();
    if n == 0 { 0.0 } else { d / f64::from(n) }
}

/// Solve the AutoNav drive rate at which the re-simulated ground strategy drives as many metres
/// per drive sol as the record, over the sols both drove to their end: a drive that faulted
/// (sol 385's 14 m) says nothing of the rate. Bisection on the rate between 10 % and 300 % of the scenario's, 40 steps; each step
/// runs `runs` ground re-simulations (run indices 0..runs, common to every step), with
/// pre-emptive shortening off: no historic drive was shortened for a passage.
///
/// # Errors
/// [`CalibrationError`] when the scenario has no record or the ground never drives.
pub fn calibrate_drive_rate(
    scenario: &Scenario,
    runs: u64,
) -> Result<DriveRateCalibration, CalibrationError> {
    if runs < 2 {
        return Err(CalibrationError::TooFewRuns(runs));
    }
    let unfaulted = |e: &&sim::SolEntry| {
        e.historic
            .is_some_and(|h| h.distance_m > 0.0 && !h.ended_in_fault)
    };
    let cal_sols = &scenario.settings.calendar.sols;
    if cal_sols
        .iter()
        .filter(unfaulted)
        .any(|e| e.drive_rate_m_per_h.is_some())
    {
        return Err(CalibrationError::OwnSpeeds(scenario.name.clone()));
    }
    let driven: Vec<f64> = scenario
        .settings
        .calendar
        .sols
        .iter()
        .filter_map(|s| s.historic)
        .filter(|h| h.distance_m > 0.0 && !h.ended_in_fault)
        .map(|h| h.distance_m)
        .collect();
    if driven.is_empty() {
        return Err(CalibrationError::NoRecord(scenario.name.clone()));
    }
    let target = driven.iter().sum::<f64>() / driven.len() as f64;
    let own = scenario.settings.rover.drive_rate_m_per_h;
    let at_own = ground_m_per_drive_sol(scenario, own, runs);
    if at_own <= 0.0 {
        return Err(CalibrationError::NoDrive(scenario.name.clone()));
    }
    // Metres per drive sol grow with the rate (the drives are time-limited): bisect.
    let (mut lo, mut hi) = (0.1 * own, 3.0 * own);
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if ground_m_per_drive_sol(scenario, mid, runs) < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let rate = 0.5 * (lo + hi);
    Ok(DriveRateCalibration {
        scenario: scenario.name.clone(),
        runs,
        record_m_per_drive_sol: target,
        scenario_rate_m_per_h: own,
        ground_m_per_drive_sol_at_scenario_rate: at_own,
        calibrated_rate_m_per_h: rate,
        ground_m_per_drive_sol_at_calibrated_rate: ground_m_per_drive_sol(scenario, rate, runs),
    })
}

impl VoCalibration {
    /// The printed report: the record, the terrain under the re-simulated drives, the solved
    /// and the shipped value, and the distance without VO the shipped value gives.
    #[must_use]
    pub fn text(&self) -> String {
        let c = self;
        let pct = |x: f64| 100.0 * x;
        let mut t = String::new();
        let _ = writeln!(
            t,
            "{} — VO failure calibration over {} ground re-simulations",
            c.scenario, c.runs
        );
        let _ = writeln!(
            t,
            "record: {:.3} m without VO in {:.1} m ({:.4} % of distance)",
            c.record_novo_m,
            c.record_distance_m,
            pct(c.record_novo_m / c.record_distance_m)
        );
        let _ = writeln!(
            t,
            "terrain under the re-simulated drives: sand {:.1} %, soil {:.1} %, bedrock {:.1} %",
            pct(c.terrain_share.sand),
            pct(c.terrain_share.soil),
            pct(c.terrain_share.bedrock)
        );
        let _ = writeln!(
            t,
            "relative failure rates (judgement): sand {}, soil {}, bedrock {}",
            c.relative.sand, c.relative.soil, c.relative.bedrock
        );
        let _ = writeln!(
            t,
            "solved VO failure probability per step on soil: {:.3e} (shipped: {:.3e}, sim::rover::errors::VO_FAILURE_SOIL)",
            c.vo_failure_soil, c.shipped_vo_failure_soil
        );
        let _ = writeln!(
            t,
            "with the shipped value, metres without VO over the record's distance: {:.3} m [95 % interval {:.3}, {:.3}] (record {:.3} m)",
            c.simulated_novo_m,
            c.simulated_novo_interval_m[0],
            c.simulated_novo_interval_m[1],
            c.record_novo_m
        );
        t
    }
}

impl DriveRateCalibration {
    /// The printed report: the record's metres per drive sol, what ground drives at the
    /// scenario's rate, and the calibrated rate.
    #[must_use]
    pub fn text(&self) -> String {
        let c = self;
        format!(
            "{} — drive rate calibration over {} ground re-simulations per step\n\
             record: {:.1} m per drive sol\n\
             at the scenario's rate, {:.1} m/h: ground drives {:.1} m per drive sol\n\
             calibrated rate: {:.1} m/h (ground then drives {:.1} m per drive sol)\n",
            c.scenario,
            c.runs,
            c.record_m_per_drive_sol,
            c.scenario_rate_m_per_h,
            c.ground_m_per_drive_sol_at_scenario_rate,
            c.calibrated_rate_m_per_h,
            c.ground_m_per_drive_sol_at_calibrated_rate
        )
    }
}
