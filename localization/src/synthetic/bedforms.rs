//! Sand bedforms on the truth terrain: the aeolian ripple field and where the sand class is
//! loose sand, armoured lag or bedrock (interdune troughs).

use maps::Raster;

#[cfg(test)]
use super::noise::value;
use super::noise::{CachedValue, sub_seed};

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
pub(super) const RIPPLE_TRAINS: [(f64, f64); 3] =
    [(20.0, RIPPLE_WAVELENGTH_M), (60.0, 2.4), (-20.0, 3.7)];
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
pub(super) struct SandCover {
    pub(super) loose: f64,
    pub(super) coarse: f64,
    pub(super) bedrock: f64,
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
    pub(super) fn at(&mut self, dem: &Raster<f32>, x: f64, y: f64, ground_m: f64) -> SandCover {
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
    pub(super) fn with_depth(&mut self, depth: f64, x: f64, y: f64) -> SandCover {
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

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use maps::GeoTransform;

    use super::*;

    #[test]
    fn interdune_troughs_are_armoured_and_bedform_crests_loose() {
        // Bedforms of 20 m spacing, 2 m crest to trough, crests running north–south.
        let mut dem = Raster::filled(100, 100, GeoTransform::new(0.0, 100.0, 1.0), 10.0f32);
        for row in 0..100 {
            for col in 0..100 {
                let h = 10.0 + (std::f64::consts::TAU * col as f64 / 20.0).cos();
                dem.set(col, row, h as f32);
            }
        }
        let (mut crest_loose, mut trough_loose, mut n) = (0.0, 0.0, 0.0);
        for k in 0..40 {
            let y = 20.0 + f64::from(k) * 1.5;
            let c = sand_cover(&dem, 5, 40.5, y, 11.0);
            let t = sand_cover(&dem, 5, 50.5, y, 9.0);
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
        let mut dem = Raster::filled(100, 100, GeoTransform::new(0.0, 100.0, 1.0), 10.0f32);
        for row in 0..100 {
            for col in 0..100 {
                let h =
                    10.0 + (std::f64::consts::TAU * col as f64 / 20.0).cos() + 0.01 * row as f64;
                dem.set(col, row, h as f32);
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
            let ground = f64::from(dem.sample_bilinear(x, y).unwrap_or(0.0));
            assert_eq!(
                bits(cover.at(&dem, x, y, ground)),
                bits(sand_cover_reference(&dem, 11, x, y, ground)),
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
}
