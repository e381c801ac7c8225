//! Operations strategies: how plans are built and how the rover is localized.
//!
//! | strategy | plans | localization |
//! |---|---|---|
//! | `replay` | as historically recorded (per plan), historic distances and VO | ground |
//! | `ground` | ground-in-the-loop (today's practice) | ground, at each uplink |
//! | `onboard` | every sol the calendar allows; none skipped or cut for a panorama | onboard after every drive sol, and ground |
//! | `extension` | opportunistic extension at every uplink | ground only, when data allows |
//! | `extension+onboard` | opportunistic extension | onboard after every drive sol, and ground |
//!
//! What each one decides, sol by sol, is in [`crate::operations::policy`].

use crate::operations::calendar::Planning;

/// An operations strategy.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub enum Strategy {
    /// The historic record: per-sol distances, VO and plan types from the scenario file.
    #[serde(rename = "replay")]
    Replay,
    /// Ground-in-the-loop localization and planning.
    #[serde(rename = "ground")]
    Ground,
    /// Ground planning, onboard global localization after each driving sol.
    #[serde(rename = "onboard")]
    Onboard,
    /// Opportunistic extension drives without onboard localization.
    #[serde(rename = "extension")]
    Extension,
    /// Opportunistic extension drives with onboard localization.
    #[serde(rename = "extension+onboard")]
    ExtensionOnboard,
}

impl Strategy {
    /// Every strategy, in report order.
    pub const ALL: [Strategy; 5] = [
        Strategy::Replay,
        Strategy::Ground,
        Strategy::Onboard,
        Strategy::Extension,
        Strategy::ExtensionOnboard,
    ];

    /// The name used on the command line and in outputs.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Strategy::Replay => "replay",
            Strategy::Ground => "ground",
            Strategy::Onboard => "onboard",
            Strategy::Extension => "extension",
            Strategy::ExtensionOnboard => "extension+onboard",
        }
    }

    /// The strategy called `name` (as printed by [`Strategy::name`]).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|s| s.name() == name)
    }

    /// How plans are built; `None` for the replay, which takes it from the record.
    #[must_use]
    pub fn planning(self) -> Option<Planning> {
        match self {
            Strategy::Replay => None,
            Strategy::Ground | Strategy::Onboard => Some(Planning::Ground),
            Strategy::Extension | Strategy::ExtensionOnboard => Some(Planning::Extension),
        }
    }

    /// Whether the rover localizes itself after every drive sol.
    #[must_use]
    pub fn onboard_localization(self) -> bool {
        matches!(self, Strategy::Onboard | Strategy::ExtensionOnboard)
    }

    /// Random-stream id of this strategy (so strategies never share draws).
    #[must_use]
    pub fn stream_id(self) -> u64 {
        self as u64
    }
}

impl std::fmt::Display for Strategy {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.pad(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for s in Strategy::ALL {
            assert_eq!(Strategy::from_name(s.name()), Some(s));
        }
        assert_eq!(Strategy::from_name("telepathy"), None);
        // Display is the name, and honours the width of a table column.
        assert_eq!(format!("{:<10}|", Strategy::Onboard), "onboard   |");
    }
}
