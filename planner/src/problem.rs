//! The planning problem for one sol, exactly as a user (or a JSON file) states it.
//!
//! [`Problem`] is the serde-facing description; [`Instance::new`](crate::Instance::new)
//! validates it and splits drives into segments. Times are integer seconds after local
//! midnight, energies watt-hours, powers watts, data megabytes, distances metres.
//!
//! ## JSON
//! Every struct here derives `Serialize`/`Deserialize` with `deny_unknown_fields`, so a typo in
//! a field name is an error rather than a silent default. Optional fields are marked
//! "(default: …)". A minimal activity:
//! `{"id": "pancam", "kind": {"type": "task", "duration_s": 600}, "earliest_start_s": 36000,
//!   "latest_start_s": 50000, "power_w": 20.0, "utility": 3.0}`.

use serde::{Deserialize, Serialize};

/// One sol's planning problem (paper 003 §3.1): a time window, the rover's resources and the
/// candidate activities and campaigns.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Problem {
    /// Start of the planning window, seconds after local midnight (0 ..= 86 400 × 2).
    pub start_s: i64,
    /// End of the planning window, seconds after local midnight; every activity ends by then.
    pub end_s: i64,
    /// Battery capacity in Wh (> 0). Recharge beyond it is clipped (lost).
    pub battery_capacity_wh: f64,
    /// Battery energy at `start_s` in Wh (0 ..= `battery_capacity_wh`).
    pub initial_energy_wh: f64,
    /// Net recharge power in W while idle: solar input minus the idle (sleep, survival heating)
    /// load, constant over the window (≥ 0). During an activity the battery changes at
    /// `recharge_w - power_w`.
    pub recharge_w: f64,
    /// Onboard data volume available for new products, MB (> 0).
    pub data_capacity_mb: f64,
    /// Data already stored at `start_s`, MB (0 ..= `data_capacity_mb`). (default: 0)
    #[serde(default)]
    pub initial_data_mb: f64,
    /// Candidate activities: optional goals, mandatory activities and auxiliary ones.
    pub activities: Vec<Activity>,
    /// Campaign intents that turn counts of member activities into utility. (default: none)
    #[serde(default)]
    pub campaigns: Vec<Campaign>,
}

/// One candidate activity (a goal, a mandatory communication pass, an auxiliary heating, a
/// drive).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Activity {
    /// Unique id, used by preconditions and in plans.
    pub id: String,
    /// Human-readable name for reports. (default: empty)
    #[serde(default)]
    pub name: String,
    /// A fixed-duration task or a drive the planner may split.
    pub kind: ActivityKind,
    /// Earliest start, s after midnight (≥ the problem's `start_s`).
    pub earliest_start_s: i64,
    /// Latest start, s after midnight (≥ `earliest_start_s`; start + duration ≤ `end_s`). For a
    /// drive this window constrains its first segment; later segments only have to end by
    /// `end_s`.
    pub latest_start_s: i64,
    /// Average power drawn above the idle load while the activity runs, W (≥ 0).
    pub power_w: f64,
    /// Data volume produced, MB (≥ 0), counted when the activity ends. (default: 0)
    #[serde(default)]
    pub data_mb: f64,
    /// Data volume downlinked, MB (≥ 0), freed when the activity ends after its own
    /// `data_mb` is added — set it on communication passes. (default: 0)
    #[serde(default)]
    pub downlink_mb: f64,
    /// Ids of activities that must have ended before this one starts (auxiliary activities
    /// such as heating before a drive are modelled this way). (default: none)
    #[serde(default)]
    pub preconditions: Vec<String>,
    /// A mandatory activity must be in every plan (e.g. a relay pass at a fixed time: set
    /// `earliest_start_s == latest_start_s`). (default: false)
    #[serde(default)]
    pub mandatory: bool,
    /// Id of the campaign this activity counts towards. (default: none)
    #[serde(default)]
    pub campaign: Option<String>,
    /// Priority tier of `utility`, 1 (highest) ..= [`MAX_TIERS`](crate::MAX_TIERS). (default: 1)
    #[serde(default = "default_tier")]
    pub tier: u8,
    /// Utility points earned when the activity is in the plan (0 ..=
    /// [`MAX_UTILITY`](crate::MAX_UTILITY)); for a drive, what the whole drive earns, a plan
    /// that drives part of it earning that fraction (its metres over the drive's length). Campaign members usually leave it at 0 and let the campaign score them.
    /// (default: 0)
    #[serde(default)]
    pub utility: f64,
    /// State-based window `[lo, hi]`: the metres driven (over all drives in the plan, plus the
    /// state's `driven_m`) when this activity starts must lie within it (paper 003 §3,
    /// state-based sampling). (default: none)
    #[serde(default)]
    pub driven_window_m: Option<[f64; 2]>,
    /// The sequencing timeline(s) the activity holds while it runs: `"main"`, `"hbs_link"`
    /// (runs while main-timeline activities run) or `"main_and_hbs_link"`; see [`Timeline`].
    /// (default: `"main"`)
    #[serde(default, skip_serializing_if = "Timeline::is_main")]
    pub timeline: Timeline,
}

