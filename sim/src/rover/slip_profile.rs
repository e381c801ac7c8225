//! Slip-versus-slope profiles per terrain class (paper 003 §4: "terrain slip profiles map slope
//! to expected rover slip for a given terrain type", with the direction of travel).
//!
//! A profile is measured by driving the rapier rover ([`crate::rover::physics::drive_on_slope`]) up,
//! down and across plane slopes of each terrain class's soil ([`crate::rover::physics::Soil::of`]):
//! [`SlipProfile::measure`]. `solsim slip-profile` runs it and writes the table (CSV) and its
//! figure; the simulator reads the bundled table ([`SlipProfile::bundled`], the output of
//! `solsim slip-profile` committed as `sim/data/slip_profile.csv`, parsed once per process), so a
//! traverse never runs rapier. `tests/slip_profile.rs` re-measures and checks the bundled table
//! is what the model gives today.
//!
//! Prediction ([`SlipProfile::predict`]) for a heading at angle ψ from the uphill direction on a
//! slope θ: the up (ψ = 0), cross (ψ = 90°) and down (ψ = 180°) profiles, each interpolated
//! linearly in θ, blended linearly in ψ between the two nearest. A slope past the last measured
//! one, or a run that could not climb (slip ≥ 1), predicts slip 1: no progress.

use std::sync::OnceLock;

use maps::TerrainClass;

use crate::rover::physics::{Heading, PhysicsError, RoverBody, Soil, drive_on_slope};

/// One measured run.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ProfileRow {
    /// Terrain class of the ground.
    pub terrain: TerrainClass,
    /// Heading relative to the slope.
    pub heading: ProfileHeading,
    /// Slope, degrees.
    pub slope_deg: f64,
    /// Measured slip, 1 − progress / commanded (negative: skid, the rover outruns its wheels).
    pub slip: f64,
    /// Chassis tilt at the end of the run, degrees.
    pub tilt_deg: f64,
    /// Sideways drift per metre commanded, metres (left positive).
    pub drift_per_m: f64,
    /// Static wheel sinkage, metres.
    pub sinkage_m: f64,
    /// The closed-form steady slip of the same soil model ([`Soil::steady_slip`]) for up and
    /// down runs; `None` across the slope or where the closed form finds no steady state.
    pub closed_form_slip: Option<f64>,
}

/// The three headings of a profile (names as in the CSV: `up`, `down`, `cross`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ProfileHeading {
    /// Straight uphill.
    Up,
    /// Straight downhill.
    Down,
    /// Along the contour.
    Cross,
}

impl ProfileHeading {
    /// All three, in table order.
    pub const ALL: [ProfileHeading; 3] = [Self::Up, Self::Cross, Self::Down];

    /// The CSV name.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Up => "up",
            Self::Down => "down",
            Self::Cross => "cross",
        }
    }

    fn physics(self) -> Heading {
        match self {
            Self::Up => Heading::UpSlope,
            Self::Down => Heading::DownSlope,
            Self::Cross => Heading::CrossSlope,
        }
    }

    fn parse(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|h| h.name() == name)
    }
}

/// How the profile runs drive (plain settings struct).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProfileSettings {
    /// Rim speed, m/s (default 0.05: MER's and MSL's top mobility speed is about 4-5 cm/s).
    pub speed_m_per_s: f64,
    /// Length of each run, seconds; slip is measured over its second half (default 20).
    pub duration_s: f64,
    /// Slope step, degrees (default 2).
    pub slope_step_deg: f64,
    /// Steepest slope measured, degrees (default 30).
    pub max_slope_deg: f64,
}

impl Default for ProfileSettings {
    fn default() -> Self {
        Self {
            speed_m_per_s: 0.05,
            duration_s: 20.0,
            slope_step_deg: 2.0,
            max_slope_deg: 30.0,
        }
    }
}

