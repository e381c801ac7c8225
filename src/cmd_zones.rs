//! `solsim zones check`: how far points are from a map's keep-in and keep-out zones.
//!
//! Reads a zones GeoJSON ([`maps::ZoneSet`]) and a points CSV, and prints one row per point:
//!
//! ```text
//! name        x_m     y_m  keep_out_distance_m  keep_in_edge_distance_m  max_uncertainty_m  status
//! L notch  130.000 140.000               15.000                   81.205             14.250  clear
//! ```
//!
//! - `keep_out_distance_m`: distance to the nearest keep-out zone (0 inside one); `inf` without
//!   keep-outs.
//! - `keep_in_edge_distance_m`: inside the union of keep-in zones, the distance to its edge; 0
//!   outside it; `inf` without keep-ins.
//! - `max_uncertainty_m` = min(the two) − footprint radius: the largest position error for which
//!   the rover's footprint stays clear of every keep-out and inside the keep-in area. Negative means
//!   it is already touching a forbidden area there; it is not a depth: inside a keep-out (or
//!   outside the keep-in area) the distance is 0, so the number is minus the footprint radius
//!   however deep the point lies.
//! - `status`: where the point is — `clear`, `footprint touches a zone` (outside every zone, but
//!   nearer one than the footprint radius), `inside keep-out (NAME, …)` (edges count as
//!   inside), `outside keep-in`, or both of the last two.
//!
//! Under the table one line says the sign convention. `--json` prints an array of objects with
//! those keys (infinite values as `null`, full precision) and the flags `inside_keep_out` and
//! `outside_keep_in`. `peers/zones_reference.py` prints the same numbers computed with shapely.

use anyhow::{Context, anyhow, bail};
use maps::ZoneSet;
use maps::input_file::{first_unsafe_char, printable};
use maps::zone::MAX_COORDINATE_M;
use std::io::Write;
use std::path::{Path, PathBuf};
use study::error::{MAX_EXCERPT_CHARS, excerpt, readable_value};

/// Check points against a map's zones: distance to the nearest keep-out zone, distance to the
/// edge of the keep-in area, the largest position uncertainty each point tolerates, and where
/// the point is.
///
/// max_uncertainty_m = min of the two distances − footprint radius. Negative means the point is
/// not drivable at any uncertainty; it is not a depth: inside a keep-out (or outside the keep-in
/// area) the distance is 0, so the number is minus the footprint radius however deep the point
/// lies. The status column says where the point is: clear, footprint touches a zone (outside
/// every zone but nearer one than the footprint radius), inside keep-out (NAME, …; edges count
/// as inside), outside keep-in. --json gives the same with the flags inside_keep_out and
/// outside_keep_in.
#[derive(Debug, Clone, clap::Args)]
pub struct ZonesCheckArgs {
    /// Zones file: a GeoJSON FeatureCollection of Polygon/MultiPolygon features in map metres,
    /// with properties `kind` ("keep_in" or "keep_out") and optional `name`.
    #[arg(long, value_name = "FILE")]
    pub zones: PathBuf,

    /// Points CSV: a header row naming the columns x_m, y_m and optionally name (any order), then
    /// one point per row in map metres.
    #[arg(long, value_name = "FILE")]
    pub points: PathBuf,

    /// Rover footprint radius in metres, subtracted from the nearer zone distance to give
    /// max_uncertainty_m.
    #[arg(long, value_name = "METRES", default_value_t = 0.0)]
    pub footprint_radius_m: f64,

    /// Print a JSON array of objects (infinite distances as null) instead of the table.
    #[arg(long)]
    pub json: bool,
}

