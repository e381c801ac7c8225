//! Reading zones from GeoJSON text: structure checks with a path for every complaint, then the
//! `geojson` crate for each Feature, then ring validation.

use super::ZoneKind;
use super::error::ZoneError;
use super::geometry::P;
use super::validation::{PolygonProblem, validate_polygon};
use serde_json::Value;
use std::borrow::Cow;
use std::path::Path;

/// Prefix of the strings that stand in for non-finite number literals (see
/// [`quote_non_finite_literals`]); a NUL never starts a real coordinate.
const NON_FINITE_MARK: char = '\u{0}';

/// One zone as read: validated polygons as open, oriented rings (shell first).
pub(super) struct ZoneRecord {
    pub feature: usize,
    pub name: String,
    pub kind: ZoneKind,
    pub polygons: Vec<Vec<Vec<P>>>,
}

/// Parse and validate every feature of a zones FeatureCollection; `check` sees the number of
/// polygons and of vertices of all features before any is converted or validated.
pub(super) fn read_zones(
    text: &str,
    path: &Path,
    check: &dyn Fn(usize, usize) -> Result<(), ZoneError>,
) -> Result<Vec<ZoneRecord>, ZoneError> {
    let text = quote_non_finite_literals(text);
    let root: Value = serde_json::from_str(&text).map_err(|error| ZoneError::InvalidJson {
        path: path.to_owned(),
        error,
    })?;
    let not_collection = |field: &str, found: String| ZoneError::NotFeatureCollection {
        path: path.to_owned(),
        field: field.to_owned(),
        found,
    };
    // Until the file shows a `type` member it may be any JSON file (a token, a key file):
    // what it holds is described, never quoted.
    let Value::Object(mut root) = root else {
        return Err(not_collection("type", json_kind(&root).to_owned()));
    };
    match root.get("type") {
        Some(Value::String(t)) if t == "FeatureCollection" => {}
        Some(other) => return Err(not_collection("type", other.to_string())),
        None => return Err(not_collection("type", "no \"type\" member".to_owned())),
    }
    let features = match root.remove("features") {
        Some(Value::Array(features)) => features,
        Some(other) => return Err(not_collection("features", describe(&other))),
        None => {
            return Err(not_collection(
                "features",
                "no \"features\" member".to_owned(),
            ));
        }
    };
    if u32::try_from(features.len()).is_err() {
        return Err(ZoneError::TooManyZones {
            path: path.to_owned(),
            count: features.len(),
        });
    }
    let (polygons, vertices) = features
        .iter()
        .map(count_geometry)
        .fold((0usize, 0usize), |(p, v), (dp, dv)| {
            (p.saturating_add(dp), v.saturating_add(dv))
        });
    check(polygons, vertices)?;
    features
        .into_iter()
        .enumerate()
        .map(|(i, value)| read_feature(i, value, path))
        .collect()
}

