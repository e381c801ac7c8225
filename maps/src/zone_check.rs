//! Points checked against a [`ZoneSet`] (`solsim zones check`): how far each is from the
//! keep-out zones and the edge of the keep-in area, the largest position uncertainty it
//! tolerates, and where it is — as a table or as JSON:
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
//!   the rover's footprint stays clear of every keep-out and inside the keep-in area. Negative
//!   means it is already touching a forbidden area there; it is not a depth: inside a keep-out
//!   (or outside the keep-in area) the distance is 0, so the number is minus the footprint radius
//!   however deep the point lies.
//! - `status`: where the point is — `clear`, `footprint touches a zone` (outside every zone, but
//!   nearer one than the footprint radius), `inside keep-out (NAME, …)` (edges count as
//!   inside), `outside keep-in`, or both of the last two.
//!
//! Under the table one line says the sign convention ([`SIGN_CONVENTION`]). The JSON
//! ([`PointCheck`]'s serialization) is an object per point with those keys (infinite values as
//! `null`, full precision) and the flags `inside_keep_out` and `outside_keep_in`.
//! `peers/zones_reference.py` prints the same numbers computed with shapely.

use crate::input_file::printable;
use crate::zone::ZoneSet;

/// Column names, in output order.
pub const COLUMNS: [&str; 7] = [
    "name",
    "x_m",
    "y_m",
    "keep_out_distance_m",
    "keep_in_edge_distance_m",
    "max_uncertainty_m",
    "status",
];

/// The line under the table: what the sign of `max_uncertainty_m` means.
pub const SIGN_CONVENTION: &str = "max_uncertainty_m = min(keep_out_distance_m, \
     keep_in_edge_distance_m) − footprint radius: the largest position error at which the point \
     stays drivable; negative = not drivable at any error, and not a depth (inside a zone the \
     distance is 0, so it is minus the footprint radius): status says where the point is";

/// One point checked against the zones.
#[derive(Clone, Debug, PartialEq)]
pub struct PointCheck<'a> {
    /// The point's name.
    pub name: &'a str,
    /// Map metres, east.
    pub x_m: f64,
    /// Map metres, north.
    pub y_m: f64,
    /// Distance to the nearest keep-out zone, metres (0 inside one; `∞` without keep-outs).
    pub keep_out_distance_m: f64,
    /// Distance to the edge of the keep-in union from inside it, metres (0 outside; `∞`
    /// without keep-ins).
    pub keep_in_edge_distance_m: f64,
    /// min(the two) − footprint radius, metres.
    pub max_uncertainty_m: f64,
    /// The keep-out zones the point lies in (edges included), by name; empty when outside.
    pub inside_keep_outs: Vec<String>,
    /// The point lies outside the keep-in area (never, without keep-in zones).
    pub outside_keep_in: bool,
}

impl ZoneSet {
    /// Checks named points (map metres) for a rover of footprint radius `footprint_radius_m`.
    #[must_use]
    pub fn check_points<'a>(
        &self,
        points: &[(&'a str, [f64; 2])],
        footprint_radius_m: f64,
    ) -> Vec<PointCheck<'a>> {
        let xy: Vec<[f64; 2]> = points.iter().map(|p| p.1).collect();
        let clearances = self.clearances(&xy, footprint_radius_m);
        points
            .iter()
            .zip(&clearances)
            .map(|(&(name, p), c)| {
                // The zone names only for a point inside one: the index answers the question
                // for every other point.
                let keep_outs: Vec<String> = if self.in_keep_out(p) {
                    self.keep_outs()
                        .filter(|(_, z)| z.covers(p))
                        .map(|(_, z)| z.name().to_string())
                        .collect()
                } else {
                    Vec::new()
                };
                PointCheck {
                    name,
                    x_m: p[0],
                    y_m: p[1],
                    keep_out_distance_m: c.keep_out_distance_m,
                    keep_in_edge_distance_m: c.keep_in_edge_distance_m,
                    max_uncertainty_m: c.max_uncertainty_m,
                    inside_keep_outs: keep_outs,
                    outside_keep_in: !self.in_keep_in(p),
                }
            })
            .collect()
    }
}

impl PointCheck<'_> {
    /// Where the point is: `clear`, `footprint touches a zone`, `inside keep-out (NAME, …)`,
    /// `outside keep-in`, or both of the last two.
    #[must_use]
    pub fn status(&self) -> String {
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

/// Keyed like the table's columns (in that order), infinite distances as `null`, and the flags
/// `inside_keep_out` and `outside_keep_in`.
impl serde::Serialize for PointCheck<'_> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
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
        JsonRow {
            name: self.name,
            x_m: self.x_m,
            y_m: self.y_m,
            keep_out_distance_m: finite(self.keep_out_distance_m),
            keep_in_edge_distance_m: finite(self.keep_in_edge_distance_m),
            max_uncertainty_m: finite(self.max_uncertainty_m),
            status: self.status(),
            inside_keep_out: !self.inside_keep_outs.is_empty(),
            outside_keep_in: self.outside_keep_in,
        }
        .serialize(serializer)
    }
}

/// Fixed-width table: names left-aligned, numbers right-aligned with 3 decimals (`inf` when
/// there are no zones of that kind), columns separated by two spaces, then
/// [`SIGN_CONVENTION`].
#[must_use]
pub fn table(rows: &[PointCheck<'_>]) -> String {
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
    let mut out = format!("{}\n", line(COLUMNS));
    for row in &cells {
        out.push_str(&line(row.each_ref().map(String::as_str)));
        out.push('\n');
    }
    out.push_str(SIGN_CONVENTION);
    out.push('\n');
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_and_json() {
        let rows = [
            PointCheck {
                name: "p",
                x_m: 1.0,
                y_m: -2.5,
                keep_out_distance_m: f64::INFINITY,
                keep_in_edge_distance_m: 3.25,
                max_uncertainty_m: 3.0,
                inside_keep_outs: Vec::new(),
                outside_keep_in: false,
            },
            PointCheck {
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
        assert_eq!(
            table(&rows),
            format!(
                "name    x_m     y_m  keep_out_distance_m  keep_in_edge_distance_m  max_uncertainty_m  status\n\
                 p     1.000  -2.500                  inf                    3.250              3.000  clear\n\
                 q     4.000   5.000                0.000                    0.000             -1.650  inside keep-out (rock), outside keep-in\n\
                 {SIGN_CONVENTION}\n"
            )
        );
        let text = serde_json::to_string_pretty(&rows).expect("json");
        let keys: Vec<usize> = COLUMNS
            .iter()
            .map(|k| text.find(&format!("\"{k}\"")).unwrap_or(usize::MAX))
            .collect();
        assert!(
            keys.windows(2).all(|w| w[0] < w[1]),
            "keys in column order: {text}"
        );
        let v: serde_json::Value = serde_json::from_str(&text).expect("json");
        assert_eq!(v[0]["keep_out_distance_m"], serde_json::Value::Null);
        assert_eq!(v[0]["keep_in_edge_distance_m"], 3.25);
        assert_eq!(v[0]["name"], "p");
        assert_eq!(v[0]["status"], "clear");
        assert_eq!(v[0]["inside_keep_out"], false);
        assert_eq!(v[1]["inside_keep_out"], true);
        assert_eq!(v[1]["outside_keep_in"], true);
    }
}
