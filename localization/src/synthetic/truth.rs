//! The truth terrain patch: a 0.25 m grid of heights and albedos around a point of a map.

use maps::{GeoTransform, MapLayers, Raster, TerrainClass};
use rayon::prelude::*;

#[cfg(test)]
use super::noise::value;
use super::noise::{CachedValue, SplitMix, ValueFbm, floor_i64, gaussian, hash2, sub_seed};
use super::statics::PatchStatics;
use super::{ORBITAL_DEM_RESOLUTION_M_PER_PX, SyntheticError, TRUTH_RESOLUTION_M_PER_PX};

/// Truth pixels per orbital DEM block along each axis (1 m / 0.25 m).
const BLOCK_PX: usize = 4;
/// Side of the square cells rocks are drawn in, metres. Rocks are a pure function of
/// (seed, cell), so two overlapping patches share their rocks.
const ROCK_CELL_M: f64 = 2.0;
/// Rock diameters, metres: a truncated power law N(>D) ∝ D^(−ROCK_SIZE_EXPONENT).
const ROCK_DIAMETER_M: (f64, f64) = (0.1, 1.5);
/// Exponent of the cumulative rock size–frequency law (more small rocks than large).
const ROCK_SIZE_EXPONENT: f64 = 1.8;
/// Rock height as a fraction of its diameter.
const ROCK_HEIGHT_RATIO: (f64, f64) = (0.3, 0.8);
/// Rock albedo (a little darker than bedrock, brighter than sand).
const ROCK_ALBEDO: (f64, f64) = (0.19, 0.27);
/// Wavelength of the fine height detail, metres.
const DETAIL_WAVELENGTH_M: f64 = 3.0;
/// Wavelength of the albedo texture, metres.
const TEXTURE_WAVELENGTH_M: f64 = 2.0;

/// Mean crest-to-crest spacing of the aeolian ripples on loose sand, metres. Large
/// (decimetre-high) ripples on Martian sand have 1–5 m spacing (Lapotre et al., Science 353,
/// 2016); 3 m is a judgement in that range. The trains of [`RIPPLE_TRAINS`] vary about it.
pub(super) const RIPPLE_WAVELENGTH_M: f64 = 3.0;
/// Half the crest-to-trough height of the ripples, metres (judgement: 10 cm crest to trough).
pub(super) const RIPPLE_AMPLITUDE_M: f64 = 0.05;
/// The ripple trains on loose sand: (crest azimuth, degrees clockwise from north; mean crest
/// spacing, metres). Martian sand carries ripples of several orientations and spacings at
/// once — a dominant train set by the prevailing wind, others left by seasonal winds from other
/// quarters, oblique to it — and in the Jezero bedform fields the rover drove near (Séítah, the
/// Kerrlaguna and Honeyguide megaripple fields, NASA Perseverance mission updates 2021–2025)
/// their crests are wavy and bifurcating, not parallel lines (large Martian ripples: Lapotre et al., Science 353,
/// 2016). The three trains, 40° apart with
/// 2.4–3.7 m spacing, are a judgement. Each train dominates its own patches of
/// [`RIPPLE_REGION_M`] and they blend at the patch borders, where crests of different spacing
/// meet, end and fork (Y-junctions).
const RIPPLE_TRAINS: [(f64, f64); 3] = [(20.0, RIPPLE_WAVELENGTH_M), (60.0, 2.4), (-20.0, 3.7)];
/// Size of the patches in which one ripple train dominates, metres (the wavelength of the
/// value noise that weights the trains; judgement: a few tens of crests).
const RIPPLE_REGION_M: f64 = 25.0;
/// Contrast of the train weights (`exp(k × noise)`): 3 lets one train dominate most places and
/// leaves transition zones a few metres wide (judgement).
const RIPPLE_REGION_SHARPNESS: f64 = 3.0;
/// Wavelength of the smooth phase warp that makes the crests wavy and the local spacing vary
/// by about ±30 % (2–4 m for the 3 m train), metres (judgement).
const RIPPLE_WARP_WAVELENGTH_M: f64 = 10.0;
/// Standard deviation of that phase warp, in ripple wavelengths (judgement).
const RIPPLE_WARP_CYCLES: f64 = 0.45;
/// Seed of the ripple pattern. The pattern is a fixed function of map position (not of the
/// case seed), so the orbital renderer can move it between epochs from the position alone.
const RIPPLE_SEED: u64 = 0x51D5_7A4D_2026_0003;
/// Standard deviation of [`value`] noise (see `noise.rs`).
const VALUE_SD: f64 = 0.75;

/// Height of the ripple field (before the loose-sand weight) at map point `(x, y)` after the
/// ripples migrated `migration_m` downwind (each train perpendicular to its crests), metres.
///
/// Each train of [`RIPPLE_TRAINS`] is a sinusoid whose phase is warped by smooth noise (wavy
/// crests, varying spacing); the trains are weighted by `exp(k × noise)` patches and summed,
/// normalised by the root of the summed squared weights so the height spread is that of one
/// train (±[`RIPPLE_AMPLITUDE_M`]) wherever one dominates. Migration translates each train's
/// pattern (warp included) along its own across-crest direction; the patch weights stay put.
/// The reference [`RippleField`] is tested against.
#[cfg(test)]
pub(super) fn ripple_height_m(x: f64, y: f64, migration_m: f64) -> f64 {
    let (mut acc, mut norm) = (0.0, 0.0);
    for (k, &(azimuth_deg, wavelength_m)) in RIPPLE_TRAINS.iter().enumerate() {
        let k = k as u64;
        let weight = (RIPPLE_REGION_SHARPNESS
            * value(
                sub_seed(RIPPLE_SEED, 2 * k),
                x / RIPPLE_REGION_M,
                y / RIPPLE_REGION_M,
            ))
        .exp();
        // Unit vector across the crests: the crest direction turned 90° clockwise.
        let across = (azimuth_deg + 90.0).to_radians();
        let (ax, ay) = (across.sin(), across.cos());
        let (xm, ym) = (x - migration_m * ax, y - migration_m * ay);
        let warp = RIPPLE_WARP_CYCLES / VALUE_SD
            * value(
                sub_seed(RIPPLE_SEED, 2 * k + 1),
                xm / RIPPLE_WARP_WAVELENGTH_M,
                ym / RIPPLE_WARP_WAVELENGTH_M,
            );
        let phase = (xm * ax + ym * ay) / wavelength_m + warp;
        acc += weight * (std::f64::consts::TAU * phase).sin();
        norm += weight * weight;
    }
    RIPPLE_AMPLITUDE_M * acc / norm.sqrt()
}

