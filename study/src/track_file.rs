//! Track files for `solsim route import`: a route in Mars longitude and latitude, from GeoJSON
//! or CSV.
//!
//! Coordinates are planetocentric degrees on the IAU 2015 Mars sphere, longitude east-positive
//! (−180 to 360) and latitude north (−90 to 90): the frame of MMGIS and of solsim's own
//! longitude/latitude GIS outputs (`IAU_2015:49900`).
//!
//! - **GeoJSON**: a `LineString` or `MultiPoint` (bare, as a Feature, or the one feature of a
//!   FeatureCollection), or a FeatureCollection of `Point` features taken in file order. A
//!   position is `[longitude, latitude]`; a third number (elevation) is ignored, since the map
//!   has its own DEM. A file whose `crs` member is a projected CRS (solsim's
//!   `gis/projected/…` layers, in map metres) is refused.
//! - **CSV**: a header row naming a `lon` and a `lat` column (also `lon_deg`/`lat_deg`,
//!   `longitude`/`latitude`; any case, any order; other columns are ignored), then one row
//!   per point. Blank lines are skipped.
//!
//! Every error names the file and the feature, position or line at fault.

use std::path::Path;

use serde_json::Value;

use crate::error::{MAX_EXCERPT_CHARS, excerpt, readable_value};
use crate::point_files::{PointFileError, read_csv};
use crate::starter::TrackPoint;

/// A track error.
type Result<T> = std::result::Result<T, PointFileError>;

/// The bundled example track of `solsim init`, relative to the repository.
pub const EXAMPLE_TRACK: &str = "scenarios/tracks/jezero-example.geojson";

/// The example track's text (compiled in, so `solsim init` works anywhere).
const EXAMPLE_TRACK_TEXT: &str = include_str!("../../scenarios/tracks/jezero-example.geojson");

/// The bundled example track ([`EXAMPLE_TRACK`]: 1.46 km north-east from the Octavia E.
/// Butler landing site).
///
/// # Errors
/// None for the bundled file (a test reads it); the type is [`parse_geojson`]'s.
pub fn example_track() -> Result<Vec<TrackPoint>> {
    parse_geojson(EXAMPLE_TRACK_TEXT, Path::new(EXAMPLE_TRACK))
}

/// Read the track at `path`: CSV when its name ends in `.csv` (any case), GeoJSON otherwise.
///
/// # Errors
/// One line naming the file and the feature, position or line at fault.
pub fn read_track(path: &Path) -> Result<Vec<TrackPoint>> {
    let text = maps::input_file::read_text_file(path).map_err(|error| PointFileError::Read {
        path: path.to_path_buf(),
        what: "track file",
        error,
    })?;
    let is_csv = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("csv"));
    if is_csv {
        parse_csv(&text, path)
    } else {
        parse_geojson(&text, path)
    }
}

/// A longitude and latitude, checked: finite, −180 ..= 360° E and −90 ..= 90° N.
fn lonlat(lon: f64, lat: f64, at: &str, file: &str) -> Result<TrackPoint> {
    if !(lon.is_finite() && (-180.0..=360.0).contains(&lon)) {
        return Err(PointFileError::field(
            file,
            at,
            "a longitude in degrees east (planetocentric), −180 ..= 360",
            readable_value(&lon.to_string()),
        ));
    }
    if !(lat.is_finite() && (-90.0..=90.0).contains(&lat)) {
        return Err(PointFileError::field(
            file,
            at,
            "a latitude in degrees north (planetocentric), −90 ..= 90",
            readable_value(&lat.to_string()),
        ));
    }
    Ok(TrackPoint {
        lonlat_deg: [lon, lat],
        at: at.to_owned(),
    })
}