/// Run `solsim zones check`, writing the table (or JSON) to `out`.
///
/// # Errors
/// An unreadable or invalid zones file (a [`maps::ZoneError`]) or points file (naming the line and
/// column), a negative or non-finite footprint radius, or a failed write.
pub fn run(args: &ZonesCheckArgs, out: &mut dyn Write) -> anyhow::Result<()> {
    let footprint = args.footprint_radius_m;
    let range = study::scenario::ranges::FOOTPRINT_RADIUS_M;
    if !range.contains(footprint) {
        bail!(
            "--footprint-radius-m: expected {} ..= {} {}, got {footprint}",
            range.min,
            range.max,
            range.unit
        );
    }
    let zones = ZoneSet::load(&args.zones)?;
    let points = read_points(&args.points)?;
    let xy: Vec<[f64; 2]> = points.iter().map(|p| p.xy).collect();
    let clearances = zones.clearances(&xy, footprint);
    let rows: Vec<Row<'_>> = points
        .iter()
        .zip(&clearances)
        .map(|(p, c)| {
            // The zone names only for a point inside one: the index answers the question
            // for every other point.
            let keep_outs: Vec<String> = if zones.in_keep_out(p.xy) {
                zones
                    .keep_outs()
                    .filter(|(_, z)| z.covers(p.xy))
                    .map(|(_, z)| z.name().to_string())
                    .collect()
            } else {
                Vec::new()
            };
            Row {
                name: &p.name,
                x_m: p.xy[0],
                y_m: p.xy[1],
                keep_out_distance_m: c.keep_out_distance_m,
                keep_in_edge_distance_m: c.keep_in_edge_distance_m,
                max_uncertainty_m: c.max_uncertainty_m,
                inside_keep_outs: keep_outs,
                outside_keep_in: !zones.in_keep_in(p.xy),
            }
        })
        .collect();
    match if args.json {
        write_json(&rows, out)
    } else {
        write_table(&rows, out)
    } {
        // A closed pipe (`| head`) means the reader has seen enough, not that the check failed.
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        written => written.context("writing the zones check output"),
    }
}

/// Column names, in output order.
const COLUMNS: [&str; 7] = [
    "name",
    "x_m",
    "y_m",
    "keep_out_distance_m",
    "keep_in_edge_distance_m",
    "max_uncertainty_m",
    "status",
];

/// The line under the table: what the sign of `max_uncertainty_m` means.
const SIGN_CONVENTION: &str = "max_uncertainty_m = min(keep_out_distance_m, \
     keep_in_edge_distance_m) − footprint radius: the largest position error at which the point \
     stays drivable; negative = not drivable at any error, and not a depth (inside a zone the \
     distance is 0, so it is minus the footprint radius): status says where the point is";

/// One output row.
struct Row<'a> {
    name: &'a str,
    x_m: f64,
    y_m: f64,
    keep_out_distance_m: f64,
    keep_in_edge_distance_m: f64,
    max_uncertainty_m: f64,
    /// The keep-out zones the point lies in (edges included), by name; empty when outside.
    inside_keep_outs: Vec<String>,
    /// The point lies outside the keep-in area (never, without keep-in zones).
    outside_keep_in: bool,
}

impl Row<'_> {
    /// Where the point is: `clear`, `footprint touches a zone`, `inside keep-out (NAME, …)`,
    /// `outside keep-in`, or both of the last two.
    fn status(&self) -> String {
        let mut parts = Vec::new();
        if !self.inside_keep_outs.is_empty() {
            parts.push(format!(
                "inside keep-out ({})",
                self.inside_keep_outs.join(", ")
            ));
        }
        if self.outside_keep_in {
            parts.push("outside keep-in".to_string());
        }
        if !parts.is_empty() {
            parts.join(", ")
        } else if self.max_uncertainty_m < 0.0 {
            "footprint touches a zone".into()
        } else {
            "clear".into()
        }
    }

    fn numbers(&self) -> [f64; 5] {
        [
            self.x_m,
            self.y_m,
            self.keep_out_distance_m,
            self.keep_in_edge_distance_m,
            self.max_uncertainty_m,
        ]
    }
}