impl ProfileSettings {
    /// The slopes measured: 0, step, 2 step, … up to the maximum.
    #[must_use]
    pub fn slopes_deg(&self) -> Vec<f64> {
        let n = (self.max_slope_deg / self.slope_step_deg + 1e-9).floor() as usize;
        (0..=n).map(|k| k as f64 * self.slope_step_deg).collect()
    }
}

/// A measured (or read) slip profile: rows for every terrain class, heading and slope.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SlipProfile {
    /// The runs, by terrain class, then heading, then slope.
    pub rows: Vec<ProfileRow>,
}

/// The CSV header (one line, after the comment lines).
pub const CSV_HEADER: &str =
    "terrain,heading,slope_deg,slip,tilt_deg,drift_per_m,sinkage_m,closed_form_slip";

impl SlipProfile {
    /// Drive the rapier rover `body` on every terrain class, heading and slope of `settings`.
    /// Runs are independent and run in parallel; the table's order (and every number) does
    /// not depend on the thread count. `progress` is called after each run.
    ///
    /// # Errors
    /// [`PhysicsError`] for settings out of range.
    pub fn measure(
        body: &RoverBody,
        settings: &ProfileSettings,
        progress: &(dyn Fn() + Sync),
    ) -> Result<Self, PhysicsError> {
        use rayon::prelude::*;
        let mut cases = Vec::new();
        for terrain in TerrainClass::ALL {
            for heading in ProfileHeading::ALL {
                for slope in settings.slopes_deg() {
                    cases.push((terrain, heading, slope));
                }
            }
        }
        let mass_kg = body.mass_kg();
        let rows = cases
            .par_iter()
            .map(|&(terrain, heading, slope_deg)| {
                let soil = Soil::of(terrain);
                let d = drive_on_slope(
                    body,
                    slope_deg,
                    heading.physics(),
                    &soil,
                    settings.speed_m_per_s,
                    settings.duration_s,
                )?;
                progress();
                let signed = match heading {
                    ProfileHeading::Up => Some(slope_deg),
                    ProfileHeading::Down => Some(-slope_deg),
                    ProfileHeading::Cross => None,
                };
                Ok(ProfileRow {
                    terrain,
                    heading,
                    slope_deg,
                    slip: d.slip,
                    tilt_deg: d.tilt_deg,
                    drift_per_m: d.drift_left_m / (settings.speed_m_per_s * settings.duration_s),
                    sinkage_m: d.sinkage_m,
                    closed_form_slip: signed.and_then(|s| {
                        soil.steady_slip(mass_kg, body.wheel_radius_m, body.wheel_width_m, s)
                    }),
                })
            })
            .collect::<Result<Vec<_>, PhysicsError>>()?;
        Ok(Self { rows })
    }

