//! The EKF of `localization::ekf` (paper 004) against an independent one: filterpy's
//! `ExtendedKalmanFilter` (`peers/ekf_filterpy.py`) fed exactly the same streams — IMU samples,
//! ranges with the orbiter's position, terrain fixes — and the same `x̂₀`, `P₀`, `Q`, `R`. The
//! script writes the rover model, its RK4 step, the transition matrix and the range model again
//! in numpy, so this checks them as well as the Kalman algebra.
//!
//! Every second's state and covariance must agree to 1e-6, relative to each component's own
//! scale: `|Δx_i| ≤ 1e-6·max(|x_i|, σ_i)` and `|ΔP_ij| ≤ 1e-6·√(P_ii P_jj)` (absolute 1e-6 would
//! say nothing about the biases, ~3e-3 m/s², nor the 10⁻¹¹ gyro-bias variance).
//!
//! filterpy runs from `peers/.venv`; without it the check is skipped with a message on stderr,
//! unless `CI` is set (`.ci/run` creates the venv), then it fails.

use crate::common;

use std::time::Duration;

use localization::ekf::{
    CaseRun, CaseSettings, FilterModel, MARS_RADIUS_M, STATE_DIM, Table1Case, run_with,
};
use serde_json::{Value, json};

/// The peer's input: frame, filter tuning and streams of `run`.
fn peer_input(run: &CaseRun) -> Value {
    let frame = &run.settings.frame;
    let t = &run.tuning;
    let matrix = |m: &localization::ekf::StateCovariance| -> Vec<Vec<f64>> {
        (0..STATE_DIM)
            .map(|i| (0..STATE_DIM).map(|j| m[(i, j)]).collect())
            .collect()
    };
    json!({
        "frame": {
            "latitude_deg": frame.site.latitude_deg,
            "longitude_deg": frame.site.longitude_deg,
            "radius_m": MARS_RADIUS_M,
            "rotation_rad_per_s": frame.rotation_rad_per_s,
            "prime_meridian_at_epoch_rad": frame.prime_meridian_at_epoch_rad,
        },
        "x0": t.initial_state.iter().collect::<Vec<_>>(),
        "P0": matrix(&t.initial_covariance),
        "Q": matrix(&t.process_noise),
        "range_variance_m2": t.range_variance_m2,
        "fix_variance_m2": t.fix_variance_m2,
        "imu": run.streams.imu.iter().map(|u| json!({
            "t_s": u.t_s,
            "accel": u.accel_body_m_per_s2.iter().collect::<Vec<_>>(),
            "yaw_rate": u.yaw_rate_rad_per_s,
        })).collect::<Vec<_>>(),
        "ranges": run.streams.ranges.iter().map(|r| json!({
            "t_s": r.t_s,
            "range_m": r.range_m,
            "orbiter_mci_m": r.orbiter_position_mci_m.iter().collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
        "fixes": run.streams.fixes.iter().map(|f| json!({
            "t_s": f.t_s,
            "enu_m": f.position_enu_m.iter().collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
    })
}

/// Largest absolute and scaled differences seen, and where.
#[derive(Debug, Default)]
struct Worst {
    abs_state: f64,
    rel_state: f64,
    abs_cov: f64,
    rel_cov: f64,
    at: String,
}

fn compare(run: &CaseRun, peer: &Value, label: &str) -> Worst {
    let steps = peer["steps"].as_array().expect("steps");
    assert_eq!(
        steps.len(),
        run.steps.len(),
        "{label}: one peer step per second"
    );
    let mut worst = Worst::default();
    for (ours, theirs) in run.steps.iter().zip(steps) {
        let t_s = ours.truth.t_s;
        assert_eq!(theirs["t_s"].as_u64(), Some(u64::from(t_s)), "{label}");
        let x: Vec<f64> = serde_json::from_value(theirs["x"].clone()).expect("x");
        let p: Vec<Vec<f64>> = serde_json::from_value(theirs["P"].clone()).expect("P");
        for i in 0..STATE_DIM {
            let d = (ours.estimate[i] - x[i]).abs();
            let scale = ours.estimate[i].abs().max(ours.covariance[(i, i)].sqrt());
            let rel = if d == 0.0 { 0.0 } else { d / scale };
            assert!(
                rel <= 1e-6,
                "{label} t = {t_s} s: x[{i}] = {} here, {} in filterpy",
                ours.estimate[i],
                x[i]
            );
            worst.abs_state = worst.abs_state.max(d);
            if rel > worst.rel_state {
                worst.rel_state = rel;
                worst.at = format!("x[{i}] at t = {t_s} s");
            }
            for (j, theirs_ij) in p[i].iter().enumerate() {
                let d = (ours.covariance[(i, j)] - theirs_ij).abs();
                let scale = (ours.covariance[(i, i)] * ours.covariance[(j, j)]).sqrt();
                let rel = if d == 0.0 { 0.0 } else { d / scale };
                assert!(
                    rel <= 1e-6,
                    "{label} t = {t_s} s: P[{i},{j}] = {} here, {theirs_ij} in filterpy",
                    ours.covariance[(i, j)]
                );
                worst.abs_cov = worst.abs_cov.max(d);
                worst.rel_cov = worst.rel_cov.max(rel);
            }
        }
    }
    worst
}

#[test]
fn the_ekf_matches_filterpy_on_the_same_streams() {
    let runs = [
        (
            "case 2, bias-estimating",
            Table1Case::Case2,
            FilterModel::BiasEstimating,
        ),
        (
            "case 4, bias-estimating",
            Table1Case::Case4,
            FilterModel::BiasEstimating,
        ),
        (
            "case 2, paper 4-state",
            Table1Case::Case2,
            FilterModel::Paper,
        ),
    ];
    let runs: Vec<_> = runs
        .into_iter()
        .map(|(label, case, model)| {
            let run = run_with(&CaseSettings::table1(case).with_model(model), 5).expect("valid");
            assert!(!run.streams.ranges.is_empty() && !run.streams.fixes.is_empty());
            (label, run)
        })
        .collect();
    let Some(python) = common::peers_python(
        "the filterpy cross-check of the EKF (only the Rust unit tests of localization::ekf ran)",
    ) else {
        return;
    };
    let dir = tempfile::tempdir().expect("tempdir");
    for (label, run) in &runs {
        let input = dir.path().join("run.json");
        let output = dir.path().join("filterpy.json");
        std::fs::write(&input, peer_input(run).to_string()).expect("write");
        let o = common::output_within(
            std::process::Command::new(&python)
                .arg(common::root().join("peers/ekf_filterpy.py"))
                .arg(&input)
                .arg(&output),
            Duration::from_secs(120),
        );
        assert!(
            o.status.success(),
            "{label}: {}\n(a venv made before filterpy joined peers/requirements.txt lacks it: \
             peers/.venv/bin/pip install -r peers/requirements.txt)",
            common::stderr(&o)
        );
        let peer: Value =
            serde_json::from_slice(&std::fs::read(&output).expect("the peer wrote its output"))
                .expect("the peer writes JSON");
        let worst = compare(run, &peer, label);
        eprintln!(
            "{label} (filterpy {}): max |Δx| {:.2e}, max |Δx|/scale {:.2e} ({}), max |ΔP| {:.2e}, \
             max |ΔP|/√(PᵢᵢPⱼⱼ) {:.2e}",
            peer["filterpy"],
            worst.abs_state,
            worst.rel_state,
            worst.at,
            worst.abs_cov,
            worst.rel_cov
        );
    }
}