/// Fixed-width table: names left-aligned, numbers right-aligned with 3 decimals (`inf` when
/// there are no zones of that kind), columns separated by two spaces.
fn write_table(rows: &[Row<'_>], out: &mut dyn Write) -> std::io::Result<()> {
    let cells: Vec<[String; 7]> = rows
        .iter()
        .map(|r| {
            let n = r.numbers().map(|v| format!("{v:.3}"));
            [
                // The loader refuses control characters in names; escape them all the same.
                printable(r.name).into_owned(),
                n[0].clone(),
                n[1].clone(),
                n[2].clone(),
                n[3].clone(),
                n[4].clone(),
                printable(&r.status()).into_owned(),
            ]
        })
        .collect();
    let mut widths = COLUMNS.map(str::len);
    for row in &cells {
        for (w, cell) in widths.iter_mut().zip(row) {
            *w = (*w).max(cell.chars().count());
        }
    }
    let line = |values: [&str; 7]| -> String {
        let mut s = format!("{:<w$}", values[0], w = widths[0]);
        for (value, w) in values.iter().zip(widths).skip(1).take(5) {
            s.push_str(&format!("  {value:>w$}"));
        }
        // The status is text, the last column: left-aligned, no padding after it.
        s.push_str(&format!("  {}", values[6]));
        s
    };
    writeln!(out, "{}", line(COLUMNS))?;
    for row in &cells {
        writeln!(out, "{}", line(row.each_ref().map(String::as_str)))?;
    }
    writeln!(out, "{SIGN_CONVENTION}")?;
    Ok(())
}

/// JSON array of objects keyed like the table's columns (in that order); infinite distances
/// become `null`.
fn write_json(rows: &[Row<'_>], out: &mut dyn Write) -> std::io::Result<()> {
    #[derive(serde::Serialize)]
    struct JsonRow<'a> {
        name: &'a str,
        x_m: f64,
        y_m: f64,
        keep_out_distance_m: Option<f64>,
        keep_in_edge_distance_m: Option<f64>,
        max_uncertainty_m: Option<f64>,
        status: String,
        inside_keep_out: bool,
        outside_keep_in: bool,
    }
    let finite = |v: f64| v.is_finite().then_some(v);
    let array: Vec<JsonRow<'_>> = rows
        .iter()
        .map(|r| JsonRow {
            name: r.name,
            x_m: r.x_m,
            y_m: r.y_m,
            keep_out_distance_m: finite(r.keep_out_distance_m),
            keep_in_edge_distance_m: finite(r.keep_in_edge_distance_m),
            max_uncertainty_m: finite(r.max_uncertainty_m),
            status: r.status(),
            inside_keep_out: !r.inside_keep_outs.is_empty(),
            outside_keep_in: r.outside_keep_in,
        })
        .collect();
    serde_json::to_writer_pretty(&mut *out, &array)?;
    writeln!(out)
}

/// A point from the CSV.
#[derive(Debug, Clone, PartialEq)]
pub struct NamedPoint {
    /// The `name` column, or `point-<k>`.
    pub name: String,
    /// `x_m`, `y_m`: map metres.
    pub xy: [f64; 2],
}

/// Read the points CSV at `path`.
fn read_points(path: &Path) -> anyhow::Result<Vec<NamedPoint>> {
    let text = maps::input_file::read_text_file(path)
        .map_err(|e| anyhow!("{}: points file: {e}", path.display()))?;
    parse_points(&text, path)
}

/// A CSV file's non-blank lines with their 1-based line numbers, after a UTF-8 byte-order mark.
pub(crate) fn numbered_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.strip_prefix('\u{feff}')
        .unwrap_or(text)
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l))
        .filter(|(_, l)| !l.trim().is_empty())
}

