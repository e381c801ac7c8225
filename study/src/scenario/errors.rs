//! `[errors]`: the error model's preset (`model`, default "calibrated") and the values that
//! override it → [`ErrorModel`], checked by [`ErrorModel::validate`].

use sim::rover::errors::{ErrorModel, ErrorPreset};

use super::raw::{RawErrors, RawPerTerrain};
use crate::check::FieldCheck;
use crate::error::ScenarioError;

/// The file's name of an [`ErrorModel`] field: the same key in `[errors]`.
pub(crate) fn toml_path(field: &str) -> String {
    format!("errors.{field}")
}

/// The error model `[errors]` describes.
///
/// # Errors
/// A [`ScenarioError`] naming the first `errors.…` field at fault.
pub(crate) fn error_model(
    c: &FieldCheck<'_>,
    raw: &RawErrors,
) -> Result<ErrorModel, ScenarioError> {
    let preset = match raw.model.as_deref() {
        None => ErrorPreset::Calibrated,
        Some(name) => ErrorPreset::from_name(name).ok_or_else(|| {
            c.err(
                "errors.model",
                "\"calibrated\" or \"stress\"",
                format!("{name:?}"),
            )
        })?,
    };
    let d = preset.model();
    let model = ErrorModel {
        preset,
        heading_sigma_deg: raw.heading_sigma_deg.unwrap_or(d.heading_sigma_deg),
        vo_scale_sigma: raw.vo_scale_sigma.unwrap_or(d.vo_scale_sigma),
        vo_noise_fraction: raw.vo_noise_fraction.unwrap_or(d.vo_noise_fraction),
        vo_failure: RawPerTerrain::over(raw.vo_failure.as_ref(), d.vo_failure),
        slip_fraction: RawPerTerrain::over(raw.slip_fraction.as_ref(), d.slip_fraction),
        slip_sigma_relative: raw.slip_sigma_relative.unwrap_or(d.slip_sigma_relative),
        ground_localization_sigma_m: raw
            .ground_localization_sigma_m
            .unwrap_or(d.ground_localization_sigma_m),
    };
    model.validate().map_err(|e| c.setting(e, toml_path))?;
    Ok(model)
}
