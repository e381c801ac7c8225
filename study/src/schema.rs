//! JSON Schemas of the scenario and campaign file formats, generated from the serde mirrors
//! the loaders parse (`deny_unknown_fields`), so a schema cannot drift from the parser. A TOML
//! file read as JSON validates against its schema when its names and types are right; values,
//! files and the scenario as a whole are checked by the loaders and [`crate::sanity`].
//!
//! Editors use them through Taplo (Even Better TOML): a `#:schema ./scenario.schema.json`
//! first line in a TOML file, or a `[[rule]]` in `.taplo.toml` (README, "Schemas and shell
//! integration").

/// The schema of scenario files ([`crate::Scenario`]), draft 2020-12.
#[must_use]
pub fn scenario() -> serde_json::Value {
    serde_json::to_value(schemars::schema_for!(crate::scenario::RawScenario))
        .expect("a schema is JSON")
}

/// The schema of `solsim plan` campaign files ([`crate::CampaignFile`]), draft 2020-12.
#[must_use]
pub fn campaign() -> serde_json::Value {
    serde_json::to_value(schemars::schema_for!(
        crate::campaign_file::raw::RawCampaignFile
    ))
    .expect("a schema is JSON")
}