/// Parse points CSV text: a header naming `x_m`, `y_m` and optionally `name` (any order, each
/// once, nothing else), then one row per point; blank lines are skipped. A row without a name
/// (or an empty one) is called `point-<k>`, `k` counting data rows from 0.
///
/// # Errors
/// One line naming the file, the line and the column at fault.
pub fn parse_points(text: &str, path: &Path) -> anyhow::Result<Vec<NamedPoint>> {
    let file = path.display();
    let mut lines = numbered_lines(text);
    let Some((header_line, header)) = lines.next() else {
        bail!(
            "{file}: empty file; expected a header row naming the columns x_m, y_m and optionally name"
        );
    };
    let header = split_fields(header).map_err(|e| anyhow!("{file}: line {header_line}: {e}"))?;
    // Until the header names one of the columns, the file may be anything (`/etc/shadow`, a
    // key file): say what was expected, quote nothing of it.
    if !header
        .iter()
        .any(|c| ["x_m", "y_m", "name"].contains(&c.as_str()))
    {
        bail!(
            "{file}: line {header_line}: expected a header row naming the columns x_m, y_m and optionally name, got {} that names none of them (not quoted: the file does not read as a points CSV)",
            if header.len() == 1 {
                "a row of 1 field".to_owned()
            } else {
                format!("a row of {} fields", header.len())
            }
        );
    }
    let mut unknown = Vec::new();
    let (mut x_col, mut y_col, mut name_col) = (None, None, None);
    for (k, column) in header.iter().enumerate() {
        let slot = match column.as_str() {
            "x_m" => &mut x_col,
            "y_m" => &mut y_col,
            "name" => &mut name_col,
            _ => {
                unknown.push(format!("{:?}", excerpt(column, 40)));
                continue;
            }
        };
        if slot.replace(k).is_some() {
            bail!(
                "{file}: line {header_line}: column {} appears twice",
                excerpt(column, 40)
            );
        }
    }
    if !unknown.is_empty() {
        bail!(
            "{file}: line {header_line}: unknown column(s) {}; expected a header row naming x_m, y_m and optionally name",
            excerpt(&unknown.join(", "), MAX_EXCERPT_CHARS)
        );
    }
    let (Some(x_col), Some(y_col)) = (x_col, y_col) else {
        let missing = if x_col.is_none() { "x_m" } else { "y_m" };
        bail!(
            "{file}: line {header_line}: missing column {missing}; expected x_m, y_m and optionally name"
        );
    };
    let mut points = Vec::new();
    for (line, text) in lines {
        let fields = split_fields(text).map_err(|e| anyhow!("{file}: line {line}: {e}"))?;
        if fields.len() != header.len() {
            bail!(
                "{file}: line {line}: expected {} fields ({}), got {}",
                header.len(),
                header.join(","),
                fields.len()
            );
        }
        let number = |col: usize| -> anyhow::Result<f64> {
            let raw = &fields[col];
            match raw.parse::<f64>() {
                Ok(v) if v.is_finite() && v.abs() <= MAX_COORDINATE_M => Ok(v),
                _ => bail!(
                    "{file}: line {line}, column {}: expected a finite number of metres within ±{MAX_COORDINATE_M}, got {:?}",
                    header[col],
                    excerpt(&readable_value(raw), 40)
                ),
            }
        };
        let xy = [number(x_col)?, number(y_col)?];
        let name = match name_col.map(|c| fields[c].clone()) {
            // Names are printed in the table: an escape sequence would drive the terminal.
            Some(name) if first_unsafe_char(&name).is_some() => bail!(
                "{file}: line {line}, column name: expected text without control characters, got \"{}\"",
                excerpt(&name, 40)
            ),
            Some(name) if !name.is_empty() => name,
            _ => format!("point-{}", points.len()),
        };
        points.push(NamedPoint { name, xy });
    }
    Ok(points)
}