/// Parse CSV track text (see the module docs).
///
/// # Errors
/// One line naming the file, the line and the column at fault.
pub fn parse_csv(text: &str, path: &Path) -> Result<Vec<TrackPoint>> {
    let file = path.display().to_string();
    let expected_header = "a header row naming a lon and a lat column (lon_deg/lat_deg and \
                           longitude/latitude also do), degrees";
    let (header, rows) = read_csv(text, &file, expected_header)?;
    let (header_line, header) = (header.line, header.fields);
    let find = |names: [&str; 3]| -> Result<Option<usize>> {
        let cols: Vec<usize> = header
            .iter()
            .enumerate()
            .filter(|(_, c)| names.iter().any(|n| c.eq_ignore_ascii_case(n)))
            .map(|(k, _)| k)
            .collect();
        match cols.as_slice() {
            [] => Ok(None),
            [k] => Ok(Some(*k)),
            _ => Err(PointFileError::field(
                &file,
                format!("line {header_line}"),
                format!("one {} column", names[0]),
                cols.len(),
            )),
        }
    };
    let (lon_col, lat_col) = (
        find(["lon", "lon_deg", "longitude"])?,
        find(["lat", "lat_deg", "latitude"])?,
    );
    let (Some(lon_col), Some(lat_col)) = (lon_col, lat_col) else {
        // Until the header names a column, the file may be anything: quote nothing of it.
        let missing = match (lon_col, lat_col) {
            (None, None) => "names neither",
            (None, _) => "has no lon column",
            _ => "has no lat column",
        };
        return Err(PointFileError::field(
            &file,
            format!("line {header_line}"),
            expected_header,
            format!(
                "a row of {} field(s) that {missing} (the header row is required)",
                header.len()
            ),
        ));
    };
    let mut points = Vec::new();
    let expected = format!("{} fields, as the header", header.len());
    for row in rows.of_width(header.len(), expected) {
        let (line, fields) = row?;
        let number = |col: usize, what: &str| -> Result<f64> {
            let raw = fields[col].as_str();
            raw.parse::<f64>().map_err(|_| {
                PointFileError::field(
                    &file,
                    format!("line {line}, column {}", excerpt(&header[col], 40)),
                    format!("a number of degrees {what}"),
                    format!("{:?}", excerpt(raw, 40)),
                )
            })
        };
        let lon = number(lon_col, "east")?;
        let lat = number(lat_col, "north")?;
        let at = format!("line {line}, column {}", excerpt(&header[lat_col], 40));
        let at_lon = format!("line {line}, column {}", excerpt(&header[lon_col], 40));
        // Name the column at fault.
        if !(lon.is_finite() && (-180.0..=360.0).contains(&lon)) {
            lonlat(lon, lat, &at_lon, &file)?;
        }
        let mut p = lonlat(lon, lat, &at, &file)?;
        p.at = format!("line {line}");
        points.push(p);
    }
    if points.len() < 2 {
        return Err(PointFileError::whole(
            &file,
            "at least 2 points (a route) below the header",
            points.len(),
        ));
    }
    Ok(points)
}

/// The `type` member of a GeoJSON object.
fn type_of<'a>(v: &'a Value, field: &str, file: &str) -> Result<&'a str> {
    match v.get("type") {
        Some(Value::String(t)) => Ok(t),
        Some(other) => Err(PointFileError::field(
            file,
            format!("{field}.type"),
            "a GeoJSON type name",
            maps::json_kind(other),
        )),
        None if v.is_object() => Err(PointFileError::field(
            file,
            format!("{field}.type"),
            "a GeoJSON type",
            "none",
        )),
        None => Err(PointFileError::field(
            file,
            field,
            "a GeoJSON object",
            maps::json_kind(v),
        )),
    }
}

