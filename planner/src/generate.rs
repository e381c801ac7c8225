//! Seeded random instances for tests, benchmarks and the CP-SAT comparison script.
//!
//! The same seed and settings give the same [`Problem`] on every platform (ChaCha8).

use crate::problem::{Activity, ActivityKind, Campaign, CampaignIntent, Drive, Problem};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// What [`generate`] builds. Plain settings; defaults in `impl Default`.
#[derive(Debug, Clone, PartialEq)]
pub struct GeneratorSettings {
    /// Optional science activities (with windows, power, data, tier 1 or 2). (default: 20)
    pub n_optional: usize,
    /// Mandatory communication passes at fixed times that downlink data. (default: 2)
    pub n_comm_passes: usize,
    /// Precedences between optional activities ("b must come after a"). (default: 3)
    pub n_precedences: usize,
    /// Energy available over the window (initial + recharge) as a fraction of the total
    /// demand of all activities, 0 < f. (default: 0.4)
    pub energy_fraction: f64,
    /// Data capacity as a fraction of the total data of all activities, 0 < f. (default: 0.5)
    pub data_fraction: f64,
    /// Add a heating activity and a drive (split into up to 3 segments) that needs it.
    /// (default: false)
    pub with_drive: bool,
    /// Put about a third of the optional activities into a goal-set campaign with
    /// `min_count` 2, `max_count` 3 and decay 0.7. (default: false)
    pub with_campaign: bool,
}

impl Default for GeneratorSettings {
    fn default() -> Self {
        Self {
            n_optional: 20,
            n_comm_passes: 2,
            n_precedences: 3,
            energy_fraction: 0.4,
            data_fraction: 0.5,
            with_drive: false,
            with_campaign: false,
        }
    }
}

/// A random one-sol problem: window 09:00–17:00, tiers 1 and 2, integer utilities 1–10.
#[must_use]
pub fn generate(seed: u64, settings: &GeneratorSettings) -> Problem {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let start_s = 9 * 3600;
    let end_s = 17 * 3600;
    let mut activities = Vec::new();
    for i in 0..settings.n_optional {
        let duration_s = 60 * rng.random_range(10..=60i64);
        let earliest = rng.random_range(start_s..=end_s - duration_s);
        let slack = 60 * rng.random_range(0..=180i64);
        let latest = (earliest + slack).min(end_s - duration_s);
        let mut a = Activity::task(
            format!("obs{i}"),
            duration_s,
            [earliest, latest],
            f64::from(rng.random_range(5..=40u32)),
            f64::from(rng.random_range(1..=10u32)),
        );
        a.data_mb = f64::from(rng.random_range(0..=200u32));
        a.tier = if rng.random_bool(0.3) { 1 } else { 2 };
        activities.push(a);
    }
    let mut campaigns = Vec::new();
    if settings.with_campaign && settings.n_optional >= 2 {
        let tier = if rng.random_bool(0.5) { 1 } else { 2 };
        campaigns.push(Campaign {
            id: "goalset".into(),
            intent: CampaignIntent::GoalSet,
            tier,
            min_count: 2,
            max_count: 3,
            utility: f64::from(rng.random_range(2..=8u32)),
            decay: 0.7,
        });
        for a in activities.iter_mut().step_by(3) {
            a.campaign = Some("goalset".into());
            a.utility = 0.0;
        }
    }
    for _ in 0..settings.n_precedences {
        if settings.n_optional < 2 {
            break;
        }
        let i = rng.random_range(0..settings.n_optional - 1);
        let j = rng.random_range(i + 1..settings.n_optional);
        let pre = activities[i].id.clone();
        if !activities[j].preconditions.contains(&pre) {
            activities[j].preconditions.push(pre);
        }
    }
    if settings.with_drive {
        let heat_start = rng.random_range(start_s..=start_s + 3 * 3600);
        let mut heat = Activity::task("heat", 600, [heat_start, heat_start + 3600], 25.0, 0.0);
        heat.tier = 2;
        let length_m = f64::from(rng.random_range(40..=100u32));
        let mut drive = Activity::task("drive", 0, [heat_start + 600, end_s - 3600], 35.0, 6.0);
        drive.kind = ActivityKind::Drive(Drive {
            length_m,
            rate_m_per_h: 60.0,
            min_segment_s: 1200,
            max_segments: 3,
            split_at_m: Vec::new(),
            latest_end_s: None,
        });
        drive.tier = 2;
        drive.data_mb = 20.0;
        drive.preconditions = vec!["heat".into()];
        activities.push(heat);
        activities.push(drive);
    }
    for k in 0..settings.n_comm_passes {
        let span = (end_s - start_s - 600) as f64;
        let at = start_s + (span * (k as f64 + 0.5) / settings.n_comm_passes as f64) as i64;
        let mut a = Activity::task(format!("comm{k}"), 600, [at, at], 10.0, 0.0);
        a.mandatory = true;
        a.downlink_mb = f64::from(rng.random_range(150..=400u32));
        activities.push(a);
    }
    let window_h = (end_s - start_s) as f64 / 3600.0;
    let demand_wh: f64 = activities
        .iter()
        .map(|a| a.power_w * a.duration_s() as f64 / 3600.0)
        .sum();
    let budget_wh = (settings.energy_fraction * demand_wh).max(1.0);
    let recharge_w = 0.5 * budget_wh / window_h;
    let initial_energy_wh = budget_wh - recharge_w * window_h;
    let biggest_wh = activities
        .iter()
        .map(|a| a.power_w * a.duration_s() as f64 / 3600.0)
        .fold(0.0, f64::max);
    let battery_capacity_wh = (1.25 * initial_energy_wh).max(biggest_wh).max(1.0);
    let total_mb: f64 = activities.iter().map(|a| a.data_mb).sum();
    let biggest_mb = activities.iter().map(|a| a.data_mb).fold(0.0, f64::max);
    let data_capacity_mb = (settings.data_fraction * total_mb).max(biggest_mb).max(1.0);
    Problem {
        start_s,
        end_s,
        battery_capacity_wh,
        initial_energy_wh,
        recharge_w,
        data_capacity_mb,
        initial_data_mb: 0.0,
        activities,
        campaigns,
    }
}

