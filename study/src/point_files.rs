//! Small text files of points a user hands solsim: the points CSV of `solsim zones check`
//! ([`parse_points`]) and the tracks of `solsim route import` ([`crate::track_file`]), read in
//! one CSV dialect ([`read_csv`]) with one error type
//! ([`PointFileError`]: one line naming the file, the line, column or feature, and what was
//! expected).

mod csv;
mod error;
mod points_csv;

pub use csv::{CsvHeader, CsvRows, read_csv};
pub use error::PointFileError;
pub use points_csv::{NamedPoint, parse_points, read_points};