/// One position `[lon, lat]` (or `[lon, lat, elevation]`) at `field`.
fn position(v: &Value, field: &str, file: &str) -> Result<TrackPoint> {
    let numbers: Option<Vec<f64>> = v
        .as_array()
        .and_then(|a| a.iter().map(Value::as_f64).collect());
    match numbers.as_deref() {
        Some([lon, lat] | [lon, lat, _]) => lonlat(*lon, *lat, field, file),
        Some(n) => Err(PointFileError::field(
            file,
            field,
            "a position [longitude, latitude] in degrees",
            format!("{} number(s)", n.len()),
        )),
        None => Err(PointFileError::field(
            file,
            field,
            "a position [longitude, latitude] in degrees",
            if v.is_array() {
                "an array holding something other than numbers"
            } else {
                maps::json_kind(v)
            },
        )),
    }
}

/// The positions of a LineString or MultiPoint geometry at `field`.
fn line_positions(geometry: &Value, field: &str, file: &str) -> Result<Vec<TrackPoint>> {
    let Some(coords) = geometry.get("coordinates").and_then(Value::as_array) else {
        return Err(PointFileError::field(
            file,
            format!("{field}.coordinates"),
            "an array of positions",
            "none",
        ));
    };
    coords
        .iter()
        .enumerate()
        .map(|(i, c)| position(c, &format!("{field}.coordinates[{i}]"), file))
        .collect()
}

/// Parse GeoJSON track text (see the module docs).
///
/// # Errors
/// One line naming the file and the feature or position at fault.
pub fn parse_geojson(text: &str, path: &Path) -> Result<Vec<TrackPoint>> {
    let file = path.display().to_string();
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let root: Value = serde_json::from_str(text).map_err(|e| {
        // JSON has no NaN or Infinity: say so where one stands.
        let offset = text
            .lines()
            .take(e.line().saturating_sub(1))
            .map(|l| l.len() + 1)
            .sum::<usize>()
            + e.column().saturating_sub(1);
        let here = text.get(offset.min(text.len())..).unwrap_or("");
        let back = text
            .get(offset.saturating_sub(1).min(text.len())..)
            .unwrap_or("");
        let non_finite = ["NaN", "Infinity", "-Infinity"]
            .iter()
            .any(|w| here.starts_with(w) || back.starts_with(w));
        if non_finite {
            PointFileError::field(
                &file,
                format!("line {}, column {}", e.line(), e.column()),
                "a finite number of degrees",
                "NaN or Infinity (not a JSON number)",
            )
        } else {
            PointFileError::whole(
                &file,
                "a GeoJSON track (JSON)",
                format!(
                    "malformed JSON: {}",
                    excerpt(&e.to_string(), MAX_EXCERPT_CHARS)
                ),
            )
        }
    })?;
    if let Some(name) = root
        .get("crs")
        .and_then(|c| c.get("properties"))
        .and_then(|p| p.get("name"))
        .and_then(Value::as_str)
        && name.trim_start().starts_with("PROJCRS")
    {
        return Err(PointFileError::field(
            &file,
            "crs",
            "longitude/latitude degrees (IAU_2015:49900, or no crs member)",
            "a projected CRS in metres (a gis/projected/ layer? use the layer beside it in gis/)",
        ));
    }
    let points = match type_of(&root, "(root)", &file)? {
        "FeatureCollection" => {
            let Some(features) = root.get("features").and_then(Value::as_array) else {
                return Err(PointFileError::field(
                    &file,
                    "features",
                    "an array of features",
                    "none",
                ));
            };
            let geometries: Vec<(String, &Value)> = features
                .iter()
                .enumerate()
                .map(|(i, f)| {
                    let field = format!("features[{i}]");
                    match type_of(f, &field, &file)? {
                        "Feature" => match f.get("geometry") {
                            Some(g) if g.is_object() => Ok((format!("{field}.geometry"), g)),
                            _ => Err(PointFileError::field(
                                &file,
                                format!("{field}.geometry"),
                                "a Point, LineString or MultiPoint",
                                "none",
                            )),
                        },
                        other => Err(PointFileError::field(
                            &file,
                            format!("{field}.type"),
                            "\"Feature\"",
                            format!("{:?}", excerpt(other, 40)),
                        )),
                    }
                })
                .collect::<Result<_>>()?;
            match geometries.as_slice() {
                [] => {
                    return Err(PointFileError::field(
                        &file,
                        "features",
                        "a track",
                        "no features",
                    ));
                }
                [(field, g)]
                    if matches!(type_of(g, field, &file)?, "LineString" | "MultiPoint") =>
                {
                    line_positions(g, field, &file)?
                }
                _ => {
                    let mut points = Vec::new();
                    for (field, g) in &geometries {
                        match type_of(g, field, &file)? {
                            "Point" => {
                                let Some(c) = g.get("coordinates") else {
                                    return Err(PointFileError::field(
                                        &file,
                                        format!("{field}.coordinates"),
                                        "a position",
                                        "none",
                                    ));
                                };
                                points.push(position(c, &format!("{field}.coordinates"), &file)?);
                            }
                            other => {
                                return Err(PointFileError::field(
                                    &file,
                                    format!("{field}.type"),
                                    "\"Point\" (a FeatureCollection of several features is a track of Points, in order; a LineString must be the only feature)",
                                    format!("{:?}", excerpt(other, 40)),
                                ));
                            }
                        }
                    }
                    points
                }
            }
        }
        "Feature" => match root.get("geometry") {
            Some(g) if g.is_object() => geometry_points(g, "geometry", &file)?,
            _ => {
                return Err(PointFileError::field(
                    &file,
                    "geometry",
                    "a LineString or MultiPoint",
                    "none",
                ));
            }
        },
        _ => geometry_points(&root, "(root)", &file)?,
    };
    if points.len() < 2 {
        return Err(PointFileError::whole(
            &file,
            "at least 2 points (a route)",
            points.len(),
        ));
    }
    Ok(points)
}

