//! The orbital products: a HiRISE-like 25 cm appearance image and a 1 m DEM of a truth patch.

use maps::Raster;
use rayon::prelude::*;

use super::noise::{gaussian, sub_seed};
use super::shading::{HeightField, Sun, gaussian_blur, radiance};
use super::{ORBITAL_DEM_RESOLUTION_M_PER_PX, SyntheticError, TruthPatch, check_param};

const SALT_IMAGE_NOISE: u64 = 11;
const SALT_DEM_NOISE: u64 = 12;

/// How the orbital camera and DEM see a truth patch (plain struct; defaults in `Default`).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct OrbitalParams {
    /// Direction the sunlight comes from, degrees clockwise from north, any finite value.
    /// (default: 250 — mid-afternoon, from the west-southwest, as HiRISE images Jezero)
    pub sun_azimuth_deg: f64,
    /// Sun elevation above the horizon, degrees, in (0, 90]. (default: 35)
    pub sun_elevation_deg: f64,
    /// Share of the light that reaches surfaces facing away from the sun or in shadow (sky and
    /// scatter), 0..1. (default: 0.2)
    pub ambient: f64,
    /// Radiance (albedo × irradiance, 0..1) that maps to 255 before the gamma. (default: 0.35)
    pub white_level: f64,
    /// Standard deviation of the Gaussian point-spread function, pixels, 0..~3; 0.7 px gives a
    /// HiRISE-like MTF at 25 cm. (default: 0.7)
    pub blur_sigma_px: f64,
    /// Standard deviation of the additive sensor noise, linear DN (0..255 scale), ≥ 0.
    /// (default: 2.0)
    pub noise_sigma_dn: f64,
    /// Exponent of the monotonic response `255 × (v / 255)^gamma`, > 0. (default: 0.8)
    pub gamma: f64,
    /// Standard deviation of the white noise added to each 1 m DEM cell, metres, ≥ 0.
    /// (default: 0.05)
    pub dem_noise_sigma_m: f64,
}

impl Default for OrbitalParams {
    fn default() -> Self {
        Self {
            sun_azimuth_deg: 250.0,
            sun_elevation_deg: 35.0,
            ambient: 0.2,
            white_level: 0.35,
            blur_sigma_px: 0.7,
            noise_sigma_dn: 2.0,
            gamma: 0.8,
            dem_noise_sigma_m: 0.05,
        }
    }
}

impl OrbitalParams {
    /// Checks every field against the range its documentation gives.
    ///
    /// # Errors
    /// [`SyntheticError::InvalidParameter`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), SyntheticError> {
        check_param("sun_azimuth_deg", self.sun_azimuth_deg, "finite", |v| {
            v.is_finite()
        })?;
        check_param(
            "sun_elevation_deg",
            self.sun_elevation_deg,
            "in (0, 90]",
            |v| v > 0.0 && v <= 90.0,
        )?;
        check_param("ambient", self.ambient, "in [0, 1]", |v| {
            (0.0..=1.0).contains(&v)
        })?;
        check_param("white_level", self.white_level, "positive, finite", |v| {
            v > 0.0 && v.is_finite()
        })?;
        check_param("blur_sigma_px", self.blur_sigma_px, "in [0, 10]", |v| {
            (0.0..=10.0).contains(&v)
        })?;
        check_param(
            "noise_sigma_dn",
            self.noise_sigma_dn,
            "≥ 0, finite",
            |v| v >= 0.0 && v.is_finite(),
        )?;
        check_param("gamma", self.gamma, "positive, finite", |v| {
            v > 0.0 && v.is_finite()
        })?;
        check_param(
            "dem_noise_sigma_m",
            self.dem_noise_sigma_m,
            "≥ 0, finite",
            |v| v >= 0.0 && v.is_finite(),
        )
    }
}

/// The orbital map of a truth patch, as the rover carries it (paper 000 §5, Fig. 14).
#[derive(Clone, Debug, PartialEq)]
pub struct OrbitalProducts {
    /// 8-bit appearance image on the truth grid (25 cm pixels).
    pub appearance: Raster<u8>,
    /// Heights in metres on a 1 m grid with the same north-west corner: the mean of each
    /// 4 × 4 block of truth pixels plus noise (a partial block at the east or south edge is
    /// dropped).
    pub dem: Raster<f32>,
}