/// What kind of JSON value `value` is ("a number", "an object", …), without any of its content:
/// for messages that must not quote a foreign file.
#[must_use]
pub fn json_kind(value: &Value) -> &'static str {
    match value {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

/// Polygons and positions of one feature's `Polygon` or `MultiPolygon`, counted in the JSON
/// (anything else counts nothing: reading the feature says what is wrong with it).
fn count_geometry(feature: &Value) -> (usize, usize) {
    let Some(geometry) = feature.get("geometry") else {
        return (0, 0);
    };
    let coordinates = geometry.get("coordinates").and_then(Value::as_array);
    let positions = |polygon: &Value| -> usize {
        polygon.as_array().map_or(0, |rings| {
            rings.iter().map(|r| r.as_array().map_or(0, Vec::len)).sum()
        })
    };
    match (geometry.get("type").and_then(Value::as_str), coordinates) {
        (Some("Polygon"), Some(_)) => (1, positions(&geometry["coordinates"])),
        (Some("MultiPolygon"), Some(parts)) => (parts.len(), parts.iter().map(positions).sum()),
        _ => (0, 0),
    }
}

/// A short description of a JSON value for messages.
fn describe(value: &Value) -> String {
    match value {
        Value::Null => "null".to_owned(),
        Value::Bool(_) => "a boolean".to_owned(),
        Value::Number(_) => "a number".to_owned(),
        Value::String(s) => format!("the string {s:?}"),
        Value::Array(_) => "an array".to_owned(),
        Value::Object(_) => "an object".to_owned(),
    }
}

/// Read feature `i`.
fn read_feature(i: usize, value: Value, path: &Path) -> Result<ZoneRecord, ZoneError> {
    let properties = value.get("properties").and_then(Value::as_object);
    let name = match properties.and_then(|p| p.get("name")) {
        None | Some(Value::Null) => format!("zone-{i}"),
        Some(Value::String(s)) if crate::input_file::first_unsafe_char(s).is_some() => {
            return Err(ZoneError::UnsafeName {
                path: path.to_owned(),
                feature: i,
                name: s.clone(),
            });
        }
        Some(Value::String(s)) => s.clone(),
        Some(other) => {
            return Err(ZoneError::InvalidName {
                path: path.to_owned(),
                feature: i,
                found: other.to_string(),
            });
        }
    };
    if let Some(coordinates) = value.get("geometry").and_then(|g| g.get("coordinates")) {
        find_non_finite(
            coordinates,
            &mut "geometry.coordinates".to_owned(),
            &|field, axis, bad| match bad {
                BadCoordinate::NonFinite(literal) => ZoneError::NonFiniteCoordinate {
                    path: path.to_owned(),
                    feature: i,
                    name: name.clone(),
                    field,
                    axis,
                    value: literal.to_owned(),
                },
                BadCoordinate::OutOfRange(value) => ZoneError::CoordinateOutOfRange {
                    path: path.to_owned(),
                    feature: i,
                    name: name.clone(),
                    field,
                    axis,
                    value,
                },
            },
        )?;
    }
    let feature: geojson::Feature =
        serde_json::from_value(value).map_err(|error| ZoneError::InvalidFeature {
            path: path.to_owned(),
            feature: i,
            name: name.clone(),
            error,
        })?;
    let kind = match feature.property("kind") {
        None | Some(Value::Null) => {
            let misspelt = feature.properties.as_ref().and_then(|p| {
                p.keys()
                    .find(|k| crate::names::closest(k, &["kind"]).is_some())
                    .cloned()
            });
            return Err(ZoneError::MissingKind {
                path: path.to_owned(),
                feature: i,
                name,
                misspelt,
            });
        }
        Some(value) => match value.as_str().and_then(parse_kind) {
            Some(kind) => kind,
            None => {
                return Err(ZoneError::UnknownKind {
                    path: path.to_owned(),
                    feature: i,
                    name,
                    found: value.to_string(),
                });
            }
        },
    };
    let Some(geometry) = feature.geometry else {
        return Err(ZoneError::MissingGeometry {
            path: path.to_owned(),
            feature: i,
            name,
        });
    };
    let ctx = FeatureContext {
        path,
        feature: i,
        name: &name,
    };
    let polygons = match geometry.value {
        geojson::GeometryValue::Polygon { coordinates } => {
            vec![ctx.polygon(&coordinates, "geometry.coordinates", "geometry")?]
        }
        geojson::GeometryValue::MultiPolygon { coordinates } if coordinates.is_empty() => {
            return Err(ZoneError::EmptyMultiPolygon {
                path: path.to_owned(),
                feature: i,
                name,
            });
        }
        geojson::GeometryValue::MultiPolygon { coordinates } => coordinates
            .iter()
            .enumerate()
            .map(|(k, polygon)| {
                let field = format!("geometry.coordinates[{k}]");
                ctx.polygon(polygon, &field, &field)
            })
            .collect::<Result<_, _>>()?,
        other => {
            return Err(ZoneError::UnsupportedGeometry {
                path: path.to_owned(),
                feature: i,
                name,
                found: other.type_name().to_owned(),
            });
        }
    };
    Ok(ZoneRecord {
        feature: i,
        name,
        kind,
        polygons,
    })
}

/// `keep_in` / `keep_out`, ignoring case, `_`, `-` and spaces (`keep-in`, `KeepIn`, `KEEP_OUT` …).
fn parse_kind(text: &str) -> Option<ZoneKind> {
    let squeezed: String = text
        .chars()
        .filter(|c| !matches!(c, '_' | '-' | ' '))
        .flat_map(char::to_lowercase)
        .collect();
    match squeezed.as_str() {
        "keepin" => Some(ZoneKind::KeepIn),
        "keepout" => Some(ZoneKind::KeepOut),
        _ => None,
    }
}

/// Where in the file a polygon sits, to turn a [`PolygonProblem`] into a [`ZoneError`].
struct FeatureContext<'a> {
    path: &'a Path,
    feature: usize,
    name: &'a str,
}

