//! `[onboard_localization]`: which localizer runs after a drive and its settings, the HBS link
//! rate and the operator margin → [`LocalizerSpec`] (the localizer before the maps an
//! image-matching one needs are read). Each setting is checked where the simulator defines
//! it (`StatisticalLocalizer::validate`, `EkfLocalizer::validate_settings`, …); a setting of
//! another localizer than the one chosen is refused rather than ignored.

use std::sync::Arc;

use localization::ekf::ParkedSettings;
use localization::matcher::Method;
use localization::onboard::OnboardSettings;
use localization::particle::{KldSettings, PanoramaFixSettings, ParticleSettings, Resampling};
use maps::MapLayers;
use sim::localizers::{
    EkfLocalizer, HBS_LINK_RATE_KB_PER_S, ImageryLocalizer, OnboardLocalizer, ParticleLocalizer,
    StatisticalLocalizer,
};
use sim::settings::physical_range::MARGIN_M;

use super::raw::RawLocalizer;
use crate::check::FieldCheck;
use crate::error::ScenarioError;

/// The default HBS link rate, KB/s: the flown 10 KB/s (paper 000 §6).
pub const DEFAULT_HBS_LINK_RATE_KB_PER_S: f64 = 10.0;
/// The default operator margin after an onboard localization, metres.
const DEFAULT_OPERATOR_MARGIN_M: f64 = 1.0;

/// The `[onboard_localization]` choice, before the maps an image-matching localizer needs
/// are read.
#[derive(Clone, Debug)]
pub enum LocalizerSpec {
    /// Errors drawn from the published statistics.
    Statistical(StatisticalLocalizer),
    /// Image matching on the co-processor model.
    Imagery {
        /// Census, NCC or MI.
        method: Method,
        /// Run-time multiplier on the co-processor.
        hbs_slowdown: f64,
    },
    /// Paper 002's particle filter on the census score surface.
    Particle {
        /// Particle count and resampling.
        params: ParticleSettings,
        /// Run-time multiplier on the co-processor.
        hbs_slowdown: f64,
    },
    /// Paper 004's EKF, the parked rover ranging through one orbiter pass.
    Ekf(ParkedSettings),
}

impl LocalizerSpec {
    /// The localizer, on `layers` for one that renders imagery, planned at `link_bytes_per_s`.
    pub(crate) fn localizer(
        self,
        layers: &Arc<MapLayers>,
        link_bytes_per_s: f64,
    ) -> OnboardLocalizer {
        let mut localizer = match self {
            LocalizerSpec::Statistical(statistical) => OnboardLocalizer::Statistical(statistical),
            LocalizerSpec::Imagery {
                method,
                hbs_slowdown,
            } => {
                let mut imagery = ImageryLocalizer::new(Arc::clone(layers), method);
                imagery.settings.hbs_slowdown = hbs_slowdown;
                OnboardLocalizer::Imagery(Box::new(imagery))
            }
            LocalizerSpec::Particle {
                params,
                hbs_slowdown,
            } => {
                let mut particle = ParticleLocalizer::new(Arc::clone(layers));
                particle.fix.params = params;
                particle.settings.hbs_slowdown = hbs_slowdown;
                OnboardLocalizer::Particle(Box::new(particle))
            }
            LocalizerSpec::Ekf(settings) => OnboardLocalizer::Ekf(EkfLocalizer {
                settings,
                ..EkfLocalizer::default()
            }),
        };
        localizer.set_link_bytes_per_s(link_bytes_per_s);
        localizer
    }
}

/// What `[onboard_localization]` holds, checked.
pub(crate) struct OnboardLocalization {
    /// The localizer.
    pub(crate) localizer: LocalizerSpec,
    /// The HBS serial link rate, bytes per second.
    pub(crate) hbs_link_bytes_per_s: f64,
    /// Added to the localizer's σ after a fix, metres.
    pub(crate) operator_margin_m: f64,
}

/// The file's name of a localizer setting: its key in `[onboard_localization]` (the last part
/// of its path in the localizer's settings: `settings.range_sigma_m` is `range_sigma_m`).
fn toml_path(field: &str) -> String {
    let key = field.rsplit('.').next().unwrap_or(field);
    format!("onboard_localization.{key}")
}