/// Split one CSV line into fields: commas separate; a field may be double-quoted (with `""` for a
/// quote inside); unquoted fields are trimmed.
pub(crate) fn split_fields(line: &str) -> Result<Vec<String>, &'static str> {
    let mut fields = Vec::new();
    let mut chars = line.chars().peekable();
    loop {
        while chars.next_if(|c| *c == ' ' || *c == '\t').is_some() {}
        let mut field = String::new();
        if chars.next_if_eq(&'"').is_some() {
            loop {
                match chars.next() {
                    Some('"') if chars.next_if_eq(&'"').is_some() => field.push('"'),
                    Some('"') => break,
                    Some(c) => field.push(c),
                    None => return Err("unterminated quoted field"),
                }
            }
            while chars.next_if(|c| *c == ' ' || *c == '\t').is_some() {}
            match chars.next() {
                None => {
                    fields.push(field);
                    return Ok(fields);
                }
                Some(',') => fields.push(field),
                Some(_) => return Err("unexpected text after a quoted field"),
            }
        } else {
            loop {
                match chars.next() {
                    None => {
                        fields.push(field.trim().to_owned());
                        return Ok(fields);
                    }
                    Some(',') => break,
                    Some(c) => field.push(c),
                }
            }
            fields.push(field.trim().to_owned());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> anyhow::Result<Vec<NamedPoint>> {
        parse_points(text, Path::new("points.csv"))
    }

    #[test]
    fn columns_in_any_order_and_default_names() {
        let pts = parse("y_m, name ,x_m\n2,\"a, b\",1\n\n4,,3\r\n").expect("valid");
        assert_eq!(
            pts,
            vec![
                NamedPoint {
                    name: "a, b".into(),
                    xy: [1.0, 2.0]
                },
                NamedPoint {
                    name: "point-1".into(),
                    xy: [3.0, 4.0]
                }
            ]
        );
        assert_eq!(parse("x_m,y_m\n").expect("header only"), vec![]);
    }

    #[test]
    fn errors_name_file_line_and_column() {
        let msg = |t: &str| parse(t).expect_err("invalid").to_string();
        assert_eq!(
            msg("name,x_m,y_m\na,1,2\nb,1,abc\n"),
            "points.csv: line 3, column y_m: expected a finite number of metres within ±11000000, got \"abc\""
        );
        assert!(msg("x_m,y_m\nNaN,1\n").contains("line 2, column x_m"));
        assert!(msg("x_m,y_m,z_m,foo\n").contains("line 1: unknown column(s) \"z_m\", \"foo\""));
        assert_eq!(
            msg("1.0,2.0\n"),
            "points.csv: line 1: expected a header row naming the columns x_m, y_m and optionally name, got a row of 2 fields that names none of them (not quoted: the file does not read as a points CSV)"
        );
        assert!(msg("x_m,y_m,name\n1,2,a\u{1b}[2J\n").contains(
            "line 2, column name: expected text without control characters, got \"a\\u{1b}[2J\""
        ));
        assert!(msg("x_m,name\n").contains("missing column y_m"));
        assert!(msg("x_m,y_m,x_m\n").contains("column x_m appears twice"));
        assert!(msg("x_m,y_m\n1\n").contains("line 2: expected 2 fields (x_m,y_m), got 1"));
        assert!(msg("").contains("empty file"));
        assert!(msg("x_m,y_m\n\"1,2\n").contains("line 2: unterminated quoted field"));
    }

    #[test]
    fn table_and_json() {
        let rows = [
            Row {
                name: "p",
                x_m: 1.0,
                y_m: -2.5,
                keep_out_distance_m: f64::INFINITY,
                keep_in_edge_distance_m: 3.25,
                max_uncertainty_m: 3.0,
                inside_keep_outs: Vec::new(),
                outside_keep_in: false,
            },
            Row {
                name: "q",
                x_m: 4.0,
                y_m: 5.0,
                keep_out_distance_m: 0.0,
                keep_in_edge_distance_m: 0.0,
                max_uncertainty_m: -1.65,
                inside_keep_outs: vec!["rock".into()],
                outside_keep_in: true,
            },
        ];
        let mut out = Vec::new();
        write_table(&rows, &mut out).expect("write");
        assert_eq!(
            String::from_utf8_lossy(&out),
            format!(
                "name    x_m     y_m  keep_out_distance_m  keep_in_edge_distance_m  max_uncertainty_m  status\n\
                 p     1.000  -2.500                  inf                    3.250              3.000  clear\n\
                 q     4.000   5.000                0.000                    0.000             -1.650  inside keep-out (rock), outside keep-in\n\
                 {SIGN_CONVENTION}\n"
            )
        );
        let mut out = Vec::new();
        write_json(&rows, &mut out).expect("write");
        let text = String::from_utf8_lossy(&out);
        let keys: Vec<usize> = COLUMNS
            .iter()
            .map(|k| text.find(&format!("\"{k}\"")).unwrap_or(usize::MAX))
            .collect();
        assert!(
            keys.windows(2).all(|w| w[0] < w[1]),
            "keys in column order: {text}"
        );
        let v: serde_json::Value = serde_json::from_slice(&out).expect("json");
        assert_eq!(v[0]["keep_out_distance_m"], serde_json::Value::Null);
        assert_eq!(v[0]["keep_in_edge_distance_m"], 3.25);
        assert_eq!(v[0]["name"], "p");
        assert_eq!(v[0]["status"], "clear");
        assert_eq!(v[0]["inside_keep_out"], false);
        assert_eq!(v[1]["inside_keep_out"], true);
        assert_eq!(v[1]["outside_keep_in"], true);
    }
}
