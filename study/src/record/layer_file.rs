//! Reading the traverse layer strictly ([`TraverseLayer::read`]): a file that is not NASA's
//! MMGIS traverse layer is one error naming the feature and the field.

use std::path::Path;

use serde_json::Value;

use super::{MAX_LAYER_BYTES, RecordEntry, TraverseLayer};
use crate::error::ScenarioError;

fn field_error(path: &Path, field: String, expected: &str, got: &Value) -> ScenarioError {
    let mut got = got.to_string();
    if got.chars().count() > 60 {
        got = format!("{}…", got.chars().take(60).collect::<String>());
    }
    ScenarioError::Field {
        path: path.to_path_buf(),
        field,
        expected: expected.to_owned(),
        got: maps::input_file::printable(&got).into_owned(),
    }
}

fn number(
    path: &Path,
    props: &Value,
    i: usize,
    key: &str,
    what: &str,
) -> Result<f64, ScenarioError> {
    let v = &props[key];
    v.as_f64()
        .filter(|x| x.is_finite())
        .ok_or_else(|| field_error(path, format!("features[{i}].properties.{key}"), what, v))
}

fn string(
    path: &Path,
    props: &Value,
    i: usize,
    key: &str,
    what: &str,
) -> Result<String, ScenarioError> {
    let v = &props[key];
    v.as_str()
        .filter(|s| {
            !s.is_empty() && s.len() <= 64 && maps::input_file::first_unsafe_char(s).is_none()
        })
        .map(str::to_owned)
        .ok_or_else(|| field_error(path, format!("features[{i}].properties.{key}"), what, v))
}

impl TraverseLayer {
    /// Read a traverse layer (`M20_traverse.json`): a GeoJSON FeatureCollection of LineStrings
    /// with the properties `sol`, `fromRMC`, `toRMC`, `length`, `SCLK_START`, `SCLK_END`.
    ///
    /// # Errors
    /// The file cannot be read, is not JSON, or is not such a layer: one error naming the
    /// feature and the field.
    pub fn read(path: &Path) -> Result<Self, ScenarioError> {
        let text =
            maps::input_file::read_text_file_capped(path, MAX_LAYER_BYTES).map_err(|error| {
                ScenarioError::Io {
                    path: path.to_path_buf(),
                    error,
                }
            })?;
        Self::from_json_str(path, &text)
    }

    /// [`TraverseLayer::read`] of the layer's text (`path` names it in errors).
    ///
    /// # Errors
    /// As [`TraverseLayer::read`].
    pub fn from_json_str(path: &Path, text: &str) -> Result<Self, ScenarioError> {
        let root: Value = serde_json::from_str(text).map_err(|e| ScenarioError::Syntax {
            path: path.to_path_buf(),
            line: e.line(),
            column: e.column(),
            text: None,
            message: format!("not JSON: {e}"),
        })?;
        let expected_layer = "a GeoJSON FeatureCollection of drives (NASA's MMGIS traverse layer, M20_traverse.json)";
        if root["type"] != "FeatureCollection" {
            return Err(field_error(
                path,
                "type".into(),
                expected_layer,
                &root["type"],
            ));
        }
        let Some(features) = root["features"].as_array() else {
            return Err(field_error(
                path,
                "features".into(),
                expected_layer,
                &root["features"],
            ));
        };
        if features.is_empty() {
            return Err(field_error(
                path,
                "features".into(),
                "at least one drive",
                &root["features"],
            ));
        }
        let name = root["name"].as_str().unwrap_or("").to_owned();
        let mut entries = Vec::with_capacity(features.len());
        for (i, f) in features.iter().enumerate() {
            let props = &f["properties"];
            if !props.is_object() {
                return Err(field_error(
                    path,
                    format!("features[{i}].properties"),
                    "an object with sol, fromRMC, toRMC, length, SCLK_START, SCLK_END (a traverse layer)",
                    props,
                ));
            }
            let sol = &props["sol"];
            let sol = sol.as_u64().filter(|&s| s <= 100_000).ok_or_else(|| {
                field_error(
                    path,
                    format!("features[{i}].properties.sol"),
                    "a sol number 0 ..= 100000 (a traverse layer's features have sol, fromRMC, toRMC, length, SCLK_START, SCLK_END)",
                    sol,
                )
            })? as u32;
            let length_m = number(path, props, i, "length", "a path length, metres ≥ 0")?;
            if !(0.0..=10_000.0).contains(&length_m) {
                return Err(field_error(
                    path,
                    format!("features[{i}].properties.length"),
                    "a path length 0 ..= 10000 metres",
                    &props["length"],
                ));
            }
            let clock = "a spacecraft clock reading, seconds 0 ..= 4e9";
            let sclk_start_s = number(path, props, i, "SCLK_START", clock)?;
            let sclk_end_s = number(path, props, i, "SCLK_END", clock)?;
            for (key, v) in [("SCLK_START", sclk_start_s), ("SCLK_END", sclk_end_s)] {
                if !(0.0..=4.0e9).contains(&v) {
                    return Err(field_error(
                        path,
                        format!("features[{i}].properties.{key}"),
                        clock,
                        &props[key],
                    ));
                }
            }
            if sclk_end_s < sclk_start_s {
                return Err(field_error(
                    path,
                    format!("features[{i}].properties.SCLK_END"),
                    &format!("a clock reading at or after SCLK_START ({sclk_start_s})"),
                    &props["SCLK_END"],
                ));
            }
            let rmc = "a Rover Motion Counter SITE_DRIVE, e.g. \"11_1110\"";
            let from_rmc = string(path, props, i, "fromRMC", rmc)?;
            let to_rmc = string(path, props, i, "toRMC", rmc)?;
            let geometry = &f["geometry"];
            let line = "a LineString of [lon, lat, elevation] points, degrees (lon -180 ..= 360, lat -90 ..= 90)";
            if geometry["type"] != "LineString" {
                return Err(field_error(
                    path,
                    format!("features[{i}].geometry.type"),
                    line,
                    &geometry["type"],
                ));
            }
            let Some(coords) = geometry["coordinates"].as_array().filter(|c| !c.is_empty()) else {
                return Err(field_error(
                    path,
                    format!("features[{i}].geometry.coordinates"),
                    line,
                    &geometry["coordinates"],
                ));
            };
            let mut path_lonlat_deg = Vec::with_capacity(coords.len());
            for (k, p) in coords.iter().enumerate() {
                let lonlat = p
                    .as_array()
                    .filter(|a| (2..=3).contains(&a.len()))
                    .and_then(|a| {
                        let lon = a[0].as_f64().filter(|v| (-180.0..=360.0).contains(v))?;
                        let lat = a[1].as_f64().filter(|v| (-90.0..=90.0).contains(v))?;
                        Some([lon, lat])
                    });
                let Some(lonlat) = lonlat else {
                    return Err(field_error(
                        path,
                        format!("features[{i}].geometry.coordinates[{k}]"),
                        line,
                        p,
                    ));
                };
                path_lonlat_deg.push(lonlat);
            }
            entries.push(RecordEntry {
                index: i,
                sol,
                from_rmc,
                to_rmc,
                length_m,
                sclk_start_s,
                sclk_end_s,
                path_lonlat_deg,
            });
        }
        Ok(Self {
            path: path.to_path_buf(),
            name,
            entries,
        })
    }
}