/// The ripple field of [`ripple_height_m`] with its constants worked out once and its value
/// noises cached ([`CachedValue`]): bit-identical to [`ripple_height_m`], several times faster
/// along a row of pixels. The train weights do not move with migration, so they are computed
/// once per point ([`RippleField::weights`]) and shared by the heights at both epochs.
#[derive(Clone, Debug)]
pub(super) struct RippleField {
    trains: [RippleTrain; RIPPLE_TRAINS.len()],
}

/// One train of [`RIPPLE_TRAINS`]: its unit vector across the crests, its spacing, and the
/// noises of its weight and of its phase warp.
#[derive(Clone, Debug)]
struct RippleTrain {
    across: (f64, f64),
    wavelength_m: f64,
    weight: CachedValue,
    warp: CachedValue,
}

impl RippleField {
    /// The field (a fixed function of map position).
    pub(super) fn new() -> Self {
        Self {
            trains: std::array::from_fn(|k| {
                let (azimuth_deg, wavelength_m) = RIPPLE_TRAINS[k];
                let k = k as u64;
                // Unit vector across the crests: the crest direction turned 90° clockwise.
                let across = (azimuth_deg + 90.0).to_radians();
                RippleTrain {
                    across: (across.sin(), across.cos()),
                    wavelength_m,
                    weight: CachedValue::new(sub_seed(RIPPLE_SEED, 2 * k)),
                    warp: CachedValue::new(sub_seed(RIPPLE_SEED, 2 * k + 1)),
                }
            }),
        }
    }

    /// The weight of each train at map point `(x, y)`.
    #[inline]
    pub(super) fn weights(&mut self, x: f64, y: f64) -> [f64; RIPPLE_TRAINS.len()] {
        let mut out = [0.0; RIPPLE_TRAINS.len()];
        for (w, t) in out.iter_mut().zip(&mut self.trains) {
            *w = (RIPPLE_REGION_SHARPNESS * t.weight.at(x / RIPPLE_REGION_M, y / RIPPLE_REGION_M))
                .exp();
        }
        out
    }

    /// [`ripple_height_m`]`(x, y, migration_m)`, given the [`RippleField::weights`] at `(x, y)`.
    #[inline]
    pub(super) fn height_m(
        &mut self,
        x: f64,
        y: f64,
        migration_m: f64,
        weights: &[f64; RIPPLE_TRAINS.len()],
    ) -> f64 {
        let (mut acc, mut norm) = (0.0, 0.0);
        for (t, &weight) in self.trains.iter_mut().zip(weights) {
            let (ax, ay) = t.across;
            let (xm, ym) = (x - migration_m * ax, y - migration_m * ay);
            let warp = RIPPLE_WARP_CYCLES / VALUE_SD
                * t.warp
                    .at(xm / RIPPLE_WARP_WAVELENGTH_M, ym / RIPPLE_WARP_WAVELENGTH_M);
            let phase = (xm * ax + ym * ay) / t.wavelength_m + warp;
            acc += weight * (std::f64::consts::TAU * phase).sin();
            norm += weight * weight;
        }
        RIPPLE_AMPLITUDE_M * acc / norm.sqrt()
    }
}

/// Radius of the ring of map-DEM samples whose mean is the local mean height that tells a
/// bedform trough (interdune) from a crest, metres: about half the 20 m spacing of the
/// benchmark's large bedforms (judgement).
const INTERDUNE_RING_M: f64 = 8.0;
/// Depth below the local mean over which a sand pixel turns from loose sand to an armoured
/// interdune, metres (judgement, against the 1–2 m relief of the large bedforms).
const INTERDUNE_DEPTH_M: f64 = 0.5;
/// Wavelength of the noise that makes the interdune armour patchy, metres (judgement).
const INTERDUNE_NOISE_M: f64 = 14.0;
/// Weight of that noise against the trough depth (in units of [`INTERDUNE_DEPTH_M`]).
const INTERDUNE_NOISE_WEIGHT: f64 = 0.8;
/// Threshold of the armour index (trough depth + noise) and the width of its soft edge:
/// chosen so about 55–65 % of the benchmark dune map stays loose sand (judgement).
const INTERDUNE_THRESHOLD: (f64, f64) = (1.1, 0.8);
/// Wavelength of the noise that picks bedrock exposures inside the armoured interdunes, metres.
const BEDROCK_EXPOSURE_NOISE_M: f64 = 9.0;
/// Noise level (unit-variance units) above which an armoured interdune shows bedrock, and the
/// width of the soft edge: about a quarter of the armoured area (judgement; Séítah's
/// megaripples lie between olivine-rich bedrock outcrops).
const BEDROCK_EXPOSURE_THRESHOLD: (f64, f64) = (0.9, 0.6);

/// How a pixel of the sand class is covered: shares of loose (rippled, mobile) sand, coarse
/// granule-and-pebble lag, and bedrock, summing to 1.
#[derive(Clone, Copy, Debug, PartialEq)]
struct SandCover {
    loose: f64,
    coarse: f64,
    bedrock: f64,
}