/// The exclusive resources an activity can hold: the rover's main sequencing timeline and the
/// serial link to the Helicopter Base Station co-processor (paper 000 §4, §6: the inputs of an
/// onboard localization take ~30 min to cross it, "in parallel with other ongoing rover
/// activities").
///
/// Two activities that hold a common timeline never overlap; an activity on the link alone
/// runs while main-timeline activities run. Preconditions still order activities across
/// timelines (a co-processor run waits for its transfer to end). Every activity of a problem
/// that uses only [`Timeline::Main`] is planned exactly as on a single timeline.
///
/// An activity on the link alone moves files and runs the co-processor: it produces and
/// downlinks no data, is not a drive and has no state-based window (checked by
/// [`Instance::new`](crate::Instance::new)). Its power adds to that of the main-timeline
/// activity it overlaps.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Timeline {
    /// The rover's main sequencing timeline, one activity at a time (the default).
    #[default]
    Main,
    /// The link to the co-processor (and the co-processor behind it) alone, one activity at
    /// a time, concurrently with the main timeline.
    HbsLink,
    /// Both timelines at once (an activity that needs the rover's sequencing and the link).
    MainAndHbsLink,
}

impl Timeline {
    /// Whether this is [`Timeline::Main`] (the serde default, left out when serialising).
    #[must_use]
    pub fn is_main(&self) -> bool {
        *self == Timeline::Main
    }

    /// Whether the activity holds the main timeline.
    #[must_use]
    pub fn uses_main(self) -> bool {
        self != Timeline::HbsLink
    }

    /// Whether the activity holds the HBS link.
    #[must_use]
    pub fn uses_link(self) -> bool {
        self != Timeline::Main
    }

    /// The name in problem files: `main`, `hbs_link` or `main_and_hbs_link`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Timeline::Main => "main",
            Timeline::HbsLink => "hbs_link",
            Timeline::MainAndHbsLink => "main_and_hbs_link",
        }
    }

    /// Whether two activities on `self` and `other` may not overlap (they share a timeline).
    #[must_use]
    pub fn shares(self, other: Timeline) -> bool {
        (self.uses_main() && other.uses_main()) || (self.uses_link() && other.uses_link())
    }
}

fn default_tier() -> u8 {
    1
}

/// What an activity does with time.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum ActivityKind {
    /// A fixed-duration activity.
    Task {
        /// Duration in s (> 0).
        duration_s: i64,
    },
    /// A traverse; see [`Drive`].
    Drive(Drive),
}

/// Slack below which a drive's computed duration rounds down to the whole second, s.
const DURATION_ROUNDING_S: f64 = 1e-6;

/// A drive of `length_m` at `rate_m_per_h`, split into segments that run in order so other
/// activities can interleave (paper 003 Fig. 3).
///
/// The split is fixed before the search: `k = clamp(floor(duration / min_segment_s), 1,
/// max_segments)` equal segments, or the explicit `split_at_m` boundaries when given. A plan
/// may drive only a prefix of the segments. The activity's `utility` is the whole drive's; each
/// segment carries its share by length, so a prefix earns it in proportion to the metres driven.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Drive {
    /// Route length in m (> 0).
    pub length_m: f64,
    /// Expected drive rate in m/h (> 0). The drive lasts `ceil(3600 × length_m / rate_m_per_h)`
    /// s.
    pub rate_m_per_h: f64,
    /// Shortest segment the drive may be cut into, s (> 0).
    pub min_segment_s: i64,
    /// Most segments (1 ..= 64). (default: 4)
    #[serde(default = "default_max_segments")]
    pub max_segments: u32,
    /// Explicit segment boundaries in m from the drive start, increasing, inside
    /// `(0, length_m)`; when non-empty they replace the equal split (use them to stop at a
    /// state-based campaign's distances). (default: none)
    #[serde(default)]
    pub split_at_m: Vec<f64>,
    /// Every segment must end by this time, s after midnight (a drive window that activities
    /// interleaved with the drive may stretch no further). (default: the problem's `end_s`)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub latest_end_s: Option<i64>,
}

fn default_max_segments() -> u32 {
    4
}