    /// The bundled profile (`sim/data/slip_profile.csv`), parsed once.
    ///
    /// # Panics
    /// Never for the committed file (a unit test parses it).
    #[must_use]
    pub fn bundled() -> &'static SlipProfile {
        static BUNDLED: OnceLock<SlipProfile> = OnceLock::new();
        BUNDLED.get_or_init(|| {
            #[allow(clippy::expect_used)]
            Self::from_csv(BUNDLED_CSV).expect("the bundled slip profile parses")
        })
    }

    /// The table as CSV: `#` comment lines naming what produced it, [`CSV_HEADER`], one row
    /// per run; numbers with 4 decimals (slip, tilt) or 5 (drift, sinkage).
    #[must_use]
    pub fn to_csv(&self, comment: &str) -> String {
        let mut out = String::new();
        for line in comment.lines() {
            out.push_str("# ");
            out.push_str(line);
            out.push('\n');
        }
        out.push_str(CSV_HEADER);
        out.push('\n');
        for r in &self.rows {
            out.push_str(&format!(
                "{},{},{},{:.4},{:.4},{:.5},{:.5},{}\n",
                r.terrain.name(),
                r.heading.name(),
                r.slope_deg,
                r.slip,
                r.tilt_deg,
                r.drift_per_m,
                r.sinkage_m,
                r.closed_form_slip
                    .map_or(String::new(), |s| format!("{s:.4}")),
            ));
        }
        out
    }

    /// Parse a table written by [`SlipProfile::to_csv`].
    ///
    /// # Errors
    /// A message naming the line and the field for anything else.
    pub fn from_csv(text: &str) -> Result<Self, String> {
        let mut lines = text
            .lines()
            .enumerate()
            .filter(|(_, l)| !l.starts_with('#') && !l.trim().is_empty());
        match lines.next() {
            Some((_, h)) if h.trim() == CSV_HEADER => {}
            Some((i, _)) => {
                return Err(format!("line {}: expected the header {CSV_HEADER}", i + 1));
            }
            None => return Err("no header".to_owned()),
        }
        let mut rows = Vec::new();
        for (i, line) in lines {
            let f: Vec<&str> = line.split(',').collect();
            let at = |k: usize, name: &str| -> Result<f64, String> {
                f.get(k)
                    .and_then(|v| v.trim().parse::<f64>().ok())
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| format!("line {}: {name}: expected a finite number", i + 1))
            };
            if f.len() != 8 {
                return Err(format!(
                    "line {}: expected 8 fields, found {}",
                    i + 1,
                    f.len()
                ));
            }
            let terrain = TerrainClass::ALL
                .into_iter()
                .find(|t| t.name() == f[0])
                .ok_or_else(|| {
                    format!("line {}: terrain: expected sand, soil or bedrock", i + 1)
                })?;
            let heading = ProfileHeading::parse(f[1])
                .ok_or_else(|| format!("line {}: heading: expected up, down or cross", i + 1))?;
            rows.push(ProfileRow {
                terrain,
                heading,
                slope_deg: at(2, "slope_deg")?,
                slip: at(3, "slip")?,
                tilt_deg: at(4, "tilt_deg")?,
                drift_per_m: at(5, "drift_per_m")?,
                sinkage_m: at(6, "sinkage_m")?,
                closed_form_slip: if f[7].trim().is_empty() {
                    None
                } else {
                    Some(at(7, "closed_form_slip")?)
                },
            });
        }
        let profile = Self { rows };
        for t in TerrainClass::ALL {
            for h in ProfileHeading::ALL {
                let c = profile.curve(t, h);
                if c.is_empty() || c.windows(2).any(|w| w[1].0 <= w[0].0) || c[0].0 != 0.0 {
                    return Err(format!(
                        "{} {}: expected rows from slope 0 in increasing slope order",
                        t.name(),
                        h.name()
                    ));
                }
            }
        }
        Ok(profile)
    }

    /// (slope, slip) of one terrain class and heading, in table order.
    #[must_use]
    pub fn curve(&self, terrain: TerrainClass, heading: ProfileHeading) -> Vec<(f64, f64)> {
        self.curve_of(terrain, heading, |r| r.slip)
    }

    fn curve_of(
        &self,
        terrain: TerrainClass,
        heading: ProfileHeading,
        value: impl Fn(&ProfileRow) -> f64,
    ) -> Vec<(f64, f64)> {
        self.rows
            .iter()
            .filter(|r| r.terrain == terrain && r.heading == heading)
            .map(|r| (r.slope_deg, value(r)))
            .collect()
    }

    /// Predicted chassis tilt, degrees, blended like [`SlipProfile::predict`]; 90 past the
    /// steepest slope measured.
    #[must_use]
    pub fn predict_tilt(&self, terrain: TerrainClass, slope_deg: f64, psi_deg: f64) -> f64 {
        if slope_deg > self.max_slope_deg() {
            return 90.0;
        }
        self.blend(psi_deg, |h| {
            interpolate(&self.curve_of(terrain, h, |r| r.tilt_deg), slope_deg)
        })
    }

    /// Blend a per-heading value over the heading's angle from uphill (module docs).
    fn blend(&self, psi_deg: f64, at: impl Fn(ProfileHeading) -> f64) -> f64 {
        let psi = psi_deg.abs() % 360.0;
        let psi = if psi > 180.0 { 360.0 - psi } else { psi };
        if psi <= 90.0 {
            let w = psi / 90.0;
            (1.0 - w) * at(ProfileHeading::Up) + w * at(ProfileHeading::Cross)
        } else {
            let w = (psi - 90.0) / 90.0;
            (1.0 - w) * at(ProfileHeading::Cross) + w * at(ProfileHeading::Down)
        }
    }

    /// The steepest slope measured, degrees.
    #[must_use]
    pub fn max_slope_deg(&self) -> f64 {
        self.rows.iter().map(|r| r.slope_deg).fold(0.0, f64::max)
    }

    /// Predicted slip of a rover heading `psi_deg` from the uphill direction (0 up, 90 across,
    /// 180 down; the sign is ignored) on a `slope_deg` slope of `terrain` (module docs). Capped
    /// to at most 1 (no progress).
    #[must_use]
    pub fn predict(&self, terrain: TerrainClass, slope_deg: f64, psi_deg: f64) -> f64 {
        if slope_deg > self.max_slope_deg() {
            return 1.0;
        }
        // A run that slid away downhill (slip far below 0) is as uncontrolled as one that
        // could not climb: both count as no controlled progress.
        self.blend(psi_deg, |h| {
            let s = interpolate(&self.curve(terrain, h), slope_deg);
            if s < -1.0 { 1.0 } else { s.min(1.0) }
        })
    }
}

