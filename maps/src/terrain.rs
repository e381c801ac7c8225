//! Terrain classes of the orbital terrain-class map (sand, soil, bedrock).

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