impl FeatureContext<'_> {
    /// Validate one polygon; `rings_field` is the JSON path of its ring array, `polygon_field` the
    /// name used for whole-polygon problems.
    fn polygon(
        &self,
        rings: &[Vec<geojson::Position>],
        rings_field: &str,
        polygon_field: &str,
    ) -> Result<Vec<Vec<P>>, ZoneError> {
        let (path, feature, name) = (self.path.to_owned(), self.feature, self.name.to_owned());
        let mut xy: Vec<Vec<P>> = Vec::with_capacity(rings.len());
        for (r, ring) in rings.iter().enumerate() {
            let mut ring_xy = Vec::with_capacity(ring.len());
            for (k, position) in ring.iter().enumerate() {
                // [x, y] only: an altitude would be dropped without a word.
                match position.as_slice() {
                    [x, y] => ring_xy.push([*x, *y]),
                    other => {
                        let field = format!("{rings_field}[{r}][{k}]");
                        return Err(ZoneError::PositionNotXy {
                            path,
                            feature,
                            name,
                            field,
                            len: other.len(),
                        });
                    }
                }
            }
            xy.push(ring_xy);
        }
        let ring_field = |r: usize| format!("{rings_field}[{r}]");
        let field = polygon_field.to_owned();
        validate_polygon(&xy).map_err(|problem| match problem {
            PolygonProblem::NoRings => ZoneError::EmptyPolygon {
                path,
                feature,
                name,
                field: rings_field.to_owned(),
            },
            PolygonProblem::TooFewPositions { ring, positions } => ZoneError::RingTooShort {
                path,
                feature,
                name,
                field: ring_field(ring),
                positions,
            },
            PolygonProblem::NotClosed { ring, first, last } => ZoneError::RingNotClosed {
                path,
                feature,
                name,
                field: ring_field(ring),
                first,
                last,
            },
            PolygonProblem::ZeroArea { ring } => ZoneError::ZeroAreaRing {
                path,
                feature,
                name,
                field: ring_field(ring),
            },
            PolygonProblem::SelfIntersection { ring, at } => ZoneError::SelfIntersection {
                path,
                feature,
                name,
                field,
                ring,
                at,
            },
            PolygonProblem::RingsCross { ring_a, ring_b, at } => ZoneError::RingsCross {
                path,
                feature,
                name,
                field,
                ring_a,
                ring_b,
                at,
            },
            PolygonProblem::HoleOutsideShell { ring } => ZoneError::HoleOutsideShell {
                path,
                feature,
                name,
                field,
                ring,
            },
            PolygonProblem::HolesOverlap { ring_a, ring_b } => ZoneError::HolesOverlap {
                path,
                feature,
                name,
                field,
                ring_a,
                ring_b,
            },
        })
    }
}

/// A coordinate the reader refuses before parsing the geometry.
enum BadCoordinate<'a> {
    /// `NaN`, `Infinity` or `-Infinity` (the literal).
    NonFinite(&'a str),
    /// Finite, but beyond [`crate::zone::MAX_COORDINATE_M`] (the value).
    OutOfRange(f64),
}