/// A campaign intent (paper 003 §3, Fig. 2): how the count of member activities in a plan
/// turns into utility.
///
/// The utility of `n` members is 0 below `min_count`, and
/// `utility × (1 + decay + … + decay^(m-1))` with `m = min(n, max_count)` otherwise — it grows
/// with the count, with diminishing returns when `decay < 1`, and saturates at `max_count`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Campaign {
    /// Unique id, named by member activities' `campaign`.
    pub id: String,
    /// The kind of intent; periodic and state-based campaigns are built from instance
    /// activities (see [`periodic_instances`](crate::periodic_instances) and
    /// [`state_based_instances`](crate::state_based_instances)).
    pub intent: CampaignIntent,
    /// Priority tier, 1 (highest) ..= [`MAX_TIERS`](crate::MAX_TIERS). (default: 1)
    #[serde(default = "default_tier")]
    pub tier: u8,
    /// Members needed before the campaign earns anything. (default: 0)
    #[serde(default)]
    pub min_count: u32,
    /// Members beyond this earn nothing (≥ `min_count`, ≥ 1).
    pub max_count: u32,
    /// Utility points of the first member (0 ..= [`MAX_UTILITY`](crate::MAX_UTILITY)).
    pub utility: f64,
    /// Each further member is worth `decay` times the previous one (0 < decay ≤ 1).
    /// (default: 1)
    #[serde(default = "default_decay")]
    pub decay: f64,
}

fn default_decay() -> f64 {
    1.0
}

/// The three campaign intents of paper 003 Fig. 2.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum CampaignIntent {
    /// Class (goal-set) sampling: any subset of the candidate observations.
    GoalSet,
    /// Temporally periodic: an instance due every `period_s` ± `tolerance_s`.
    Periodic {
        /// Cadence in s.
        period_s: i64,
        /// Allowed timing slack either side of a due time, s.
        tolerance_s: i64,
    },
    /// State-based: an instance due every `every_m` metres driven ± `tolerance_m`.
    StateBased {
        /// Cadence in m driven.
        every_m: f64,
        /// Allowed slack either side, m.
        tolerance_m: f64,
    },
}

impl Activity {
    /// A fixed-duration, optional, tier-1 activity with no data, preconditions or campaign.
    #[must_use]
    pub fn task(
        id: impl Into<String>,
        duration_s: i64,
        window_s: [i64; 2],
        power_w: f64,
        utility: f64,
    ) -> Self {
        Self {
            id: id.into(),
            name: String::new(),
            kind: ActivityKind::Task { duration_s },
            earliest_start_s: window_s[0],
            latest_start_s: window_s[1],
            power_w,
            data_mb: 0.0,
            downlink_mb: 0.0,
            preconditions: Vec::new(),
            mandatory: false,
            campaign: None,
            tier: 1,
            utility,
            driven_window_m: None,
            timeline: Timeline::Main,
        }
    }

    /// The duration in s: the task's, or the whole drive's.
    #[must_use]
    pub fn duration_s(&self) -> i64 {
        match &self.kind {
            ActivityKind::Task { duration_s } => *duration_s,
            ActivityKind::Drive(d) => d.duration_s(),
        }
    }
}

impl Drive {
    /// Segment boundaries in metres from the drive start, `0` first and `length_m` last: the
    /// explicit `split_at_m`, or `k = clamp(floor(duration / min_segment_s), 1, max_segments)`
    /// equal segments. The planner splits the drive here.
    #[must_use]
    pub fn boundaries_m(&self) -> Vec<f64> {
        if !self.split_at_m.is_empty() {
            let mut b = Vec::with_capacity(self.split_at_m.len() + 2);
            b.push(0.0);
            b.extend_from_slice(&self.split_at_m);
            b.push(self.length_m);
            return b;
        }
        let k = (self.duration_s() / self.min_segment_s.max(1))
            .clamp(1, i64::from(self.max_segments.max(1)));
        (0..=k)
            .map(|j| self.length_m * j as f64 / k as f64)
            .collect()
    }

    /// Whole-drive duration, `ceil(3600 × length_m / rate_m_per_h)` s (0 if not finite).
    ///
    /// A quotient within a microsecond above a whole second counts as that second: a length
    /// computed as `rate × window / 3600` must give back the window, and the round trip
    /// through floating point can land one ulp above it (issue 12: at 88.2 m/h a 5241 s
    /// window came back as 5242 s and made the sol's plan infeasible).
    ///
    /// # Units
    /// Seconds.
    #[must_use]
    pub fn duration_s(&self) -> i64 {
        let s = (3600.0 * self.length_m / self.rate_m_per_h - DURATION_ROUNDING_S).ceil();
        if (0.0..1e12).contains(&s) {
            s as i64
        } else {
            0
        }
    }
}
