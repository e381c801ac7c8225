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

use anyhow::{anyhow, bail};
use serde_json::Value;
use study::error::{MAX_EXCERPT_CHARS, excerpt, readable_value};
use study::starter::TrackPoint;

/// Read the track at `path`: CSV when its name ends in `.csv` (any case), GeoJSON otherwise.
///
/// # Errors
/// One line naming the file and the feature, position or line at fault.
pub fn read_track(path: &Path) -> anyhow::Result<Vec<TrackPoint>> {
    let text = maps::input_file::read_text_file(path)
        .map_err(|e| anyhow!("{}: track file: {e}", path.display()))?;
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
fn lonlat(lon: f64, lat: f64, at: &str, file: &str) -> anyhow::Result<TrackPoint> {
    if !(lon.is_finite() && (-180.0..=360.0).contains(&lon)) {
        bail!(
            "{file}: {at}: expected a longitude in degrees east (planetocentric), −180 ..= 360, got {}",
            readable_value(&lon.to_string())
        );
    }
    if !(lat.is_finite() && (-90.0..=90.0).contains(&lat)) {
        bail!(
            "{file}: {at}: expected a latitude in degrees north (planetocentric), −90 ..= 90, got {}",
            readable_value(&lat.to_string())
        );
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
pub fn parse_csv(text: &str, path: &Path) -> anyhow::Result<Vec<TrackPoint>> {
    let file = path.display().to_string();
    let mut lines = crate::cmd_zones::numbered_lines(text);
    let expected_header = "a header row naming a lon and a lat column (lon_deg/lat_deg and \
                           longitude/latitude also do), degrees";
    let Some((header_line, header)) = lines.next() else {
        bail!("{file}: empty file; expected {expected_header}");
    };
    let header = crate::cmd_zones::split_fields(header)
        .map_err(|e| anyhow!("{file}: line {header_line}: {e}"))?;
    let find = |names: [&str; 3]| -> anyhow::Result<Option<usize>> {
        let cols: Vec<usize> = header
            .iter()
            .enumerate()
            .filter(|(_, c)| names.iter().any(|n| c.eq_ignore_ascii_case(n)))
            .map(|(k, _)| k)
            .collect();
        match cols.as_slice() {
            [] => Ok(None),
            [k] => Ok(Some(*k)),
            _ => bail!(
                "{file}: line {header_line}: expected one {} column, got {}",
                names[0],
                cols.len()
            ),
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
        bail!(
            "{file}: line {header_line}: expected {expected_header}, got a row of {} field(s) that {missing} (the header row is required)",
            header.len()
        );
    };
    let mut points = Vec::new();
    for (line, row) in lines {
        let fields =
            crate::cmd_zones::split_fields(row).map_err(|e| anyhow!("{file}: line {line}: {e}"))?;
        if fields.len() != header.len() {
            bail!(
                "{file}: line {line}: expected {} fields, as the header, got {}",
                header.len(),
                fields.len()
            );
        }
        let number = |col: usize, what: &str| -> anyhow::Result<f64> {
            let raw = fields[col].as_str();
            raw.parse::<f64>().map_err(|_| {
                anyhow!(
                    "{file}: line {line}, column {}: expected a number of degrees {what}, got {:?}",
                    excerpt(&header[col], 40),
                    excerpt(raw, 40)
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
        bail!(
            "{file}: expected at least 2 points (a route) below the header, got {}",
            points.len()
        );
    }
    Ok(points)
}

/// The `type` member of a GeoJSON object.
fn type_of<'a>(v: &'a Value, field: &str, file: &str) -> anyhow::Result<&'a str> {
    match v.get("type") {
        Some(Value::String(t)) => Ok(t),
        Some(other) => bail!(
            "{file}: {field}.type: expected a GeoJSON type name, got {}",
            maps::json_kind(other)
        ),
        None if v.is_object() => bail!("{file}: {field}.type: expected a GeoJSON type, got none"),
        None => bail!(
            "{file}: {field}: expected a GeoJSON object, got {}",
            maps::json_kind(v)
        ),
    }
}

/// One position `[lon, lat]` (or `[lon, lat, elevation]`) at `field`.
fn position(v: &Value, field: &str, file: &str) -> anyhow::Result<TrackPoint> {
    let numbers: Option<Vec<f64>> = v
        .as_array()
        .and_then(|a| a.iter().map(Value::as_f64).collect());
    match numbers.as_deref() {
        Some([lon, lat] | [lon, lat, _]) => lonlat(*lon, *lat, field, file),
        Some(n) => bail!(
            "{file}: {field}: expected a position [longitude, latitude] in degrees, got {} number(s)",
            n.len()
        ),
        None => bail!(
            "{file}: {field}: expected a position [longitude, latitude] in degrees, got {}",
            if v.is_array() {
                "an array holding something other than numbers"
            } else {
                maps::json_kind(v)
            }
        ),
    }
}

/// The positions of a LineString or MultiPoint geometry at `field`.
fn line_positions(geometry: &Value, field: &str, file: &str) -> anyhow::Result<Vec<TrackPoint>> {
    let Some(coords) = geometry.get("coordinates").and_then(Value::as_array) else {
        bail!("{file}: {field}.coordinates: expected an array of positions, got none");
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
pub fn parse_geojson(text: &str, path: &Path) -> anyhow::Result<Vec<TrackPoint>> {
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
        let back = text.get(offset.saturating_sub(1).min(text.len())..).unwrap_or("");
        let non_finite = ["NaN", "Infinity", "-Infinity"]
            .iter()
            .any(|w| here.starts_with(w) || back.starts_with(w));
        if non_finite {
            anyhow!(
                "{file}: line {}, column {}: expected a finite number of degrees, got NaN or Infinity (not a JSON number)",
                e.line(),
                e.column()
            )
        } else {
            anyhow!(
                "{file}: expected a GeoJSON track (JSON), got malformed JSON: {}",
                excerpt(&e.to_string(), MAX_EXCERPT_CHARS)
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
        bail!(
            "{file}: crs: expected longitude/latitude degrees (IAU_2015:49900, or no crs member), got a projected CRS in metres (a gis/projected/ layer? use the layer beside it in gis/)"
        );
    }
    let points = match type_of(&root, "(root)", &file)? {
        "FeatureCollection" => {
            let Some(features) = root.get("features").and_then(Value::as_array) else {
                bail!("{file}: features: expected an array of features, got none");
            };
            let geometries: Vec<(String, &Value)> = features
                .iter()
                .enumerate()
                .map(|(i, f)| {
                    let field = format!("features[{i}]");
                    match type_of(f, &field, &file)? {
                        "Feature" => match f.get("geometry") {
                            Some(g) if g.is_object() => Ok((format!("{field}.geometry"), g)),
                            _ => bail!(
                                "{file}: {field}.geometry: expected a Point, LineString or MultiPoint, got none"
                            ),
                        },
                        other => bail!(
                            "{file}: {field}.type: expected \"Feature\", got {:?}",
                            excerpt(other, 40)
                        ),
                    }
                })
                .collect::<anyhow::Result<_>>()?;
            match geometries.as_slice() {
                [] => bail!("{file}: features: expected a track, got no features"),
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
                                    bail!(
                                        "{file}: {field}.coordinates: expected a position, got none"
                                    );
                                };
                                points.push(position(c, &format!("{field}.coordinates"), &file)?);
                            }
                            other => bail!(
                                "{file}: {field}.type: expected \"Point\" (a FeatureCollection of several features is a track of Points, in order; a LineString must be the only feature), got {:?}",
                                excerpt(other, 40)
                            ),
                        }
                    }
                    points
                }
            }
        }
        "Feature" => match root.get("geometry") {
            Some(g) if g.is_object() => geometry_points(g, "geometry", &file)?,
            _ => bail!("{file}: geometry: expected a LineString or MultiPoint, got none"),
        },
        _ => geometry_points(&root, "(root)", &file)?,
    };
    if points.len() < 2 {
        bail!(
            "{file}: expected at least 2 points (a route), got {}",
            points.len()
        );
    }
    Ok(points)
}

/// The positions of a bare geometry: a LineString or a MultiPoint.
fn geometry_points(g: &Value, field: &str, file: &str) -> anyhow::Result<Vec<TrackPoint>> {
    match type_of(g, field, file)? {
        "LineString" | "MultiPoint" => line_positions(g, field, file),
        other => bail!(
            "{file}: {field}.type: expected a LineString, a MultiPoint, a Feature of one or a FeatureCollection (of one LineString or of Points), got {:?}",
            excerpt(other, 40)
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn geo(text: &str) -> anyhow::Result<Vec<TrackPoint>> {
        parse_geojson(text, Path::new("t.geojson"))
    }
    fn csv(text: &str) -> anyhow::Result<Vec<TrackPoint>> {
        parse_csv(text, Path::new("t.csv"))
    }
    fn err(r: anyhow::Result<Vec<TrackPoint>>) -> String {
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