/// The localizer, link rate and operator margin `[onboard_localization]` describes.
///
/// # Errors
/// A [`ScenarioError`] naming the first `onboard_localization.…` field at fault.
pub(crate) fn onboard_localization(
    c: &FieldCheck<'_>,
    l: &RawLocalizer,
) -> Result<OnboardLocalization, ScenarioError> {
    let name = l.localizer.as_deref().unwrap_or("statistical");
    let method = match name {
        "statistical" | "particle" | "ekf" => None,
        name => Some(Method::from_name(name).ok_or_else(|| {
            c.err(
                "onboard_localization.localizer",
                "\"statistical\", \"census\", \"ncc\", \"mi\", \"particle\" or \"ekf\"",
                format!("{name:?}"),
            )
        })?),
    };
    // Each setting belongs to some localizers; given with another, it is refused rather than
    // silently ignored.
    const STATISTICAL: &[&str] = &["statistical"];
    const ON_HBS: &[&str] = &["census", "ncc", "mi", "particle"];
    const PARTICLE: &[&str] = &["particle"];
    const EKF: &[&str] = &["ekf"];
    let owned: [(&str, bool, &[&str]); 11] = [
        ("mean_error_m", l.mean_error_m.is_some(), STATISTICAL),
        ("p99_error_m", l.p99_error_m.is_some(), STATISTICAL),
        ("failure_rate", l.failure_rate.is_some(), STATISTICAL),
        (
            "reported_sigma_m",
            l.reported_sigma_m.is_some(),
            STATISTICAL,
        ),
        ("hbs_slowdown", l.hbs_slowdown.is_some(), ON_HBS),
        ("particle_count", l.particle_count.is_some(), PARTICLE),
        ("resampling", l.resampling.is_some(), PARTICLE),
        ("range_sigma_m", l.range_sigma_m.is_some(), EKF),
        ("pass_duration_s", l.pass_duration_s.is_some(), EKF),
        ("elevation_mask_deg", l.elevation_mask_deg.is_some(), EKF),
        ("image_resolution_m", l.image_resolution_m.is_some(), EKF),
    ];
    for (field, given, owners) in owned {
        if given && !owners.contains(&name) {
            return Err(c.err(
                &format!("onboard_localization.{field}"),
                format!(
                    "no value: it sets the {} localizer{} only",
                    owners.join(", "),
                    if owners.len() > 1 { "s" } else { "" }
                ),
                format!("a value with localizer = {name:?}"),
            ));
        }
    }
    let setting = |e| c.setting(e, toml_path);
    let hbs_slowdown = l
        .hbs_slowdown
        .unwrap_or(OnboardSettings::default().hbs_slowdown);
    let on_hbs = OnboardSettings {
        hbs_slowdown,
        ..OnboardSettings::default()
    };
    let localizer = match (name, method) {
        (_, Some(method)) => {
            ImageryLocalizer::validate_settings(&on_hbs).map_err(setting)?;
            LocalizerSpec::Imagery {
                method,
                hbs_slowdown,
            }
        }
        ("particle", None) => {
            let mut params = ParticleSettings::default();
            if let Some(n) = l.particle_count {
                params.particle_count = n as usize;
            }
            ImageryLocalizer::validate_settings(&on_hbs).map_err(setting)?;
            let fix = PanoramaFixSettings {
                params,
                ..PanoramaFixSettings::default()
            };
            ParticleLocalizer::validate_fix(&fix).map_err(setting)?;
            // Parsed after the ranges above, so that of two bad values the first reported is
            // the one the loader has always reported first.
            if let Some(r) = &l.resampling {
                params.resampling = match r.as_str() {
                    "systematic" => Resampling::Systematic,
                    "kld" => Resampling::Kld(KldSettings::default()),
                    other => {
                        return Err(c.err(
                            "onboard_localization.resampling",
                            "\"systematic\" or \"kld\"",
                            format!("{other:?}"),
                        ));
                    }
                };
            }
            LocalizerSpec::Particle {
                params,
                hbs_slowdown,
            }
        }
        ("ekf", None) => {
            let d = ParkedSettings::default();
            let settings = ParkedSettings {
                range_sigma_m: l.range_sigma_m.unwrap_or(d.range_sigma_m),
                pass_duration_s: l.pass_duration_s.unwrap_or(d.pass_duration_s),
                elevation_mask_deg: l.elevation_mask_deg.unwrap_or(d.elevation_mask_deg),
                image_resolution_m: l.image_resolution_m,
                ..d
            };
            EkfLocalizer::validate_settings(&settings).map_err(setting)?;
            LocalizerSpec::Ekf(settings)
        }
        _ => {
            let d = StatisticalLocalizer::default();
            LocalizerSpec::Statistical(StatisticalLocalizer {
                mean_error_m: l.mean_error_m.unwrap_or(d.mean_error_m),
                p99_error_m: l.p99_error_m.unwrap_or(d.p99_error_m),
                failure_rate: l.failure_rate.unwrap_or(d.failure_rate),
                reported_sigma_m: l.reported_sigma_m.unwrap_or(d.reported_sigma_m),
                // The link rate is set with every localizer's, in `LocalizerSpec::localizer`.
                hbs: d.hbs,
            })
        }
    };
    let hbs_link_rate_kb_per_s = l
        .hbs_link_rate_kb_per_s
        .unwrap_or(DEFAULT_HBS_LINK_RATE_KB_PER_S);
    c.range(
        HBS_LINK_RATE_KB_PER_S,
        "onboard_localization.hbs_link_rate_kb_per_s",
        hbs_link_rate_kb_per_s,
    )?;
    // The statistical localizer's settings after the link rate, the others' before it: a
    // file's first error stays the one it always was.
    if let LocalizerSpec::Statistical(statistical) = &localizer {
        statistical.validate().map_err(setting)?;
    }
    let operator_margin_m = c.range(
        MARGIN_M,
        "onboard_localization.operator_margin_m",
        l.operator_margin_m.unwrap_or(DEFAULT_OPERATOR_MARGIN_M),
    )?;
    Ok(OnboardLocalization {
        localizer,
        hbs_link_bytes_per_s: 1_000.0 * hbs_link_rate_kb_per_s,
        operator_margin_m,
    })
}