/// The B6 benchmark instance (`BENCHMARKS.md`, "Activity planner"): [`generate`] with
/// `n_optional` optional activities, 2 mandatory comm passes, `n_optional / 4` precedences,
/// 40 % energy and 50 % data, no drive and no campaign, then *quantised* so that an exact
/// integer model (OR-Tools CP-SAT, `peers/planner_cpsat.py`) states the very same problem:
///
/// - `recharge_w` and `initial_energy_wh` are rounded down to multiples of 1/16 (W, Wh), so
///   `3600 × 16 ×` every energy level at an integer second is an integer, and the planner's
///   `f64` feasibility tests (slack [`ENERGY_EPS_WH`](crate::ENERGY_EPS_WH) = 10⁻⁹ Wh) decide
///   exactly as the integer ones do (the smallest nonzero level is 1/57 600 Wh ≫ 10⁻⁹);
/// - `battery_capacity_wh` is raised to `initial + recharge × window` (+1 Wh): no level can
///   reach it (a task never charges faster than idling), so the capacity clipping of the
///   planner's battery never binds and the peer need not model it;
/// - `data_capacity_mb` is rounded down to whole MB (all data volumes are whole MB).
#[must_use]
pub fn b6_problem(n_optional: usize, seed: u64) -> Problem {
    let settings = GeneratorSettings {
        n_optional,
        n_precedences: n_optional / 4,
        ..GeneratorSettings::default()
    };
    let mut p = generate(seed, &settings);
    let q = |x: f64| (x * 16.0).floor() / 16.0;
    p.recharge_w = q(p.recharge_w);
    p.initial_energy_wh = q(p.initial_energy_wh);
    let window_h = (p.end_s - p.start_s) as f64 / 3600.0;
    let biggest_wh = p
        .activities
        .iter()
        .map(|a| a.power_w * a.duration_s() as f64 / 3600.0)
        .fold(0.0, f64::max);
    p.battery_capacity_wh = (p.initial_energy_wh + p.recharge_w * window_h + 1.0)
        .ceil()
        .max(biggest_wh.ceil() + 1.0);
    p.data_capacity_mb = p.data_capacity_mb.floor();
    p
}
