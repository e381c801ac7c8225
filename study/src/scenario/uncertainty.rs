//! `[uncertainty]`: the disc's growth with and without VO and its initial margin →
//! [`UncertaintyModel`], checked by [`UncertaintyModel::validate`].

use sim::rover::uncertainty::UncertaintyModel;

use super::raw::RawUncertainty;
use crate::check::FieldCheck;
use crate::error::ScenarioError;

/// The uncertainty model `[uncertainty]` describes.
///
/// # Errors
/// A [`ScenarioError`] naming the first `uncertainty.…` field at fault.
pub(crate) fn uncertainty_model(
    c: &FieldCheck<'_>,
    raw: &RawUncertainty,
) -> Result<UncertaintyModel, ScenarioError> {
    let d = UncertaintyModel::default();
    let model = UncertaintyModel {
        k_vo: raw.k_vo.unwrap_or(d.k_vo),
        k_novo: raw.k_novo.unwrap_or(d.k_novo),
        initial_margin_m: raw.initial_margin_m.unwrap_or(d.initial_margin_m),
    };
    model
        .validate()
        .map_err(|e| c.setting(e, |f| format!("uncertainty.{f}")))?;
    Ok(model)
}
