//! Terrain classes of the orbital terrain-class map (sand, soil, bedrock), and a value per class
//! ([`PerTerrain`]: VO failure, slip, path cost, metres driven on each).

/// Surface type of a map pixel. Drives Visual Odometry success and slip (paper 003 §4).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TerrainClass {
    /// Loose aeolian sand: poor VO texture, high slip.
    Sand,
    /// Regolith and gravel: the common case.
    Soil,
    /// Exposed rock: good VO texture, low slip.
    Bedrock,
}

impl TerrainClass {
    /// Every class, in code order.
    pub const ALL: [TerrainClass; 3] = [
        TerrainClass::Sand,
        TerrainClass::Soil,
        TerrainClass::Bedrock,
    ];

    /// The code stored in terrain-class rasters: sand = 1, soil = 2, bedrock = 3 (0 = no data).
    #[must_use]
    pub fn code(self) -> u8 {
        match self {
            TerrainClass::Sand => 1,
            TerrainClass::Soil => 2,
            TerrainClass::Bedrock => 3,
        }
    }

    /// The class for a raster code, or `None` for 0 (no data) and unknown codes.
    #[must_use]
    pub fn from_code(code: u8) -> Option<Self> {
        match code {
            1 => Some(TerrainClass::Sand),
            2 => Some(TerrainClass::Soil),
            3 => Some(TerrainClass::Bedrock),
            _ => None,
        }
    }

    /// Lower-case name as used in scenario files.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            TerrainClass::Sand => "sand",
            TerrainClass::Soil => "soil",
            TerrainClass::Bedrock => "bedrock",
        }
    }
}

/// A value per terrain class.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct PerTerrain {
    /// Value on sand.
    pub sand: f64,
    /// Value on soil.
    pub soil: f64,
    /// Value on bedrock.
    pub bedrock: f64,
}

impl PerTerrain {
    /// The value for `class`.
    #[must_use]
    pub fn get(&self, class: TerrainClass) -> f64 {
        match class {
            TerrainClass::Sand => self.sand,
            TerrainClass::Soil => self.soil,
            TerrainClass::Bedrock => self.bedrock,
        }
    }

    /// Add `v` to the value of `class`.
    pub fn add(&mut self, class: TerrainClass, v: f64) {
        match class {
            TerrainClass::Sand => self.sand += v,
            TerrainClass::Soil => self.soil += v,
            TerrainClass::Bedrock => self.bedrock += v,
        }
    }

    /// The sum over the classes.
    #[must_use]
    pub fn total(&self) -> f64 {
        self.sand + self.soil + self.bedrock
    }
}

impl std::ops::AddAssign for PerTerrain {
    fn add_assign(&mut self, other: Self) {
        self.sand += other.sand;
        self.soil += other.soil;
        self.bedrock += other.bedrock;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_round_trip() {
        for c in TerrainClass::ALL {
            assert_eq!(TerrainClass::from_code(c.code()), Some(c));
        }
        assert_eq!(TerrainClass::from_code(0), None);
        assert_eq!(TerrainClass::from_code(9), None);
    }
}
