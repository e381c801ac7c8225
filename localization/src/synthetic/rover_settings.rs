//! [`RoverImagingSettings`]: how the rover's mast cameras image the terrain, with validation.

use super::{SyntheticError, check_param};

/// How the rover's mast cameras image the terrain after a drive (plain struct; defaults in
/// `Default`). Ranges `[lo, hi]` are drawn uniformly per observation from the seed.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RoverImagingSettings {
    /// Stereo wedges in the panorama, 1..=12; Perseverance takes 5, sometimes 3 or 4 (paper 000
    /// §4). They are spaced evenly in azimuth from a seeded start. (default: 4)
    pub wedge_count: usize,
    /// Horizontal field of view of one wedge, degrees, in (0, 360]; with 3 wedges of 96° there
    /// are 24° gaps with no data. (default: 96 — the NavCam field of view)
    pub wedge_width_deg: f64,
    /// Camera height above the ground under the rover, metres, > 0. (default: 2.0)
    pub mast_height_m: f64,
    /// Pixels closer than this to the rover are masked: the rover body and the blind zone
    /// below the mast, metres, ≥ 0. (default: 1.5)
    pub min_range_m: f64,
    /// Pixels farther than this are not mapped (stereo too coarse), metres, > `min_range_m`.
    /// (default: 30)
    pub max_range_m: f64,
    /// Range of the sun azimuth, degrees clockwise from north (direction the light comes
    /// from). (default: [240, 300] — late afternoon)
    pub sun_azimuth_range_deg: [f64; 2],
    /// Range of the sun elevation, degrees, within (0, 90]. (default: [12, 30] — late
    /// afternoon, lower than the orbital mid-afternoon sun, so shadows are longer)
    pub sun_elevation_range_deg: [f64; 2],
    /// Share of the light reaching surfaces facing away from the sun or in shadow, 0..1.
    /// (default: 0.2)
    pub ambient: f64,
    /// Radiance (albedo × irradiance) that maps to 255 at gain 1, offset 0, > 0.
    /// (default: 0.25)
    pub white_level: f64,
    /// Range of the per-wedge gain, > 0. (default: [0.75, 1.25])
    pub gain_range: [f64; 2],
    /// Range of the per-wedge offset, DN. (default: [-15, 15])
    pub offset_range_dn: [f64; 2],
    /// Range of the per-wedge response exponent, > 0: each wedge maps radiance `L` to
    /// `offset + gain × 255 × (L / white_level)^gamma`, a different monotonic function per wedge
    /// (paper 000 Fig. 13). (default: [0.75, 1.35])
    pub gamma_range: [f64; 2],
    /// Standard deviation of the additive sensor noise, DN, ≥ 0. (default: 2.0)
    pub noise_sigma_dn: f64,
    /// Angle one camera pixel subtends, milliradians, ≥ 0. Seen from the mast at range `r`, a
    /// pixel covers about `r² × ifov / mast_height_m` of ground along the line of sight, which
    /// blurs the orthomosaic radially at long range. (default: 0.8)
    pub pixel_ifov_mrad: f64,
    /// Standard deviation of the stereo range error at 10 m, metres, ≥ 0; it grows with the
    /// square of the range (0.45 m at 30 m by default) and shifts ortho pixels along the line of
    /// sight, smoothly over ~0.75 m. (default: 0.05)
    pub range_sigma_m_at_10m: f64,
    /// Standard deviation of the stereo height error at 10 m, metres, ≥ 0; it grows with the
    /// square of the range (0.18 m at 30 m by default). (default: 0.02)
    pub height_sigma_m_at_10m: f64,
    /// Share of the ground at `max_range_m` where stereo matching fails (grazing view, weak
    /// texture), 0..1; it falls off with range² and leaves blotchy holes up to ~1 m across.
    /// (default: 0.3)
    pub stereo_dropout_at_max_range: f64,
    /// Valid 25 cm samples a 1 m rover DEM cell needs (of 16) to be valid, 1..=16. (default: 4)
    pub dem_min_samples: usize,
    /// Standard deviation of the heading (attitude) error of the mosaic, degrees, 0..10: the
    /// whole orthomosaic is rotated about the rover by a seeded Gaussian angle. The matcher
    /// assumes an accurate orientation from SunFind (paper 000 §5); sun-sensor and IMU
    /// heading knowledge is good to a fraction of a degree to ~1° (judgement). (default: 0.5)
    pub heading_sigma_deg: f64,
    /// Standard deviation of the relative scale error of the mosaic, 0..0.1: mast height,
    /// stereo baseline and camera calibration errors make the rover map ground `r` m away at
    /// `r × (1 + ε)`. (default: 0.003 — judgement, 9 cm at 30 m)
    pub scale_sigma: f64,
    /// Standard deviation of the offset between the rover's true position and the centre of
    /// its own mosaic frame, metres per axis, 0..1 (the mosaic is built about the rover
    /// navigation frame origin, whose position relative to the cameras is known to a few cm;
    /// localization error can be no better). (default: 0.03 — judgement)
    pub mosaic_offset_sigma_m: f64,
}

