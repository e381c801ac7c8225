//! The rover's slip against slope per terrain class and heading ([`slip_profile_svg`]), what
//! `solsim slip-profile` writes.

use plotters::prelude::*;

use crate::figures::canvas::{FigureError, Legend, Mark, WIDTH, plot_error, svg_with_legend};

/// The slip profile (`solsim slip-profile`): one panel per terrain class, slip (%) against
/// slope for up-, cross- and down-slope travel as measured by the rapier rover (lines), and the
/// closed-form steady slip of the same soil model for up and down (circles).
///
/// # Errors
/// When plotters cannot draw.
pub fn slip_profile_svg(
    profile: &sim::rover::slip_profile::SlipProfile,
) -> Result<String, FigureError> {
    use maps::TerrainClass;
    use sim::rover::slip_profile::ProfileHeading;
    let colour = |h: ProfileHeading| match h {
        ProfileHeading::Up => RGBColor(214, 39, 40),
        ProfileHeading::Cross => RGBColor(255, 127, 14),
        ProfileHeading::Down => RGBColor(31, 119, 180),
    };
    let mut legend: Legend = ProfileHeading::ALL
        .iter()
        .map(|&h| {
            (
                format!("{}-slope (rapier rover)", h.name()),
                Mark::Line(colour(h), 2),
            )
        })
        .collect();
    legend.push((
        "closed form, same soil (circles)".to_owned(),
        Mark::Fill(RGBColor(80, 80, 80).to_rgba()),
    ));
    let max_slope = profile.max_slope_deg().max(1.0);
    svg_with_legend(WIDTH, 380, &legend, |root| {
        let panels = root.split_evenly((1, 3));
        for (panel, terrain) in panels.iter().zip(TerrainClass::ALL) {
            let mut chart = ChartBuilder::on(panel)
                .caption(terrain.name(), ("sans-serif", 16))
                .margin(10)
                .x_label_area_size(36)
                .y_label_area_size(48)
                .build_cartesian_2d(0.0..max_slope, -20.0..105.0)
                .map_err(plot_error)?;
            chart
                .configure_mesh()
                .max_light_lines(1)
                .x_desc("slope (deg)")
                .y_desc("slip (%)")
                .draw()
                .map_err(plot_error)?;
            for h in ProfileHeading::ALL {
                let points: Vec<(f64, f64)> = profile
                    .curve(terrain, h)
                    .into_iter()
                    .map(|(x, s)| (x, 100.0 * s.clamp(-0.2, 1.05)))
                    .collect();
                chart
                    .draw_series(LineSeries::new(points, colour(h).stroke_width(2)))
                    .map_err(plot_error)?;
                let closed = profile
                    .rows
                    .iter()
                    .filter(|r| r.terrain == terrain && r.heading == h)
                    .filter_map(|r| r.closed_form_slip.map(|c| (r.slope_deg, 100.0 * c)))
                    .map(|p| Circle::new(p, 3, colour(h).filled()));
                chart.draw_series(closed).map_err(plot_error)?;
            }
        }
        Ok(())
    })
}
