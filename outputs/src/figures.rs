//! Figures as SVG (plotters, no fonts needed: the SVG carries its text as `<text>` elements).
//!
//! One run (written by `solsim compare` beside its other files, and shown by `solsim report`):
//! - [`uncertainty_by_sol_svg`]: the position-uncertainty radius against sol, one line per
//!   strategy (paper 000 Fig. 2 and 5);
//! - [`metres_by_sol_svg`]: metres driven per sol, one bar per strategy;
//! - [`route_map_svg`]: one strategy's traverse on the map — zones, keep-outs grown by the r
//!   the rover had where it passed each (or a chosen r), the route, the driven path, sol-end
//!   discs and faults (paper 000 Fig. 3-4), over the whole traverse or zoomed on a window (a
//!   fault); [`passages_svg`]: zoomed panels at each passage the path went through;
//! - [`sol_plans_gantt_svg`]: each sol's executed plan as a Gantt chart, the co-processor
//!   (HBS) chain on its own row.
//!
//! A sweep (shown by `solsim report`): [`segment_sols_cdf_svg`], the distribution of the sols
//! each strategy took, and [`rates_svg`], the fault rates with their 95 % intervals.
//!
//! The rover: [`slip_profile_svg`], slip against slope per terrain class and heading.
//!
//! Every strategy has one colour in every figure ([`strategy_colour`]), and where lines of
//! several strategies can coincide one dash pattern and marker ([`strategy_dash`],
//! [`strategy_marker`]); legends sit below the plot, where they cover nothing.
//! [`run_figures()`] is the set a compare run writes beside its files and shows in its report,
//! each with its file name and caption.
//!
//! The modules: [`canvas`] (sizes, strategy styles, legends, [`FigureError`]); [`by_sol`];
//! [`gantt`]; [`mod@zone_moments`] (where each keep-out mattered, the panels and windows of the
//! maps); [`map_canvas`] (the map drawing [`route_map`] and [`passages`] share);
//! [`sweep_figures`]; [`slip_profile`]; [`mod@run_figures`].

pub mod by_sol;
pub mod canvas;
pub mod gantt;
pub mod map_canvas;
pub mod passages;
pub mod route_map;
pub mod run_figures;
pub mod slip_profile;
pub mod sweep_figures;
pub mod zone_moments;

pub use by_sol::{metres_by_sol_svg, uncertainty_by_sol_svg};
pub use canvas::{FigureError, Marker, strategy_colour, strategy_dash, strategy_marker};
pub use gantt::sol_plans_gantt_svg;
pub use passages::passages_svg;
pub use route_map::{Growth, route_map_svg};
pub use run_figures::{RunFigure, run_figures};
pub use slip_profile::slip_profile_svg;
pub use sweep_figures::{rates_svg, segment_sols_cdf_svg};
pub use zone_moments::{Panel, REACH_M, ZoneMoment, fault_window, passage_panels, zone_moments};