impl Default for RoverImagingSettings {
    fn default() -> Self {
        Self {
            wedge_count: 4,
            wedge_width_deg: 96.0,
            mast_height_m: 2.0,
            min_range_m: 1.5,
            max_range_m: 30.0,
            sun_azimuth_range_deg: [240.0, 300.0],
            sun_elevation_range_deg: [12.0, 30.0],
            ambient: 0.2,
            white_level: 0.25,
            gain_range: [0.75, 1.25],
            offset_range_dn: [-15.0, 15.0],
            gamma_range: [0.75, 1.35],
            noise_sigma_dn: 2.0,
            pixel_ifov_mrad: 0.8,
            range_sigma_m_at_10m: 0.05,
            height_sigma_m_at_10m: 0.02,
            stereo_dropout_at_max_range: 0.3,
            dem_min_samples: 4,
            heading_sigma_deg: 0.5,
            scale_sigma: 0.003,
            mosaic_offset_sigma_m: 0.03,
        }
    }
}

impl RoverImagingSettings {
    /// Checks every field against the range its documentation gives.
    ///
    /// # Errors
    /// [`SyntheticError::InvalidParameter`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), SyntheticError> {
        let finite_nonneg = |v: f64| v >= 0.0 && v.is_finite();
        let finite_pos = |v: f64| v > 0.0 && v.is_finite();
        check_param("wedge_count", self.wedge_count as f64, "in 1..=12", |v| {
            (1.0..=12.0).contains(&v)
        })?;
        check_param(
            "wedge_width_deg",
            self.wedge_width_deg,
            "in (0, 360]",
            |v| v > 0.0 && v <= 360.0,
        )?;
        check_param(
            "mast_height_m",
            self.mast_height_m,
            "> 0, finite",
            finite_pos,
        )?;
        check_param(
            "min_range_m",
            self.min_range_m,
            "≥ 0, finite",
            finite_nonneg,
        )?;
        check_param(
            "max_range_m",
            self.max_range_m,
            "> min_range_m, finite",
            |v| v > self.min_range_m && v.is_finite(),
        )?;
        check_range(
            "sun_azimuth_range_deg",
            self.sun_azimuth_range_deg,
            "finite",
            |v| v.is_finite(),
        )?;
        check_range(
            "sun_elevation_range_deg",
            self.sun_elevation_range_deg,
            "in (0, 90]",
            |v| v > 0.0 && v <= 90.0,
        )?;
        check_param("ambient", self.ambient, "in [0, 1]", |v| {
            (0.0..=1.0).contains(&v)
        })?;
        check_param("white_level", self.white_level, "> 0, finite", finite_pos)?;
        check_range("gain_range", self.gain_range, "> 0, finite", finite_pos)?;
        check_range("offset_range_dn", self.offset_range_dn, "finite", |v| {
            v.is_finite()
        })?;
        check_range("gamma_range", self.gamma_range, "> 0, finite", finite_pos)?;
        check_param(
            "noise_sigma_dn",
            self.noise_sigma_dn,
            "≥ 0, finite",
            finite_nonneg,
        )?;
        check_param(
            "pixel_ifov_mrad",
            self.pixel_ifov_mrad,
            "≥ 0, finite",
            finite_nonneg,
        )?;
        check_param(
            "range_sigma_m_at_10m",
            self.range_sigma_m_at_10m,
            "≥ 0, finite",
            finite_nonneg,
        )?;
        check_param(
            "height_sigma_m_at_10m",
            self.height_sigma_m_at_10m,
            "≥ 0, finite",
            finite_nonneg,
        )?;
        check_param(
            "stereo_dropout_at_max_range",
            self.stereo_dropout_at_max_range,
            "in [0, 1]",
            |v| (0.0..=1.0).contains(&v),
        )?;
        check_param(
            "dem_min_samples",
            self.dem_min_samples as f64,
            "in 1..=16",
            |v| (1.0..=16.0).contains(&v),
        )?;
        check_param(
            "heading_sigma_deg",
            self.heading_sigma_deg,
            "in [0, 10]",
            |v| (0.0..=10.0).contains(&v),
        )?;
        check_param("scale_sigma", self.scale_sigma, "in [0, 0.1]", |v| {
            (0.0..=0.1).contains(&v)
        })?;
        check_param(
            "mosaic_offset_sigma_m",
            self.mosaic_offset_sigma_m,
            "in [0, 1]",
            |v| (0.0..=1.0).contains(&v),
        )
    }
}

/// Checks both ends of a `[lo, hi]` range field and that `lo <= hi`.
fn check_range(
    field: &'static str,
    range: [f64; 2],
    expected: &'static str,
    ok: impl Fn(f64) -> bool,
) -> Result<(), SyntheticError> {
    check_param(field, range[0], expected, &ok)?;
    check_param(field, range[1], expected, &ok)?;
    check_param(field, range[1], "an upper end ≥ the lower end", |v| {
        v >= range[0]
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_bad_values_are_named() {
        assert!(RoverImagingSettings::default().validate().is_ok());
        let bad = RoverImagingSettings {
            gamma_range: [1.2, 0.9],
            ..RoverImagingSettings::default()
        };
        assert!(matches!(
            bad.validate(),
            Err(SyntheticError::InvalidParameter {
                field: "gamma_range",
                ..
            })
        ));
        let bad = RoverImagingSettings {
            max_range_m: 1.0,
            ..RoverImagingSettings::default()
        };
        assert!(bad.validate().is_err());
    }
}
