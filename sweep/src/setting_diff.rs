//! The settings two scenario files give different values (`solsim whatif`): their TOML
//! flattened to dotted paths and compared, leaving out what does not change a run.

use serde::Serialize;
use study::Scenario;

use crate::error::SweepError;

/// A setting the two scenario files give different values.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct SettingDifference {
    /// Its TOML path: `rover.slip_aware_routing`, `sols[3].drive_window_lmst`.
    pub field: String,
    /// The base's value, as TOML (`None`: not set, so the default applies).
    pub base: Option<String>,
    /// The variant's value, as TOML (`None`: not set, so the default applies).
    pub variant: Option<String>,
}

impl std::fmt::Display for SettingDifference {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let shown = |v: &Option<String>| v.clone().unwrap_or_else(|| "(not set: default)".into());
        write!(
            f,
            "{}: {} → {}",
            self.field,
            shown(&self.base),
            shown(&self.variant)
        )
    }
}

/// Fields of a scenario file that do not change a run: its name, its description, per-sol
/// notes and the `[[expect]]` entries `solsim regress` checks.
fn is_setting(field: &str) -> bool {
    let top = field.split(['.', '[']).next().unwrap_or(field);
    let note = field.starts_with("sols[") && field.ends_with("].note");
    !(note || matches!(top, "name" | "description" | "expect"))
}

/// Every setting whose value differs between two scenario files' TOML, in field order: the
/// tables flattened to dotted paths, arrays of tables indexed (`sols[3].distance_m`), other
/// arrays compared whole. A field one file sets and the other leaves to its default is a
/// difference (`None` on the side that does not set it). The name, the description, per-sol
/// notes and `[[expect]]` entries are left out: they do not change a run.
///
/// # Errors
/// Text that is not TOML (the scenario loader has read it already, so this is not expected).
pub fn setting_differences(
    base_toml: &str,
    variant_toml: &str,
) -> Result<Vec<SettingDifference>, toml::de::Error> {
    fn flatten(
        prefix: &str,
        v: &toml::Value,
        out: &mut std::collections::BTreeMap<String, String>,
    ) {
        let key = |k: &str| {
            if prefix.is_empty() {
                k.to_string()
            } else {
                format!("{prefix}.{k}")
            }
        };
        match v {
            toml::Value::Table(t) => {
                for (k, v) in t {
                    flatten(&key(k), v, out);
                }
            }
            toml::Value::Array(a) if !a.is_empty() && a.iter().all(toml::Value::is_table) => {
                for (i, v) in a.iter().enumerate() {
                    flatten(&format!("{prefix}[{i}]"), v, out);
                }
            }
            other => {
                out.insert(prefix.to_string(), other.to_string());
            }
        }
    }
    let flat = |text: &str| -> Result<_, toml::de::Error> {
        let table: toml::Table = toml::from_str(text)?;
        let mut out = std::collections::BTreeMap::new();
        flatten("", &toml::Value::Table(table), &mut out);
        Ok(out)
    };
    let (b, v) = (flat(base_toml)?, flat(variant_toml)?);
    let mut fields: Vec<&String> = b.keys().chain(v.keys()).collect();
    fields.sort();
    fields.dedup();
    Ok(fields
        .into_iter()
        .filter(|f| is_setting(f) && b.get(*f) != v.get(*f))
        .map(|f| SettingDifference {
            field: f.clone(),
            base: b.get(f).cloned(),
            variant: v.get(f).cloned(),
        })
        .collect())
}

/// The settings that differ between the loaded `base` and `variant`, read from their files; a
/// map file named by a different path but with the same contents (SHA-256) is not a
/// difference.
///
/// # Errors
/// A file that cannot be read again, or no longer parses as TOML.
pub fn differences_of(
    base: &Scenario,
    variant: &Scenario,
) -> Result<Vec<SettingDifference>, SweepError> {
    let read = |s: &Scenario| {
        maps::input_file::read_text_file(&s.path)
            .map_err(|e| SweepError::io(&s.path, "cannot read it again", e))
    };
    let all =
        setting_differences(&read(base)?, &read(variant)?).map_err(|e| SweepError::Reread {
            base: base.path.clone(),
            variant: variant.path.clone(),
            message: e.to_string(),
        })?;
    let sha = |s: &Scenario, field: &str| {
        s.inputs_sha256
            .iter()
            .find(|(f, _, _)| *f == field)
            .map(|(_, _, sha)| sha.clone())
    };
    Ok(all
        .into_iter()
        .filter(|d| {
            let same_file = sha(base, &d.field).is_some_and(|b| sha(variant, &d.field) == Some(b));
            !same_file
        })
        .collect())
}
