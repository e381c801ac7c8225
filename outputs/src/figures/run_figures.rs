//! The figures of one compare run ([`run_figures`]): what `solsim compare` writes beside its
//! files as SVG and `report.html` shows inline, each with its file name and caption.

use sim::CampaignOutcome;
use study::Scenario;

use crate::figures::by_sol::{metres_by_sol_svg, uncertainty_by_sol_svg};
use crate::figures::canvas::FigureError;
use crate::figures::gantt::sol_plans_gantt_svg;
use crate::figures::passages::passages_svg;
use crate::figures::route_map::{Growth, route_map_svg};
use crate::figures::zone_moments::{REACH_M, fault_window};

/// One figure of a compare run.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RunFigure {
    /// File name in the output directory, e.g. `sol383-386.replay.map.svg`.
    pub file: String,
    /// What the figure shows, one paragraph (the report's caption).
    pub caption: String,
    /// The SVG document.
    pub svg: String,
}

/// The figures of one compare run, each with its file name and caption: the uncertainty radius and
/// the metres per sol of every strategy, and per strategy its map (keep-outs grown at
/// `map_r_m`, or by default each at the r the rover had where it passed it), the zoomed panels
/// at its passages, a zoom on each fault and, where its sols were planned, the Gantt chart of
/// the plans.
///
/// # Errors
/// When a figure cannot be drawn.
pub fn run_figures(
    scenario: &Scenario,
    outcomes: &[CampaignOutcome],
    map_r_m: Option<f64>,
) -> Result<Vec<RunFigure>, FigureError> {
    let name = &scenario.name;
    let mut out = vec![
        (
            format!("{name}.uncertainty.svg"),
            "Position-uncertainty radius r per sol: growth while driving, drops where a \
             localization resets it, red crosses at faults (paper 000 Fig. 2 and 5). Each \
             strategy has its own dash pattern and a marker at the end of each drive, and the \
             lines are shifted 2 px apart, so where strategies share a line all stay visible."
                .to_string(),
            uncertainty_by_sol_svg(&format!("{name}: uncertainty radius r per sol"), outcomes)?,
        ),
        (
            format!("{name}.metres.svg"),
            "Metres driven per sol and strategy; red crosses where the drive ended in a fault."
                .to_string(),
            metres_by_sol_svg(&format!("{name}: metres driven per sol"), outcomes)?,
        ),
    ];
    for o in outcomes {
        let strategy = o.strategy.name();
        let (growth, how) = match map_r_m {
            Some(r) => (
                Growth::At(r),
                format!(
                    "keep-outs grown by r = {r:.1} m (as asked, --map-r-m) plus the rover footprint"
                ),
            ),
            None => (
                Growth::AtTheMoment,
                format!(
                    "each keep-out grown by the r the rover had where its path came closest to it, \
                     plus the rover footprint (light grey: never within {:.0} m of the path, not \
                     grown)",
                    REACH_M
                ),
            ),
        };
        let passages = passages_svg(scenario, o)?;
        let boxes = if passages.is_some() && map_r_m.is_none() {
            "; the lettered boxes are the zoomed panels of the next figure"
        } else {
            ""
        };
        out.push((
            format!("{name}.{strategy}.map.svg"),
            format!(
                "{strategy} on the map: {how}; the route, the driven path, each sol's end with its \
                 uncertainty disc, faults in red{boxes} (paper 000 Fig. 3-4)."
            ),
            route_map_svg(scenario, o, growth, None)?,
        ));
        if let Some(svg) = passages {
            out.push((
                format!("{name}.{strategy}.passages.svg"),
                format!(
                    "{strategy} at each passage it drove through, zoomed: the keep-outs grown by the \
                     r it had at its closest pass (the dot, with its uncertainty disc) plus the rover \
                     footprint, so a passage is drawn as open or closed as it was when the rover got \
                     there."
                ),
                svg,
            ));
        }
        // A zoom on each fault, at the fault's own r (paper 000 Fig. 4 shows sol 385's).
        let footprint_m = scenario.settings.grid.footprint_radius_m;
        for s in &o.sols {
            let Some(f) = &s.fault else { continue };
            let r_fault = map_r_m.unwrap_or(f.uncertainty_m);
            out.push((
                format!("{name}.{strategy}.fault-sol{}.map.svg", s.sol),
                format!(
                    "{strategy}: the {} of sol {} after {:.1} m, at r = {:.2} m: the keep-outs \
                     grown by r = {r_fault:.2} m plus the footprint, the path and the disc at \
                     the end of the drive.",
                    f.kind.name(),
                    s.sol,
                    f.after_m,
                    f.uncertainty_m
                ),
                route_map_svg(
                    scenario,
                    o,
                    Growth::At(r_fault),
                    Some(fault_window(f.position_m, r_fault, footprint_m)),
                )?,
            ));
        }
        if let Some(svg) = sol_plans_gantt_svg(&format!("{name}: {strategy} sol plans (LMST)"), o)?
        {
            out.push((
                format!("{name}.{strategy}.plans.svg"),
                format!(
                    "{strategy}: each sol's plan as executed (LMST), the co-processor (HBS) \
                     chain on its own row below the sol it belongs to."
                ),
                svg,
            ));
        }
    }
    Ok(out
        .into_iter()
        .map(|(file, caption, svg)| RunFigure { file, caption, svg })
        .collect())
}