/// The positions of a bare geometry: a LineString or a MultiPoint.
fn geometry_points(g: &Value, field: &str, file: &str) -> Result<Vec<TrackPoint>> {
    match type_of(g, field, file)? {
        "LineString" | "MultiPoint" => line_positions(g, field, file),
        other => Err(PointFileError::field(
            file,
            format!("{field}.type"),
            "a LineString, a MultiPoint, a Feature of one or a FeatureCollection (of one LineString or of Points)",
            format!("{:?}", excerpt(other, 40)),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn geo(text: &str) -> Result<Vec<TrackPoint>> {
        parse_geojson(text, Path::new("t.geojson"))
    }
    fn csv(text: &str) -> Result<Vec<TrackPoint>> {
        parse_csv(text, Path::new("t.csv"))
    }
    fn err(r: Result<Vec<TrackPoint>>) -> String {
        r.expect_err("refused").to_string()
    }

    #[test]
    fn every_geojson_shape_reads_in_order() {
        let line =
            r#"{"type": "LineString", "coordinates": [[77.45, 18.44], [77.46, 18.45, -2500]]}"#;
        let want = [[77.45, 18.44], [77.46, 18.45]];
        let ll = |p: Vec<TrackPoint>| p.iter().map(|p| p.lonlat_deg).collect::<Vec<_>>();
        assert_eq!(ll(geo(line).expect("bare")), want);
        let feature = format!(r#"{{"type": "Feature", "properties": {{}}, "geometry": {line}}}"#);
        assert_eq!(ll(geo(&feature).expect("feature")), want);
        let fc = format!(r#"{{"type": "FeatureCollection", "features": [{feature}]}}"#);
        assert_eq!(ll(geo(&fc).expect("collection")), want);
        let mp = line.replace("LineString", "MultiPoint");
        assert_eq!(ll(geo(&mp).expect("multipoint")), want);
        let points = r#"{"type": "FeatureCollection", "features": [
            {"type": "Feature", "geometry": {"type": "Point", "coordinates": [77.45, 18.44]}},
            {"type": "Feature", "geometry": {"type": "Point", "coordinates": [77.46, 18.45]}}]}"#;
        let p = geo(points).expect("points");
        assert_eq!(ll(p.clone()), want);
        assert_eq!(p[1].at, "features[1].geometry.coordinates");
    }

    #[test]
    fn bad_geojson_names_the_place() {
        assert!(
            err(geo("{\"type\": "))
                .contains("t.geojson: expected a GeoJSON track (JSON), got malformed JSON")
        );
        let e = err(geo(
            r#"{"type": "LineString", "coordinates": [[77.4, NaN], [77.5, 18.4]]}"#,
        ));
        assert!(
            e.contains("line 1, column") && e.contains("NaN or Infinity"),
            "{e}"
        );
        let e = err(geo(
            r#"{"type": "LineString", "coordinates": [[77.4, 18.4], [77.5, 95.0]]}"#,
        ));
        assert!(
            e.contains("t.geojson: (root).coordinates[1]: expected a latitude in degrees north"),
            "{e}"
        );
        let e = err(geo(
            r#"{"type": "LineString", "coordinates": [[77.4, 18.4]]}"#,
        ));
        assert!(
            e.contains("expected at least 2 points (a route), got 1"),
            "{e}"
        );
        let e = err(geo(r#"{"type": "FeatureCollection", "features": [
            {"type": "Feature", "geometry": {"type": "Point", "coordinates": [77.45, 18.44]}},
            {"type": "Feature", "geometry": {"type": "Polygon", "coordinates": []}}]}"#));
        assert!(
            e.contains("features[1].geometry.type: expected \"Point\""),
            "{e}"
        );
        let e = err(geo(r#"{"type": "Polygon", "coordinates": []}"#));
        assert!(e.contains("(root).type: expected a LineString"), "{e}");
        let e = err(geo(
            r#"{"type": "LineString", "coordinates": [[77.4, "18.4"], [77.5, 18.4]]}"#,
        ));
        assert!(
            e.contains("coordinates[0]: expected a position [longitude, latitude] in degrees"),
            "{e}"
        );
        let e = err(geo(
            r#"{"type": "LineString", "crs": {"type": "name", "properties": {"name": "PROJCRS[\"x\"]"}}, "coordinates": []}"#,
        ));
        assert!(
            e.contains("crs: expected longitude/latitude degrees"),
            "{e}"
        );
    }

    #[test]
    fn csv_reads_with_its_header() {
        let p = csv("name,Lat,lon\na,18.44,77.45\n\nb,18.45,77.46\n").expect("csv");
        assert_eq!(p[1].lonlat_deg, [77.46, 18.45]);
        assert_eq!(p[1].at, "line 4");
        let e = err(csv("77.45,18.44\n77.46,18.45\n"));
        assert!(
            e.contains("t.csv: line 1: expected a header row naming a lon and a lat column"),
            "{e}"
        );
        assert!(e.contains("the header row is required"), "{e}");
        let e = err(csv("lon,lat\n77.45,nan\n77.46,18.45\n"));
        assert!(
            e.contains("t.csv: line 2, column lat: expected a latitude in degrees north"),
            "{e}"
        );
        let e = err(csv("lon,lat\n77.45,18.4\n400,18.45\n"));
        assert!(
            e.contains("t.csv: line 3, column lon: expected a longitude"),
            "{e}"
        );
        let e = err(csv("lon,lat\n77.45,18.4\n77.46\n"));
        assert!(e.contains("t.csv: line 3: expected 2 fields"), "{e}");
        let e = err(csv("lon,lat\n77.45,north\n"));
        assert!(
            e.contains("line 2, column lat: expected a number of degrees north, got \"north\""),
            "{e}"
        );
        let e = err(csv("lon,lat\n77.45,18.4\n"));
        assert!(e.contains("expected at least 2 points"), "{e}");
    }
}
