//! The points CSV of `solsim zones check`: a header naming `x_m`, `y_m` and optionally `name`
//! (any order, each once, nothing else), then one point per row in map metres.

use std::path::Path;

use maps::input_file::first_unsafe_char;
use maps::zone::MAX_COORDINATE_M;

use super::csv::read_csv;
use super::error::PointFileError;
use crate::error::{MAX_EXCERPT_CHARS, excerpt, readable_value};

/// A point from the CSV.
#[derive(Debug, Clone, PartialEq)]
pub struct NamedPoint {
    /// The `name` column, or `point-<k>`.
    pub name: String,
    /// `x_m`, `y_m`: map metres.
    pub xy: [f64; 2],
}

/// Read the points CSV at `path` ([`parse_points`]).
///
/// # Errors
/// A file that cannot be read, or any error of [`parse_points`].
pub fn read_points(path: &Path) -> Result<Vec<NamedPoint>, PointFileError> {
    let text = maps::input_file::read_text_file(path).map_err(|error| PointFileError::Read {
        path: path.to_path_buf(),
        what: "points file",
        error,
    })?;
    parse_points(&text, path)
}

/// What the header row must name.
const EXPECTED_HEADER: &str = "a header row naming the columns x_m, y_m and optionally name";

/// Parse points CSV text: a header naming `x_m`, `y_m` and optionally `name` (any order, each
/// once, nothing else), then one row per point; blank lines are skipped. A row without a name
/// (or an empty one) is called `point-<k>`, `k` counting data rows from 0.
///
/// # Errors
/// One line naming the file, the line and the column at fault.
pub fn parse_points(text: &str, path: &Path) -> Result<Vec<NamedPoint>, PointFileError> {
    let file = path.display().to_string();
    let (header, rows) = read_csv(text, &file, EXPECTED_HEADER)?;
    let (header_line, header) = (header.line, header.fields);
    let at_header = format!("line {header_line}");
    // Until the header names one of the columns, the file may be anything (`/etc/shadow`, a
    // key file): say what was expected, quote nothing of it.
    if !header
        .iter()
        .any(|c| ["x_m", "y_m", "name"].contains(&c.as_str()))
    {
        let row = if header.len() == 1 {
            "a row of 1 field".to_owned()
        } else {
            format!("a row of {} fields", header.len())
        };
        return Err(PointFileError::field(
            &file,
            at_header,
            EXPECTED_HEADER,
            format!(
                "{row} that names none of them (not quoted: the file does not read as a points CSV)"
            ),
        ));
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
            return Err(PointFileError::DuplicateColumn {
                file,
                line: header_line,
                column: excerpt(column, 40),
            });
        }
    }
    if !unknown.is_empty() {
        return Err(PointFileError::UnknownColumns {
            file,
            line: header_line,
            columns: excerpt(&unknown.join(", "), MAX_EXCERPT_CHARS),
            expected: "a header row naming x_m, y_m and optionally name",
        });
    }
    let (Some(x_col), Some(y_col)) = (x_col, y_col) else {
        return Err(PointFileError::MissingColumn {
            file,
            line: header_line,
            column: if x_col.is_none() { "x_m" } else { "y_m" },
            expected: "x_m, y_m and optionally name",
        });
    };
    let mut points = Vec::new();
    let expected = format!("{} fields ({})", header.len(), header.join(","));
    for row in rows.of_width(header.len(), expected) {
        let (line, fields) = row?;
        let number = |col: usize| -> Result<f64, PointFileError> {
            let raw = &fields[col];
            match raw.parse::<f64>() {
                Ok(v) if v.is_finite() && v.abs() <= MAX_COORDINATE_M => Ok(v),
                _ => Err(PointFileError::field(
                    &file,
                    format!("line {line}, column {}", header[col]),
                    format!("a finite number of metres within ±{MAX_COORDINATE_M}"),
                    format!("{:?}", excerpt(&readable_value(raw), 40)),
                )),
            }
        };
        let xy = [number(x_col)?, number(y_col)?];
        let name = match name_col.map(|c| fields[c].clone()) {
            // Names are printed in the table: an escape sequence would drive the terminal.
            Some(name) if first_unsafe_char(&name).is_some() => {
                return Err(PointFileError::field(
                    &file,
                    format!("line {line}, column name"),
                    "text without control characters",
                    format!("\"{}\"", excerpt(&name, 40)),
                ));
            }
            Some(name) if !name.is_empty() => name,
            _ => format!("point-{}", points.len()),
        };
        points.push(NamedPoint { name, xy });
    }
    Ok(points)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Vec<NamedPoint>, PointFileError> {
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
}