/// Report the first non-finite stand-in (see [`quote_non_finite_literals`]) or out-of-range
/// number in a coordinates array, with its JSON path.
fn find_non_finite(
    value: &Value,
    field: &mut String,
    error: &dyn Fn(String, &'static str, BadCoordinate<'_>) -> ZoneError,
) -> Result<(), ZoneError> {
    let Value::Array(items) = value else {
        return Ok(());
    };
    for (k, item) in items.iter().enumerate() {
        let axis = match k {
            0 => "x",
            1 => "y",
            _ => "z",
        };
        match item {
            Value::String(s) if s.starts_with(NON_FINITE_MARK) => {
                let literal = &s[NON_FINITE_MARK.len_utf8()..];
                return Err(error(
                    field.clone(),
                    axis,
                    BadCoordinate::NonFinite(literal),
                ));
            }
            Value::Number(n)
                if n.as_f64()
                    .is_some_and(|v| v.abs() > crate::zone::MAX_COORDINATE_M) =>
            {
                let v = n.as_f64().unwrap_or(f64::INFINITY);
                let field = format!("{field}[{k}]");
                return Err(error(field, axis, BadCoordinate::OutOfRange(v)));
            }
            Value::Array(_) => {
                let len = field.len();
                field.push_str(&format!("[{k}]"));
                find_non_finite(item, field, error)?;
                field.truncate(len);
            }
            _ => {}
        }
    }
    Ok(())
}

/// Replace the non-standard literals `NaN`, `Infinity` and `-Infinity` outside strings (Python's
/// `json.dump` writes them) by marked strings, so that instead of a bare syntax error the reader
/// can say which coordinate is not finite. Text without them is returned unchanged.
fn quote_non_finite_literals(text: &str) -> Cow<'_, str> {
    const LITERALS: [&str; 3] = ["-Infinity", "Infinity", "NaN"];
    let bytes = text.as_bytes();
    let mut out: Option<String> = None;
    let (mut in_string, mut escaped) = (false, false);
    let mut copied = 0;
    let mut i = 0;
    while i < bytes.len() {
        let c = bytes[i];
        if in_string {
            match c {
                _ if escaped => escaped = false,
                b'\\' => escaped = true,
                b'"' => in_string = false,
                _ => {}
            }
        } else if c == b'"' {
            in_string = true;
        } else if let Some(literal) = LITERALS
            .iter()
            .find(|l| bytes[i..].starts_with(l.as_bytes()))
        {
            let s = out.get_or_insert_with(|| String::with_capacity(text.len() + 16));
            s.push_str(&text[copied..i]);
            s.push('"');
            s.push_str("\\u0000");
            s.push_str(literal);
            s.push('"');
            i += literal.len();
            copied = i;
            continue;
        }
        i += 1;
    }
    match out {
        Some(mut s) => {
            s.push_str(&text[copied..]);
            Cow::Owned(s)
        }
        None => Cow::Borrowed(text),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kinds() {
        for k in ["keep_in", "keep-in", "keepin", "KEEP_IN", "Keep In"] {
            assert_eq!(parse_kind(k), Some(ZoneKind::KeepIn), "{k}");
        }
        for k in ["keep_out", "KEEP-OUT", "keepOut"] {
            assert_eq!(parse_kind(k), Some(ZoneKind::KeepOut), "{k}");
        }
        assert_eq!(parse_kind("keep"), None);
        assert_eq!(parse_kind(""), None);
    }

    #[test]
    fn non_finite_literals_are_quoted_outside_strings_only() {
        assert!(matches!(
            quote_non_finite_literals("[1, 2]"),
            Cow::Borrowed(_)
        ));
        assert_eq!(
            quote_non_finite_literals("[NaN, -Infinity]"),
            "[\"\\u0000NaN\", \"\\u0000-Infinity\"]"
        );
        assert_eq!(
            quote_non_finite_literals(r#"{"a": "NaN \" Infinity"}"#),
            r#"{"a": "NaN \" Infinity"}"#
        );
        let v: Value =
            serde_json::from_str(&quote_non_finite_literals("[Infinity]")).expect("json");
        assert_eq!(v[0].as_str(), Some("\u{0}Infinity"));
    }
}
