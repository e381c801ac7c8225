//! The localizers of the comparison: their names, what each needs.

use localization::matcher::Method;

/// One localizer of the comparison.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Candidate {
    /// The statistical model of the flight accuracy.
    Statistical,
    /// Census, NCC or MI matching.
    Matcher(Method),
    /// Paper 002's particle filter.
    Particle,
    /// Paper 004's EKF.
    Ekf,
}

impl Candidate {
    /// The six, in the order of the table.
    pub const ALL: [Candidate; 6] = [
        Candidate::Statistical,
        Candidate::Matcher(Method::Census),
        Candidate::Matcher(Method::Ncc),
        Candidate::Matcher(Method::MutualInformation),
        Candidate::Particle,
        Candidate::Ekf,
    ];

    /// Its name in scenario files and on the command line.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Candidate::Statistical => "statistical",
            Candidate::Matcher(m) => m.name(),
            Candidate::Particle => "particle",
            Candidate::Ekf => "ekf",
        }
    }

    /// The candidate named `name`.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|c| c.name() == name)
    }

    /// What it needs besides the rover's estimate.
    #[must_use]
    pub fn needs(self) -> &'static str {
        match self {
            Candidate::Statistical => "nothing (a model of the flight statistics)",
            Candidate::Matcher(_) => "post-drive imagery, orbital map, co-processor",
            Candidate::Particle => "post-drive imagery, orbital map, co-processor",
            Candidate::Ekf => "an orbiter pass (ranges), IMU",
        }
    }

    /// Whether it needs the rendered imagery.
    pub(super) fn uses_imagery(self) -> bool {
        matches!(self, Candidate::Matcher(_) | Candidate::Particle)
    }
}