#[inline]
fn smoothstep01(t: f64) -> f64 {
    let t = t.clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The cover of a sand-class pixel at map point `(x, y)` whose map-DEM height is `ground_m`.
///
/// Martian dune and megaripple fields are not wall-to-wall sand: the mobile sand sits on the
/// bedform bodies, and the interdune corridors are deflated, armoured by coarse granules and
/// pebbles with scattered rocks, with bedrock showing through in places — the megaripples
/// Perseverance studied at Kerrlaguna and Hazyview are crusted and coarse-grained, about 1 m
/// tall, between rocky ground (NASA Perseverance mission updates, 2025; Séítah's bedforms lie
/// between olivine-cumulate outcrops, Farley et al., Science 377, 2022). Here the armour index
/// is the depth of the pixel below the mean map height on a ring of [`INTERDUNE_RING_M`]
/// (troughs) in units of [`INTERDUNE_DEPTH_M`], plus patchy noise; it turns loose sand into
/// coarse lag over a soft threshold, and a second noise turns part of the lag into bedrock.
/// A pure function of (seed, map position).
#[cfg(test)]
fn sand_cover(dem: &Raster<f32>, seed: u64, x: f64, y: f64, ground_m: f64) -> SandCover {
    SandCoverField::new(seed).at(dem, x, y, ground_m)
}

/// [`sand_cover`] of one seed with the ring offsets worked out once and the noises cached
/// ([`CachedValue`]): bit-identical, and cheap for neighbouring pixels.
#[derive(Clone, Debug)]
pub(super) struct SandCoverField {
    /// Offsets of the ring samples, metres.
    ring: [(f64, f64); 8],
    patchy: CachedValue,
    exposure: CachedValue,
}

impl SandCoverField {
    /// The cover of seed `seed`.
    pub(super) fn new(seed: u64) -> Self {
        Self {
            ring: std::array::from_fn(|k| {
                let a = f64::from(k as u8) * std::f64::consts::FRAC_PI_4;
                (INTERDUNE_RING_M * a.cos(), INTERDUNE_RING_M * a.sin())
            }),
            patchy: CachedValue::new(seed),
            exposure: CachedValue::new(sub_seed(seed, 1)),
        }
    }

    /// [`sand_cover`] at map point `(x, y)` whose map-DEM height is `ground_m`.
    fn at(&mut self, dem: &Raster<f32>, x: f64, y: f64, ground_m: f64) -> SandCover {
        let depth = self.depth_m(dem, x, y, ground_m);
        self.with_depth(depth, x, y)
    }

    /// The depth of map point `(x, y)` (map-DEM height `ground_m`) below the mean map-DEM
    /// height on the interdune ring around it, metres (independent of the seed).
    pub(super) fn depth_m(&self, dem: &Raster<f32>, x: f64, y: f64, ground_m: f64) -> f64 {
        let mut ring = 0.0;
        for &(dx, dy) in &self.ring {
            ring += dem
                .sample_bilinear(x + dx, y + dy)
                .map_or(ground_m, f64::from);
        }
        ring / 8.0 - ground_m
    }

    /// [`sand_cover`] at map point `(x, y)`, given its [`SandCoverField::depth_m`].
    fn with_depth(&mut self, depth: f64, x: f64, y: f64) -> SandCover {
        let patchy = self.patchy.at(x / INTERDUNE_NOISE_M, y / INTERDUNE_NOISE_M) / VALUE_SD;
        let index = depth / INTERDUNE_DEPTH_M + INTERDUNE_NOISE_WEIGHT * patchy;
        let (t0, tw) = INTERDUNE_THRESHOLD;
        let armoured = smoothstep01((index - t0) / tw);
        let exposure = self
            .exposure
            .at(x / BEDROCK_EXPOSURE_NOISE_M, y / BEDROCK_EXPOSURE_NOISE_M)
            / VALUE_SD;
        let (b0, bw) = BEDROCK_EXPOSURE_THRESHOLD;
        let bedrock = armoured * smoothstep01((exposure - b0) / bw);
        SandCover {
            loose: 1.0 - armoured,
            coarse: armoured - bedrock,
            bedrock,
        }
    }
}

const SALT_DETAIL: u64 = 1;
const SALT_TEXTURE: u64 = 2;
const SALT_GRAIN: u64 = 3;
const SALT_ROCKS: u64 = 4;
const SALT_COVER: u64 = 5;

/// The true terrain around a point: what the orbital and rover renderers image.
///
/// All rasters share one 0.25 m grid ([`TRUTH_RESOLUTION_M_PER_PX`]).
#[derive(Clone, Debug, PartialEq)]
pub struct TruthPatch {
    /// Surface height, metres (map DEM + fine detail + sand ripples + rocks).
    pub height_m: Raster<f32>,
    /// Lambertian albedo, 0..1 (dimensionless).
    pub albedo: Raster<f32>,
    /// Share of loose sand at each pixel, 0..1 (the sand class blended across class borders):
    /// where the ripples are, and where they move between the orbital and the rover epoch.
    pub sand: Raster<f32>,
}

impl TruthPatch {
    /// A hand-built patch with no sand (so nothing moves between epochs).
    #[must_use]
    pub fn from_rasters(height_m: Raster<f32>, albedo: Raster<f32>) -> Self {
        let sand = Raster {
            width: height_m.width,
            height: height_m.height,
            geo: height_m.geo,
            data: vec![0.0; height_m.data.len()],
        };
        Self {
            height_m,
            albedo,
            sand,
        }
    }

    /// Checks a (possibly hand-built) patch before rendering: both rasters the same size with
    /// width × height samples, and a positive finite pixel size.
    pub(super) fn check(&self) -> Result<(), SyntheticError> {
        let (h, a) = (&self.height_m, &self.albedo);
        if h.width != a.width
            || h.height != a.height
            || h.data.len() != h.width * h.height
            || a.data.len() != a.width * a.height
        {
            return Err(SyntheticError::MalformedPatch {
                height_px: [h.width, h.height],
                height_samples: h.data.len(),
                albedo_px: [a.width, a.height],
                albedo_samples: a.data.len(),
            });
        }
        let sd = &self.sand;
        if sd.width != h.width || sd.height != h.height || sd.data.len() != h.data.len() {
            return Err(SyntheticError::InvalidParameter {
                field: "patch.sand",
                value: sd.data.len() as f64,
                expected: "as many sand samples as height samples, on the same grid",
            });
        }
        let res = h.geo.resolution_m_per_px;
        if !(res.is_finite() && res > 0.0) {
            return Err(SyntheticError::InvalidParameter {
                field: "patch.height_m.geo.resolution_m_per_px",
                value: res,
                expected: "a positive finite pixel size in metres",
            });
        }
        Ok(())
    }
}

/// Surface properties of one terrain class.
#[derive(Clone, Copy, Debug, Default)]
struct ClassLook {
    /// Mean albedo.
    albedo: f64,
    /// Relative albedo texture amplitude.
    texture: f64,
    /// Amplitude of the fine height detail, metres.
    detail_m: f64,
    /// Rocks per square metre.
    rocks_per_m2: f64,
    /// Share of loose sand (1 on the sand class, 0 elsewhere).
    sand: f64,
}

impl ClassLook {
    /// Sand is dark and smooth, bedrock bright, textured and rocky; no-data reads as soil.
    fn of_code(code: u8) -> Self {
        match TerrainClass::from_code(code) {
            Some(TerrainClass::Sand) => Self {
                albedo: 0.15,
                texture: 0.04,
                detail_m: 0.03,
                rocks_per_m2: 0.004,
                sand: 1.0,
            },
            Some(TerrainClass::Bedrock) => Self {
                albedo: 0.29,
                texture: 0.16,
                detail_m: 0.20,
                rocks_per_m2: 0.4,
                sand: 0.0,
            },
            Some(TerrainClass::Soil) | None => Self {
                albedo: 0.22,
                texture: 0.09,
                detail_m: 0.08,
                rocks_per_m2: 0.08,
                sand: 0.0,
            },
        }
    }

    /// The coarse lag of armoured interdunes: granules and pebbles over sand, brighter and
    /// more textured than loose sand, with scattered rocks (0.04 per m², half the soil's;
    /// judgement), and a thin veneer of loose sand (its ripples subdued to 15 %).
    fn coarse_lag() -> Self {
        Self {
            albedo: 0.18,
            texture: 0.07,
            detail_m: 0.04,
            rocks_per_m2: 0.02,
            sand: 0.15,
        }
    }

    /// The look of a sand-class pixel with cover `c`: loose sand, coarse lag and bedrock
    /// blended by their shares.
    fn of_sand_cover(c: SandCover) -> Self {
        let mut look = Self::default();
        look.add_scaled(Self::of_code(TerrainClass::Sand.code()), c.loose);
        look.add_scaled(Self::coarse_lag(), c.coarse);
        look.add_scaled(Self::of_code(TerrainClass::Bedrock.code()), c.bedrock);
        look
    }

    fn add_scaled(&mut self, o: Self, k: f64) {
        self.albedo += k * o.albedo;
        self.texture += k * o.texture;
        self.detail_m += k * o.detail_m;
        self.rocks_per_m2 += k * o.rocks_per_m2;
        self.sand += k * o.sand;
    }

    /// The look at map point `(x, y)` (map-DEM height `ground_m`): classes blended bilinearly
    /// between terrain pixel centres, so class borders are not staircases of map pixels; the
    /// sand class by its [`sand_cover`] there (from its ring depth `depth_m` when known).
    fn blended(
        layers: &MapLayers,
        cover: &mut SandCoverField,
        x: f64,
        y: f64,
        ground_m: f64,
        depth_m: Option<f64>,
    ) -> Self {
        let mut look = Self::default();
        let mut sand_look = None;
        for (code, k) in terrain_corners(&layers.terrain, x, y) {
            let corner = if code == TerrainClass::Sand.code() {
                *sand_look.get_or_insert_with(|| {
                    let depth =
                        depth_m.unwrap_or_else(|| cover.depth_m(&layers.dem, x, y, ground_m));
                    Self::of_sand_cover(cover.with_depth(depth, x, y))
                })
            } else {
                Self::of_code(code)
            };
            look.add_scaled(corner, k);
        }
        look
    }

    /// Rocks per m² at map point `(x, y)`: the class under it (nearest map pixel), the sand
    /// class by its cover.
    fn rock_density(layers: &MapLayers, cover: &mut SandCoverField, x: f64, y: f64) -> f64 {
        match layers.terrain.sample_nearest(x, y) {
            None => 0.0,
            Some(code) if code == TerrainClass::Sand.code() => {
                let ground = layers.dem.sample_bilinear(x, y).map_or(0.0, f64::from);
                Self::of_sand_cover(cover.at(&layers.dem, x, y, ground)).rocks_per_m2
            }
            Some(code) => Self::of_code(code).rocks_per_m2,
        }
    }
}

/// The terrain-class codes of the four map pixels around map point `(x, y)` and their bilinear
/// weights, in the order [`ClassLook::blended`] adds them.
pub(super) fn terrain_corners(terrain: &Raster<u8>, x: f64, y: f64) -> [(u8, f64); 4] {
    let (c, r) = terrain.geo.pixel_of(x, y);
    let (w, h) = (terrain.width, terrain.height);
    let c = (c - 0.5).clamp(0.0, (w - 1) as f64);
    let r = (r - 0.5).clamp(0.0, (h - 1) as f64);
    let (c0, r0) = (c as usize, r as usize);
    let (c1, r1) = ((c0 + 1).min(w - 1), (r0 + 1).min(h - 1));
    let (tx, ty) = (c - c0 as f64, r - r0 as f64);
    [
        (c0, r0, (1.0 - tx) * (1.0 - ty)),
        (c1, r0, tx * (1.0 - ty)),
        (c0, r1, (1.0 - tx) * ty),
        (c1, r1, tx * ty),
    ]
    .map(|(cc, rr, k)| (terrain.data[rr * w + cc], k))
}

/// One rock: an ellipsoidal dome sitting on the ground.
#[derive(Clone, Copy, Debug)]
struct Rock {
    center_m: [f64; 2],
    /// Semi-axes, metres.
    semi_axes_m: [f64; 2],
    /// Orientation of the first axis, radians counter-clockwise from east.
    angle_rad: f64,
    height_m: f64,
    albedo: f64,
}

/// The rocks whose centres fall in world cell `(ix, iy)`: a Poisson number at the densest
/// class's rate, thinned by the density of the class under each rock.
fn rocks_in_cell(
    seed: u64,
    cover: &mut SandCoverField,
    ix: i64,
    iy: i64,
    layers: &MapLayers,
    out: &mut Vec<Rock>,
) {
    let max_density = ClassLook::of_code(TerrainClass::Bedrock.code()).rocks_per_m2;
    let lambda = max_density * ROCK_CELL_M * ROCK_CELL_M;
    let mut rng = SplitMix(hash2(seed, ix, iy));
    // Poisson by multiplying uniforms (Knuth); λ is under 2.
    let limit = (-lambda).exp();
    let mut n = 0;
    let mut prod = rng.next_f64();
    while prod > limit && n < 32 {
        n += 1;
        prod *= rng.next_f64();
    }
    let (d_min, d_max) = ROCK_DIAMETER_M;
    let (a_min, a_max) = (
        d_min.powf(-ROCK_SIZE_EXPONENT),
        d_max.powf(-ROCK_SIZE_EXPONENT),
    );
    for _ in 0..n {
        let x = (ix as f64 + rng.next_f64()) * ROCK_CELL_M;
        let y = (iy as f64 + rng.next_f64()) * ROCK_CELL_M;
        let keep = rng.next_f64();
        let u = rng.next_f64();
        let diameter = (a_min - u * (a_min - a_max)).powf(-1.0 / ROCK_SIZE_EXPONENT);
        let aspect = rng.range(0.6, 1.0);
        let angle_rad = rng.range(0.0, std::f64::consts::PI);
        let height_m = diameter * rng.range(ROCK_HEIGHT_RATIO.0, ROCK_HEIGHT_RATIO.1);
        let albedo = rng.range(ROCK_ALBEDO.0, ROCK_ALBEDO.1);
        let density = ClassLook::rock_density(layers, cover, x, y);
        if keep * max_density < density {
            out.push(Rock {
                center_m: [x, y],
                semi_axes_m: [0.5 * diameter, 0.5 * diameter * aspect],
                angle_rad,
                height_m,
                albedo,
            });
        }
    }
}

/// Builds the truth patch around `center_m` from the map `layers`, deterministically.
///
/// The grid has [`TRUTH_RESOLUTION_M_PER_PX`] pixels and covers a square of side
/// `2 × half_size_m` rounded up to whole metres; its north-west corner is snapped to the 1 m
/// lattice of the map DEM's origin so that its 1 m blocks line up with 1 m map pixels.
/// Heights are the bilinear map DEM plus fine fBm detail (±3 cm on sand to ±20 cm on bedrock)
/// plus rocks (ellipsoidal domes 0.1–1.5 m across, 0.3–0.8 × their diameter high; about 0.4
/// per m² on bedrock, 0.08 on soil, 0.04 on coarse interdune lag, 0.004 on loose sand; one in
/// twenty is over 0.5 m across), plus on loose sand aeolian ripples (three trains 40° apart
/// with 2.4–3.7 m mean spacing, wavy, forking crests, 10 cm crest to trough; see
/// `RIPPLE_TRAINS`), weighted by the loose-sand share that [`TruthPatch::sand`] records.
/// The sand class is loose sand on the bedform bodies and armoured lag or bedrock in the
/// troughs between them (`sand_cover`).
/// Albedo follows the terrain class (loose sand 0.15 and smooth, lag 0.20, soil 0.22, bedrock
/// 0.29 and textured; rocks 0.19–0.27) with seeded texture; classes blend over one map pixel. The map's
/// appearance layer is not used: [`render_orbital`](super::render_orbital) makes its own.
/// Every value is a pure function of (`seed`, map position), so overlapping patches agree where
/// they overlap and the thread count does not matter.
///
/// # Errors
/// [`SyntheticError::InvalidParameter`] for a non-finite centre or a `half_size_m` that is not
/// a positive finite number; [`SyntheticError::PatchOutsideMap`] if the square leaves the DEM or
/// the terrain layer of the map.
pub fn truth_patch(
    layers: &MapLayers,
    center_m: [f64; 2],
    half_size_m: f64,
    seed: u64,
) -> Result<TruthPatch, SyntheticError> {
    let (geo, n) = patch_grid(layers, center_m, half_size_m)?;
    Ok(truth_patch_on(layers, geo, n, seed, None, None))
}

/// The grid of [`truth_patch`]: its transform and its side, pixels.
///
/// # Errors
/// As [`truth_patch`].
pub(crate) fn patch_grid(
    layers: &MapLayers,
    center_m: [f64; 2],
    half_size_m: f64,
) -> Result<(GeoTransform, usize), SyntheticError> {
    for (field, value) in [("center_m[0]", center_m[0]), ("center_m[1]", center_m[1])] {
        if !value.is_finite() {
            return Err(SyntheticError::InvalidParameter {
                field,
                value,
                expected: "a finite map coordinate",
            });
        }
    }
    if !(half_size_m.is_finite() && half_size_m > 0.0) {
        return Err(SyntheticError::InvalidParameter {
            field: "half_size_m",
            value: half_size_m,
            expected: "a positive finite number of metres",
        });
    }
    let block_m = ORBITAL_DEM_RESOLUTION_M_PER_PX;
    let blocks = ((2.0 * half_size_m / block_m) - 1e-9).ceil().max(1.0);
    let side_m = blocks * block_m;
    let [dem_ox, dem_oy] = layers.dem.geo.origin_m;
    let ox = dem_ox + ((center_m[0] - 0.5 * side_m - dem_ox) / block_m).round() * block_m;
    let oy = dem_oy + ((center_m[1] + 0.5 * side_m - dem_oy) / block_m).round() * block_m;
    let patch_extent_m = [ox, oy - side_m, ox + side_m, oy];
    for (layer, raster_extent) in [
        ("dem", layers.dem.extent_m()),
        ("terrain", layers.terrain.extent_m()),
    ] {
        let (x0, y0, x1, y1) = raster_extent;
        let tol = 1e-9 * (1.0 + x0.abs().max(y1.abs()));
        if patch_extent_m[0] < x0 - tol
            || patch_extent_m[1] < y0 - tol
            || patch_extent_m[2] > x1 + tol
            || patch_extent_m[3] > y1 + tol
        {
            return Err(SyntheticError::PatchOutsideMap {
                layer,
                patch_extent_m,
                map_extent_m: [x0, y0, x1, y1],
            });
        }
    }

    let n = blocks as usize * BLOCK_PX;
    Ok((GeoTransform::new(ox, oy, TRUTH_RESOLUTION_M_PER_PX), n))
}

/// The truth patch of [`truth_patch`] on its grid (`geo`, `n`: see [`patch_grid`]), with the
/// seed-independent fields taken from `statics` when given: the same values, computed once per
/// map (see [`super::statics`]).
///
/// `donor`, when given, is a patch of the same map and `seed` on the same pixel lattice (from
/// [`truth_patch`] or this function): every pixel is a pure function of (`seed`, map position),
/// and with lattice coordinates exact (the caller's guarantee, as for `statics`) the same bits,
/// so the pixels it covers are copied and only the rest is computed.
pub(crate) fn truth_patch_on(
    layers: &MapLayers,
    geo: GeoTransform,
    n: usize,
    seed: u64,
    statics: Option<&PatchStatics<'_>>,
    donor: Option<&TruthPatch>,
) -> TruthPatch {
    let statics = statics.filter(|s| s.n() == n);
    let overlap = donor.and_then(|d| Overlap::of(d, geo, n));
    let detail = ValueFbm::new(sub_seed(seed, SALT_DETAIL), DETAIL_WAVELENGTH_M, 4);
    let texture = ValueFbm::new(sub_seed(seed, SALT_TEXTURE), TEXTURE_WAVELENGTH_M, 3);
    let grain_seed = sub_seed(seed, SALT_GRAIN);
    let cover_seed = sub_seed(seed, SALT_COVER);
    let xs: Vec<f64> = (0..n).map(|col| geo.center_of(col, 0).0).collect();
    let mut height = vec![0.0f32; n * n];
    let mut albedo = vec![0.0f32; n * n];
    let mut sand = vec![0.0f32; n * n];
    height
        .par_chunks_mut(n)
        .zip(albedo.par_chunks_mut(n))
        .zip(sand.par_chunks_mut(n))
        .enumerate()
        .for_each_init(
            || {
                let rows = (vec![0.0; n], vec![0.0; n]);
                let static_rows = (vec![0.0f32; n], vec![0.0; n], vec![0.0; n]);
                let fields = (RippleField::new(), SandCoverField::new(cover_seed));
                (fields, rows, static_rows)
            },
            |((ripple, cover), (detail_row, texture_row), (ground_row, depth_row, ripple_row)),
             (row, ((h_row, a_row), s_row))| {
                // The columns the donor covers on this row, copied; the rest computed.
                let copied = match (&overlap, donor) {
                    (Some(o), Some(d)) if o.rows.contains(&row) => {
                        let cols = o.cols.clone();
                        // Donor pixel (row + dj, col + di), both inside the donor here.
                        let start = (row as isize + o.dj) as usize * d.height_m.width;
                        let (c0, c1) = (
                            (cols.start as isize + o.di) as usize,
                            (cols.end as isize + o.di) as usize,
                        );
                        let take = |dst: &mut [f32], data: &[f32]| {
                            dst[cols.clone()].copy_from_slice(&data[start + c0..start + c1]);
                        };
                        take(h_row, &d.height_m.data);
                        take(a_row, &d.albedo.data);
                        take(s_row, &d.sand.data);
                        cols
                    }
                    _ => 0..0,
                };
                let y = geo.center_of(0, row).1;
                if let Some(st) = statics {
                    st.truth_row(row, ground_row, depth_row, ripple_row);
                }
                for span in [0..copied.start, copied.end.max(copied.start)..n] {
                    if span.is_empty() {
                        continue;
                    }
                    detail.row(&xs[span.clone()], y, &mut detail_row[span.clone()]);
                    texture.row(&xs[span.clone()], y, &mut texture_row[span.clone()]);
                    for col in span {
                        let x = xs[col];
                        // Pixel centres lie inside the DEM (checked above); the fallback is never
                        // used.
                        let (ground, depth) = match statics {
                            Some(_) => (f64::from(ground_row[col]), Some(depth_row[col])),
                            None => {
                                let g = layers.dem.sample_bilinear(x, y).unwrap_or(0.0);
                                (f64::from(g), None)
                            }
                        };
                        let look = ClassLook::blended(layers, cover, x, y, ground, depth);
                        let ripples = if look.sand > 0.0 {
                            match statics {
                                Some(_) => look.sand * ripple_row[col],
                                None => {
                                    let weights = ripple.weights(x, y);
                                    look.sand * ripple.height_m(x, y, 0.0, &weights)
                                }
                            }
                        } else {
                            0.0
                        };
                        h_row[col] = (ground + look.detail_m * detail_row[col] + ripples) as f32;
                        s_row[col] = look.sand as f32;
                        // World pixel indices, so the grain does not depend on where the patch
                        // starts.
                        let (gx, gy) = (
                            floor_i64(x / TRUTH_RESOLUTION_M_PER_PX),
                            floor_i64(y / TRUTH_RESOLUTION_M_PER_PX),
                        );
                        let grain = 0.35 * gaussian(grain_seed, gx, gy).clamp(-3.0, 3.0);
                        let mottle = texture_row[col] + grain;
                        a_row[col] =
                            (look.albedo * (1.0 + look.texture * mottle)).clamp(0.02, 0.6) as f32;
                    }
                }
            },
        );

    // Rocks on the computed pixels only (the copied ones carry theirs).
    let rocks_seed = sub_seed(seed, SALT_ROCKS);
    let full = [0..n, 0..n];
    let rects = match &overlap {
        Some(o) => o.rest(n),
        None => vec![full],
    };
    for [rows, cols] in rects {
        stamp_rocks(
            rocks_seed,
            cover_seed,
            layers,
            geo,
            n,
            [rows, cols],
            &mut height,
            &mut albedo,
        );
    }

    TruthPatch {
        height_m: Raster {
            width: n,
            height: n,
            geo,
            data: height,
        },
        albedo: Raster {
            width: n,
            height: n,
            geo,
            data: albedo,
        },
        sand: Raster {
            width: n,
            height: n,
            geo,
            data: sand,
        },
    }
}

/// Where a donor patch covers a new patch grid: the new grid's rows and columns it covers, and
/// the donor's pixel offset (`donor (row + dj, col + di)` is the new `(row, col)`).
#[derive(Clone, Debug, PartialEq)]
struct Overlap {
    rows: std::ops::Range<usize>,
    cols: std::ops::Range<usize>,
    di: isize,
    dj: isize,
}

impl Overlap {
    /// The overlap of `donor` with the `n × n` grid `geo`, or `None` if it is not on the same
    /// pixel lattice (an exact whole number of pixels away) or covers nothing.
    fn of(donor: &TruthPatch, geo: GeoTransform, n: usize) -> Option<Self> {
        let dg = donor.height_m.geo;
        let res = geo.resolution_m_per_px;
        if dg.resolution_m_per_px.to_bits() != res.to_bits() {
            return None;
        }
        let (fi, fj) = (
            (geo.origin_m[0] - dg.origin_m[0]) / res,
            (dg.origin_m[1] - geo.origin_m[1]) / res,
        );
        if !(fi.fract() == 0.0 && fj.fract() == 0.0 && fi.abs() < 1e9 && fj.abs() < 1e9) {
            return None;
        }
        let (di, dj) = (fi as isize, fj as isize);
        let (dw, dh) = (
            donor.height_m.width as isize,
            donor.height_m.height as isize,
        );
        let span = |d: isize, len: isize| {
            let lo = (-d).clamp(0, n as isize) as usize;
            let hi = (len - d).clamp(0, n as isize) as usize;
            lo..hi.max(lo)
        };
        let (rows, cols) = (span(dj, dh), span(di, dw));
        (!rows.is_empty() && !cols.is_empty()).then_some(Self { rows, cols, di, dj })
    }

    /// The rectangles `[rows, cols]` of the `n × n` grid outside the overlap.
    fn rest(&self, n: usize) -> Vec<[std::ops::Range<usize>; 2]> {
        let mut out = Vec::new();
        for cols in [0..self.cols.start, self.cols.end..n] {
            if !cols.is_empty() {
                out.push([0..n, cols]);
            }
        }
        for rows in [0..self.rows.start, self.rows.end..n] {
            if !rows.is_empty() {
                out.push([rows, self.cols.clone()]);
            }
        }
        out
    }
}

/// Adds, on the pixels `rows × cols` of the `n × n` grid at `geo`, the rocks of every cell that
/// can reach them. Where rocks overlap the tallest wins, so the result does not depend on the
/// order they are stamped in, nor on which other pixels are stamped with them.
#[allow(clippy::too_many_arguments)]
fn stamp_rocks(
    seed: u64,
    cover_seed: u64,
    layers: &MapLayers,
    geo: GeoTransform,
    n: usize,
    [rows, cols]: [std::ops::Range<usize>; 2],
    height: &mut [f32],
    albedo: &mut [f32],
) {
    let res = geo.resolution_m_per_px;
    let [ox, oy] = geo.origin_m;
    let reach_m = 0.5 * ROCK_DIAMETER_M.1;
    let cell = |v: f64| floor_i64(v / ROCK_CELL_M);
    // The rectangle's extent, as the whole grid's is `[ox, ox + n·res] × [oy − n·res, oy]`.
    let (x0, x1) = (ox + cols.start as f64 * res, ox + cols.end as f64 * res);
    let (y1, y0) = (oy - rows.start as f64 * res, oy - rows.end as f64 * res);
    let (ix0, ix1) = (cell(x0 - reach_m), cell(x1 + reach_m));
    let (iy0, iy1) = (cell(y0 - reach_m), cell(y1 + reach_m));
    let mut cover = SandCoverField::new(cover_seed);
    let mut rocks = Vec::new();
    for iy in iy0..=iy1 {
        for ix in ix0..=ix1 {
            rocks_in_cell(seed, &mut cover, ix, iy, layers, &mut rocks);
        }
    }
    let (rw, rh) = (cols.len(), rows.len());
    let mut rock_h = vec![0.0f32; rw * rh];
    let mut rock_albedo = vec![0.0f32; rw * rh];
    for rock in &rocks {
        let [rx, ry] = rock.center_m;
        let a = rock.semi_axes_m[0];
        let px = |v: f64| v.floor().clamp(0.0, n as f64) as usize;
        let (c0, c1) = (px((rx - a - ox) / res), px((rx + a - ox) / res + 1.0));
        let (r0, r1) = (px((oy - ry - a) / res), px((oy - ry + a) / res + 1.0));
        let (cos, sin) = (rock.angle_rad.cos(), rock.angle_rad.sin());
        for row in r0.max(rows.start)..r1.min(rows.end) {
            for col in c0.max(cols.start)..c1.min(cols.end) {
                let (x, y) = geo.center_of(col, row);
                let (dx, dy) = (x - rx, y - ry);
                let u = (dx * cos + dy * sin) / rock.semi_axes_m[0];
                let v = (-dx * sin + dy * cos) / rock.semi_axes_m[1];
                let q = 1.0 - u * u - v * v;
                if q <= 0.0 {
                    continue;
                }
                let z = (rock.height_m * q.sqrt()) as f32;
                let i = (row - rows.start) * rw + (col - cols.start);
                if z > rock_h[i] || (z == rock_h[i] && (rock.albedo as f32) > rock_albedo[i]) {
                    rock_h[i] = z;
                    rock_albedo[i] = rock.albedo as f32;
                }
            }
        }
    }
    for (r, row) in rows.enumerate() {
        for (c, col) in cols.clone().enumerate() {
            let (k, i) = (r * rw + c, row * n + col);
            if rock_h[k] > 0.0 {
                height[i] += rock_h[k];
                // Keep a little of the ground's texture on the rock surface.
                albedo[i] = 0.85 * rock_albedo[k] + 0.15 * albedo[i];
            }
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn layers(code: u8) -> MapLayers {
        let geo = GeoTransform::new(0.0, 100.0, 1.0);
        MapLayers {
            appearance: Raster::filled(100, 100, geo, 0),
            dem: Raster::filled(100, 100, geo, 10.0),
            terrain: Raster::filled(100, 100, geo, code),
        }
    }

    fn rocks_per_m2(l: &MapLayers) -> f64 {
        let mut rocks = Vec::new();
        let mut cover = SandCoverField::new(8);
        for iy in 5..45 {
            for ix in 5..45 {
                rocks_in_cell(7, &mut cover, ix, iy, l, &mut rocks);
            }
        }
        rocks.len() as f64 / (40.0 * 40.0 * ROCK_CELL_M * ROCK_CELL_M)
    }

    #[test]
    fn rock_cover_follows_the_terrain_class() {
        let (sand, soil, rock) = (
            rocks_per_m2(&layers(1)),
            rocks_per_m2(&layers(2)),
            rocks_per_m2(&layers(3)),
        );
        // Flat sand (no bedform troughs): almost all loose sand (0.004 per m²), a few patches
        // of lag; the troughs' armour is tested below.
        assert!(
            sand < 0.02 && (0.06..0.10).contains(&soil) && (0.33..0.47).contains(&rock),
            "{sand} {soil} {rock}"
        );
        let sand = truth_patch(&layers(1), [50.0, 50.0], 20.0, 3).unwrap();
        let rock = truth_patch(&layers(3), [50.0, 50.0], 20.0, 3).unwrap();
        let mean = |p: &TruthPatch| p.albedo.data.iter().sum::<f32>() / p.albedo.data.len() as f32;
        assert!(mean(&sand) < mean(&rock));
    }

    #[test]
    fn interdune_troughs_are_armoured_and_bedform_crests_loose() {
        // Bedforms of 20 m spacing, 2 m crest to trough, crests running north–south.
        let mut l = layers(1);
        for row in 0..100 {
            for col in 0..100 {
                let h = 10.0 + (std::f64::consts::TAU * col as f64 / 20.0).cos();
                l.dem.set(col, row, h as f32);
            }
        }
        let (mut crest_loose, mut trough_loose, mut n) = (0.0, 0.0, 0.0);
        for k in 0..40 {
            let y = 20.0 + f64::from(k) * 1.5;
            let c = sand_cover(&l.dem, 5, 40.5, y, 11.0);
            let t = sand_cover(&l.dem, 5, 50.5, y, 9.0);
            for v in [c, t] {
                assert!(
                    (v.loose + v.coarse + v.bedrock - 1.0).abs() < 1e-12,
                    "{v:?}"
                );
                assert!(
                    v.loose >= 0.0 && v.coarse >= 0.0 && v.bedrock >= 0.0,
                    "{v:?}"
                );
            }
            crest_loose += c.loose;
            trough_loose += t.loose;
            n += 1.0;
        }
        assert!(
            crest_loose / n > 0.8 && trough_loose / n < 0.2,
            "{crest_loose} {trough_loose}"
        );
    }

    /// `sand_cover` as first written (a value-noise call per noise, the ring's trigonometry per
    /// sample): the reference for [`SandCoverField`].
    fn sand_cover_reference(
        dem: &Raster<f32>,
        seed: u64,
        x: f64,
        y: f64,
        ground_m: f64,
    ) -> SandCover {
        let mut ring = 0.0;
        for k in 0..8 {
            let a = f64::from(k) * std::f64::consts::FRAC_PI_4;
            let (px, py) = (
                x + INTERDUNE_RING_M * a.cos(),
                y + INTERDUNE_RING_M * a.sin(),
            );
            ring += dem.sample_bilinear(px, py).map_or(ground_m, f64::from);
        }
        let depth = ring / 8.0 - ground_m;
        let patchy = value(seed, x / INTERDUNE_NOISE_M, y / INTERDUNE_NOISE_M) / VALUE_SD;
        let index = depth / INTERDUNE_DEPTH_M + INTERDUNE_NOISE_WEIGHT * patchy;
        let (t0, tw) = INTERDUNE_THRESHOLD;
        let armoured = smoothstep01((index - t0) / tw);
        let exposure = value(
            sub_seed(seed, 1),
            x / BEDROCK_EXPOSURE_NOISE_M,
            y / BEDROCK_EXPOSURE_NOISE_M,
        ) / VALUE_SD;
        let (b0, bw) = BEDROCK_EXPOSURE_THRESHOLD;
        let bedrock = armoured * smoothstep01((exposure - b0) / bw);
        SandCover {
            loose: 1.0 - armoured,
            coarse: armoured - bedrock,
            bedrock,
        }
    }

    #[test]
    fn cached_fields_equal_their_references_bit_for_bit() {
        let mut l = layers(1);
        for row in 0..100 {
            for col in 0..100 {
                let h =
                    10.0 + (std::f64::consts::TAU * col as f64 / 20.0).cos() + 0.01 * row as f64;
                l.dem.set(col, row, h as f32);
            }
        }
        let bits = |c: SandCover| [c.loose.to_bits(), c.coarse.to_bits(), c.bedrock.to_bits()];
        let (mut ripple, mut migrated, mut cover) = (
            RippleField::new(),
            RippleField::new(),
            SandCoverField::new(11),
        );
        // Along rows of 25 cm pixels, as the patch renders them, then scattered points.
        let mut points: Vec<(f64, f64)> = (0..3000)
            .map(|i| {
                (
                    20.125 + f64::from(i % 300) * 0.25,
                    70.875 - f64::from(i / 300) * 3.5,
                )
            })
            .collect();
        points
            .extend((0..300).map(|i| (f64::from(i * 53 % 97) + 0.3, f64::from(i * 31 % 89) + 0.7)));
        for (x, y) in points {
            let w = ripple.weights(x, y);
            assert_eq!(
                ripple.height_m(x, y, 0.0, &w).to_bits(),
                ripple_height_m(x, y, 0.0).to_bits(),
                "({x}, {y})"
            );
            assert_eq!(
                migrated.height_m(x, y, -0.75, &w).to_bits(),
                ripple_height_m(x, y, -0.75).to_bits(),
                "({x}, {y})"
            );
            let ground = f64::from(l.dem.sample_bilinear(x, y).unwrap_or(0.0));
            assert_eq!(
                bits(cover.at(&l.dem, x, y, ground)),
                bits(sand_cover_reference(&l.dem, 11, x, y, ground)),
                "({x}, {y})"
            );
        }
    }

    #[test]
    fn ripples_are_not_periodic() {
        // A perfectly periodic train repeats exactly one wavelength across its crests; the
        // warped, blended trains do not.
        let across = (110.0f64).to_radians();
        let (ax, ay) = (across.sin(), across.cos());
        let (mut diff, mut power) = (0.0, 0.0);
        for i in 0..4000 {
            let (x, y) = (f64::from(i % 200) * 0.37, f64::from(i / 200) * 2.3);
            let h = ripple_height_m(x, y, 0.0);
            let h1 = ripple_height_m(
                x + RIPPLE_WAVELENGTH_M * ax,
                y + RIPPLE_WAVELENGTH_M * ay,
                0.0,
            );
            diff += (h - h1).powi(2);
            power += h * h;
            assert!(h.abs() <= 1.8 * RIPPLE_AMPLITUDE_M, "{h}");
        }
        assert!(diff / power > 0.3, "{}", diff / power);
        // Migration moves the pattern.
        assert!(ripple_height_m(3.1, 7.9, 0.75) != ripple_height_m(3.1, 7.9, 0.0));
    }

    #[test]
    fn overlapping_patches_agree() {
        let l = layers(3);
        let a = truth_patch(&l, [40.0, 40.0], 10.0, 9).unwrap();
        let b = truth_patch(&l, [45.0, 37.0], 10.0, 9).unwrap();
        // Pixel (0, 0) of b lies inside a at an integer offset (grids share the 1 m lattice).
        let (dc, dr) = (
            ((b.height_m.geo.origin_m[0] - a.height_m.geo.origin_m[0]) / 0.25).round() as usize,
            ((a.height_m.geo.origin_m[1] - b.height_m.geo.origin_m[1]) / 0.25).round() as usize,
        );
        for (r, c) in [(0, 0), (5, 7), (30, 12)] {
            assert_eq!(
                b.height_m.get(c, r).to_bits(),
                a.height_m.get(c + dc, r + dr).to_bits()
            );
            assert_eq!(
                b.albedo.get(c, r).to_bits(),
                a.albedo.get(c + dc, r + dr).to_bits()
            );
        }
    }

    #[test]
    fn bad_sizes_and_off_map_patches_are_errors() {
        let l = layers(2);
        assert!(matches!(
            truth_patch(&l, [50.0, 50.0], 0.0, 1),
            Err(SyntheticError::InvalidParameter { .. })
        ));
        assert!(matches!(
            truth_patch(&l, [f64::NAN, 50.0], 5.0, 1),
            Err(SyntheticError::InvalidParameter { .. })
        ));
        assert!(matches!(
            truth_patch(&l, [95.0, 50.0], 10.0, 1),
            Err(SyntheticError::PatchOutsideMap { .. })
        ));
        let p = truth_patch(&l, [50.0, 50.0], 50.0, 1).unwrap();
        assert_eq!(p.height_m.width, 400);
    }
}
