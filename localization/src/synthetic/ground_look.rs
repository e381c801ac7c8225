//! What each terrain class looks like on the truth terrain (albedo, texture, detail, rocks),
//! blended over the map pixels around a point.

use maps::{MapLayers, Raster, TerrainClass};

use super::bedforms::{SandCover, SandCoverField};

/// Surface properties of one terrain class.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct ClassLook {
    /// Mean albedo.
    pub(super) albedo: f64,
    /// Relative albedo texture amplitude.
    pub(super) texture: f64,
    /// Amplitude of the fine height detail, metres.
    pub(super) detail_m: f64,
    /// Rocks per square metre.
    pub(super) rocks_per_m2: f64,
    /// Share of loose sand (1 on the sand class, 0 elsewhere).
    pub(super) sand: f64,
}

impl ClassLook {
    /// Sand is dark and smooth, bedrock bright, textured and rocky; no-data reads as soil.
    pub(super) fn of_code(code: u8) -> Self {
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
    pub(super) fn of_sand_cover(c: SandCover) -> Self {
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
    pub(super) fn blended(
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
    pub(super) fn rock_density(
        layers: &MapLayers,
        cover: &mut SandCoverField,
        x: f64,
        y: f64,
    ) -> f64 {
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