/// Renders the orbital appearance image and DEM of `patch`, deterministically.
///
/// The image is Lambertian shading under the orbital sun with cast shadows (a march towards the
/// sun over the truth heights) times the albedo, blurred by a Gaussian PSF, plus Gaussian sensor
/// noise, through the monotonic response `255 × (v / 255)^gamma` (clamped to 0..=255), rounded
/// to u8. Shadows cast
/// by terrain outside the patch are missing, so keep the region of interest a few shadow
/// lengths from the patch edge. The DEM is the block mean of the truth heights over
/// [`ORBITAL_DEM_RESOLUTION_M_PER_PX`] cells plus white noise.
///
/// # Errors
/// [`SyntheticError::InvalidParameter`] if `p` fails [`OrbitalParams::validate`] or the patch's
/// pixel size is not positive; [`SyntheticError::MalformedPatch`] if its rasters disagree.
pub fn render_orbital(
    patch: &TruthPatch,
    p: &OrbitalParams,
    seed: u64,
) -> Result<OrbitalProducts, SyntheticError> {
    p.validate()?;
    patch.check()?;
    let hf = HeightField::new(&patch.height_m);
    let (w, h) = (hf.width, hf.height);
    let geo = patch.height_m.geo;
    let sun = Sun::new(p.sun_azimuth_deg, p.sun_elevation_deg, hf.resolution_m);
    let scale = 255.0 / p.white_level;
    let mut linear = vec![0.0f32; w * h];
    linear
        .par_chunks_mut(w.max(1))
        .enumerate()
        .for_each(|(row, out)| {
            for (col, v) in out.iter_mut().enumerate() {
                let cos = hf.cos_incidence(col, row, sun.dir);
                let lit = cos > 0.0 && hf.sunlit(col, row, &sun);
                let albedo = patch.albedo.data[row * w + col];
                *v = (scale * radiance(albedo, cos, lit, p.ambient)) as f32;
            }
        });
    let blurred = gaussian_blur(&linear, w, h, p.blur_sigma_px);
    let noise_seed = sub_seed(seed, SALT_IMAGE_NOISE);
    // round(255 × (v / 255)^gamma) steps from k − 1 to k where v crosses thresholds[k − 1]:
    // 255 powers once instead of one per pixel.
    let thresholds: Vec<f64> = (1..=255)
        .map(|k| 255.0 * ((f64::from(k) - 0.5) / 255.0).powf(1.0 / p.gamma))
        .collect();
    let appearance: Vec<u8> = blurred
        .par_iter()
        .enumerate()
        .map(|(i, &v)| {
            let (col, row) = ((i % w) as i64, (i / w) as i64);
            let noisy = f64::from(v) + p.noise_sigma_dn * gaussian(noise_seed, col, row);
            // At most 255 thresholds lie below, so the count fits a u8.
            thresholds.partition_point(|&t| t <= noisy) as u8
        })
        .collect();

    let block = ((ORBITAL_DEM_RESOLUTION_M_PER_PX / hf.resolution_m).round() as usize).max(1);
    let (dw, dh) = (w / block, h / block);
    let dem_seed = sub_seed(seed, SALT_DEM_NOISE);
    let dem: Vec<f32> = (0..dw * dh)
        .map(|i| {
            let (bc, br) = (i % dw, i / dw);
            let mut sum = 0.0f64;
            for row in br * block..(br + 1) * block {
                for col in bc * block..(bc + 1) * block {
                    sum += f64::from(hf.at(col, row));
                }
            }
            let mean = sum / (block * block) as f64;
            (mean + p.dem_noise_sigma_m * gaussian(dem_seed, bc as i64, br as i64)) as f32
        })
        .collect();

    Ok(OrbitalProducts {
        appearance: Raster {
            width: w,
            height: h,
            geo,
            data: appearance,
        },
        dem: Raster {
            width: dw,
            height: dh,
            geo: geo.scaled(block as f64),
            data: dem,
        },
    })
}