/// The profile resampled for the hot loops (A* move costs, every drive step): predicted slip and
/// tilt by terrain class on a grid over the slope's components along and across the direction
/// of travel, as tangents (`a = ∇z · û`, positive uphill; `c = |∇z × û|`), so a lookup needs
/// no trigonometry. The grid steps [`SlipTable::STEP`] in tangent (0.57° near level) out to
/// [`SlipTable::MAX_TAN`] (35°); a lookup takes the nearest node. Past the profile's steepest
/// slope it predicts slip 1.
#[derive(Clone, Debug, PartialEq)]
pub struct SlipTable {
    /// `[class][ia * NC + ic]`: predicted slip.
    slip: [Vec<f32>; 3],
    /// Same layout: predicted chassis tilt, degrees.
    tilt: [Vec<f32>; 3],
}

impl SlipTable {
    /// Grid step, tangent units.
    pub const STEP: f64 = 0.01;
    /// Largest tangent on the grid (tan 35° = 0.70).
    pub const MAX_TAN: f64 = 0.70;
    const NA: usize = 141; // a in −0.70 ..= 0.70
    const NC: usize = 71; // c in 0 ..= 0.70

    /// Resample `profile` ([`SlipProfile::predict`], and the tilt likewise).
    #[must_use]
    pub fn new(profile: &SlipProfile) -> Self {
        let build = |class: TerrainClass, tilt: bool| -> Vec<f32> {
            let mut v = Vec::with_capacity(Self::NA * Self::NC);
            for ia in 0..Self::NA {
                let a = (ia as f64 - 70.0) * Self::STEP;
                for ic in 0..Self::NC {
                    let c = ic as f64 * Self::STEP;
                    let slope_deg = a.hypot(c).atan().to_degrees();
                    let psi_deg = if a == 0.0 && c == 0.0 {
                        0.0
                    } else {
                        c.atan2(a).to_degrees()
                    };
                    let value = if tilt {
                        profile.predict_tilt(class, slope_deg, psi_deg)
                    } else {
                        profile.predict(class, slope_deg, psi_deg)
                    };
                    v.push(value as f32);
                }
            }
            v
        };
        let per_class = |tilt: bool| TerrainClass::ALL.map(|t| build(t, tilt));
        Self {
            slip: per_class(false),
            tilt: per_class(true),
        }
    }

