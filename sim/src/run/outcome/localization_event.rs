//! What a localization reports in the sol log: the ground's at an uplink, or the rover's own
//! after a drive ([`LocalizationEvent`]), with its steps, its ellipse and why it was rejected.

use std::fmt;

use localization::hbs::HbsStep;
use localization::onboard::LostReason;
use serde::Serialize;

/// Who localized the rover: serialised and displayed as `ground` or `onboard`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum LocalizationKind {
    /// The mapping specialists on the ground, with the uplink (`MOB_GROUND_LOCALIZED_HERE`).
    #[serde(rename = "ground")]
    Ground,
    /// The rover itself after a drive (the statistical model or image matching on board).
    #[serde(rename = "onboard")]
    Onboard,
}

impl LocalizationKind {
    /// The name in the sol log: `ground` or `onboard`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            LocalizationKind::Ground => "ground",
            LocalizationKind::Onboard => "onboard",
        }
    }
}

impl fmt::Display for LocalizationKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.pad(self.name())
    }
}

/// Why an onboard localization was not applied. Displayed, and serialised as a string, as the
/// sol log's sentence (`validity checks failed: …`, `run 1 timed out (HBS stall)`, …).
#[derive(Clone, Debug, PartialEq)]
pub enum RejectionReason {
    /// The statistical localizer's validity checks refused the run (its configured
    /// `failure_rate`); it models an ambiguous map match:
    /// `validity checks failed: ambiguous map match`.
    ModelledAmbiguousMatch,
    /// The image-matching activity was lost: no imagery for the search window, or the
    /// co-processor's checksums, timeouts, comparison or the result's validity checks.
    Onboard(LostReason),
    /// A filter localizer (particle, EKF) refused its own result: a belief with several modes,
    /// no gain over the prior, nothing to update with. The sentence says which.
    Filter(String),
}

impl fmt::Display for RejectionReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RejectionReason::ModelledAmbiguousMatch => {
                f.write_str("validity checks failed: ambiguous map match")
            }
            RejectionReason::Onboard(reason) => reason.fmt(f),
            RejectionReason::Filter(reason) => write!(f, "filter: {reason}"),
        }
    }
}

impl Serialize for RejectionReason {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_str(self)
    }
}

/// A step of a localization activity: the ground's flight command, or a step of the onboard
/// activity. Serialised and displayed as its flight-style name ([`LocalizationStep::name`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LocalizationStep {
    /// `MOB_GROUND_LOCALIZED_HERE`: the ground's position, sent with the uplink.
    GroundLocalizedHere,
    /// A flight command or co-processor step of the onboard activity (paper 000 Fig. 19).
    Onboard(HbsStep),
}

impl LocalizationStep {
    /// The flight-style name (`MOB_GROUND_LOCALIZED_HERE`, `RUN_1`, `COMPARE`, …).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            LocalizationStep::GroundLocalizedHere => "MOB_GROUND_LOCALIZED_HERE",
            LocalizationStep::Onboard(step) => step.name(),
        }
    }
}

impl From<HbsStep> for LocalizationStep {
    fn from(step: HbsStep) -> Self {
        LocalizationStep::Onboard(step)
    }
}

impl fmt::Display for LocalizationStep {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.pad(self.name())
    }
}

impl Serialize for LocalizationStep {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

/// A filter's 1σ position ellipse, with the angle MMGIS draws it at.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PositionEllipse {
    /// Semi-major axis, metres.
    pub semi_major_m: f64,
    /// Semi-minor axis, metres.
    pub semi_minor_m: f64,
    /// Azimuth of the major axis, degrees east of north, `[0, 180)`.
    pub azimuth_deg: f64,
    /// MMGIS's angle for `xAxisProp` = semi-major, `yAxisProp` = semi-minor, degrees.
    pub mmgis_angle_deg: f64,
    /// The disc the keep-out zones grow by: 3 × the semi-major axis, metres.
    pub disc_radius_m: f64,
}

impl PositionEllipse {
    /// The record of a 1σ ellipse.
    #[must_use]
    pub fn from_ellipse(e: localization::particle::Ellipse) -> Self {
        Self {
            semi_major_m: e.semi_major_m,
            semi_minor_m: e.semi_minor_m,
            azimuth_deg: e.azimuth_deg,
            mmgis_angle_deg: e.mmgis_angle_deg(),
            disc_radius_m: e.disc_radius_m(),
        }
    }
}

/// A localization at the start (ground) or end (onboard) of a sol.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LocalizationEvent {
    /// Ground or onboard.
    pub kind: LocalizationKind,
    /// The localizer: `"ground"` (mapping specialists), or the onboard localizer's name
    /// (`"statistical"`, `"census"`, `"ncc"`, `"mi"`).
    pub localizer: &'static str,
    /// Whether the result was applied to the rover's estimate.
    pub applied: bool,
    /// Why it was not applied (`None` when applied).
    pub reason: Option<RejectionReason>,
    /// Distance from the applied estimate to the truth, metres (`None` when not applied).
    pub error_m: Option<f64>,
    /// Image matching only: distance from the matcher's best estimate to the truth, metres,
    /// whether or not it passed the checks (what a rejection gave up; the truth is known only
    /// to the simulator).
    pub matched_error_m: Option<f64>,
    /// The localizer's σ, metres (`None` for ground localization or when nothing was applied).
    pub sigma_m: Option<f64>,
    /// Search radius of an image-matching localization, metres.
    pub search_radius_m: Option<f64>,
    /// A filter localizer's (particle, EKF) 1σ position ellipse after its update, whether or
    /// not the result was applied (`None` for the other localizers, or when the filter did
    /// not run).
    pub ellipse: Option<PositionEllipse>,
    /// Uncertainty radius after the event, metres.
    pub uncertainty_after_m: f64,
    /// When the activity started, LMST `HH:MM` (`None` for a ground localization, which
    /// arrives with the uplink).
    pub start_lmst: Option<String>,
    /// How long the activity took on board, seconds (transfer, runs, reboot, compare, apply).
    pub duration_s: Option<f64>,
    /// Its steps: the flight commands (`MOB_GROUND_LOCALIZED_HERE`, `MOB_WRITE_ONBD_INPUT_FILE`,
    /// `MOB_APPLY_ONBD_LOCALIZATION`) and the co-processor steps in between.
    pub steps: Vec<ActivityStep>,
}

impl LocalizationEvent {
    /// An onboard event of `localizer` started at LMST `start_lmst` that has applied nothing
    /// yet (every result field empty, the uncertainty after it still to be set).
    #[must_use]
    pub fn pending_onboard(localizer: &'static str, start_lmst: String) -> Self {
        Self {
            kind: LocalizationKind::Onboard,
            localizer,
            applied: false,
            reason: None,
            error_m: None,
            matched_error_m: None,
            sigma_m: None,
            search_radius_m: None,
            ellipse: None,
            uncertainty_after_m: 0.0,
            start_lmst: Some(start_lmst),
            duration_s: None,
            steps: Vec::new(),
        }
    }
}

/// One step of a localization activity in the sol log.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ActivityStep {
    /// LMST `HH:MM` of the step (`None` for a ground step, which comes with the uplink).
    pub lmst: Option<String>,
    /// Seconds since the activity started.
    pub t_s: f64,
    /// The flight command or co-processor step.
    pub step: LocalizationStep,
    /// What happened.
    pub detail: String,
}
