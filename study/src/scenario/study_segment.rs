//! `[study_segment]`: the stretch of the traverse a study compares strategies on →
//! [`StudySegment`], also what a sweep's manifest records and its `segment_sols` count.

use sim::operations::calendar::Calendar;

use super::raw::RawStudySegment;
use crate::check::FieldCheck;
use crate::error::ScenarioError;
use crate::ranges;

/// `[study_segment]`: the stretch of the traverse a study compares strategies on — the sols
/// needed to drive `distance_m` metres counted from `from_sol` (`segment_sols` in a sweep's
/// `runs.parquet`; `segment` in its `manifest.json`).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StudySegment {
    /// First sol counted (a sol of the calendar).
    pub from_sol: u32,
    /// Metres to cover.
    pub distance_m: f64,
}

/// The study segment `[study_segment]` describes, on `calendar`.
///
/// # Errors
/// A [`ScenarioError`] naming `study_segment.from_sol` (not a sol of the calendar) or
/// `study_segment.distance_m` (outside [`ranges::STUDY_SEGMENT_M`]).
pub(crate) fn study_segment(
    c: &FieldCheck<'_>,
    raw: Option<&RawStudySegment>,
    calendar: &Calendar,
) -> Result<Option<StudySegment>, ScenarioError> {
    let Some(g) = raw else { return Ok(None) };
    if !calendar.sols.iter().any(|s| s.sol == g.from_sol) {
        return Err(c.err(
            "study_segment.from_sol",
            "a sol of the calendar",
            g.from_sol,
        ));
    }
    c.range(
        ranges::STUDY_SEGMENT_M,
        "study_segment.distance_m",
        g.distance_m,
    )?;
    Ok(Some(StudySegment {
        from_sol: g.from_sol,
        distance_m: g.distance_m,
    }))
}