    /// The table of the bundled profile, built once.
    #[must_use]
    pub fn bundled() -> &'static SlipTable {
        static TABLE: OnceLock<SlipTable> = OnceLock::new();
        TABLE.get_or_init(|| SlipTable::new(SlipProfile::bundled()))
    }

    fn index(along_tan: f32, across_tan: f32) -> Option<usize> {
        let ia = (along_tan / Self::STEP as f32).round() + 70.0;
        let ic = (across_tan.abs() / Self::STEP as f32).round();
        // NaN fails both comparisons and is treated as off the grid.
        if (0.0..=140.0).contains(&ia) && (0.0..=70.0).contains(&ic) {
            Some(ia as usize * Self::NC + ic as usize)
        } else {
            None
        }
    }

    /// Predicted slip on `class` with the slope's tangent `along_tan` along the direction of
    /// travel (positive uphill) and `across_tan` across it; 1 off the grid.
    #[must_use]
    pub fn slip(&self, class: TerrainClass, along_tan: f32, across_tan: f32) -> f32 {
        Self::index(along_tan, across_tan).map_or(1.0, |i| self.slip[class_index(class)][i])
    }

    /// Predicted chassis tilt, degrees, likewise; 90 off the grid.
    #[must_use]
    pub fn tilt_deg(&self, class: TerrainClass, along_tan: f32, across_tan: f32) -> f32 {
        Self::index(along_tan, across_tan).map_or(90.0, |i| self.tilt[class_index(class)][i])
    }
}

/// The tangents of the slope of height gradient `g` (`[∂z/∂x east, ∂z/∂y north]`) along the
/// unit map direction (`ux`, `uy`) (positive uphill) and across it: the coordinates
/// [`SlipTable`] is indexed by.
#[must_use]
pub fn along_across(g: [f32; 2], ux: f32, uy: f32) -> (f32, f32) {
    (g[0] * ux + g[1] * uy, (g[0] * uy - g[1] * ux).abs())
}

fn class_index(class: TerrainClass) -> usize {
    match class {
        TerrainClass::Sand => 0,
        TerrainClass::Soil => 1,
        TerrainClass::Bedrock => 2,
    }
}

/// The bundled table's text (`solsim slip-profile` output).
pub const BUNDLED_CSV: &str = include_str!("../../data/slip_profile.csv");

/// Linear interpolation of `(x, y)` points sorted by x, clamped at the ends.
fn interpolate(points: &[(f64, f64)], x: f64) -> f64 {
    let Some(first) = points.first() else {
        return 1.0;
    };
    if x <= first.0 {
        return first.1;
    }
    for w in points.windows(2) {
        let ((x0, y0), (x1, y1)) = (w[0], w[1]);
        if x <= x1 {
            return y0 + (y1 - y0) * (x - x0) / (x1 - x0);
        }
    }
    points.last().map_or(1.0, |p| p.1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bundled_profile_parses_and_predicts_by_heading() {
        let p = SlipProfile::bundled();
        assert_eq!(p.rows.len(), 3 * 3 * 16);
        let sand_up = p.predict(TerrainClass::Sand, 15.0, 0.0);
        let sand_down = p.predict(TerrainClass::Sand, 15.0, 180.0);
        let sand_cross = p.predict(TerrainClass::Sand, 15.0, 90.0);
        assert!(
            sand_up > sand_cross && sand_cross > sand_down,
            "{sand_up} {sand_cross} {sand_down}"
        );
        assert!(
            p.predict(TerrainClass::Sand, 15.0, 0.0) > p.predict(TerrainClass::Bedrock, 15.0, 0.0)
        );
        assert_eq!(p.predict(TerrainClass::Soil, 31.0, 90.0), 1.0);
    }

    #[test]
    fn a_broken_table_names_the_line_and_field() {
        let bad = format!("{CSV_HEADER}\nsand,up,0,x,0,0,0,\n");
        let e = SlipProfile::from_csv(&bad).expect_err("refused");
        assert!(e.contains("line 2: slip"), "{e}");
        let e = SlipProfile::from_csv("terrain\n").expect_err("refused");
        assert!(e.contains("header"), "{e}");
    }
}
