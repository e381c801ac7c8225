//! What `solsim slip-profile` writes beside the measured [`SlipProfile`]: the provenance
//! lines of its CSV and the printed table.

use maps::TerrainClass;
use sim::rover::physics::RoverBody;
use sim::rover::slip_profile::{ProfileHeading, ProfileSettings, SlipProfile};

/// What produced a table: the comment lines of its CSV.
#[must_use]
pub fn provenance(settings: &ProfileSettings) -> String {
    let body = RoverBody::default();
    format!(
        "solsim slip-profile {}: the rapier rover (six wheels, {:.1} kg, wheel radius {} m, width {} m) \
         driving at {} m/s for {} s per run (slip over the second half)\n\
         soils: sim::rover::physics::soil (sand: Wong dry sand; soil: Wong sandy loam; bedrock: rigid, mu 0.8)\n\
         slip = 1 - progress / commanded; closed_form_slip = the same soil model's steady state (up and down only)",
        // Every crate of the workspace carries solsim's version.
        env!("CARGO_PKG_VERSION"),
        body.mass_kg(),
        body.wheel_radius_m,
        body.wheel_width_m,
        settings.speed_m_per_s,
        settings.duration_s,
    )
}

/// The text table: slip (%) per slope, one column per terrain class and heading.
#[must_use]
pub fn table(profile: &SlipProfile) -> String {
    let mut s = String::from("slip % by slope (up / cross / down); 100 = no progress\n");
    s.push_str("slope_deg");
    for t in TerrainClass::ALL {
        s.push_str(&format!("  {:>22}", t.name()));
    }
    s.push('\n');
    let slopes: Vec<f64> = profile
        .curve(TerrainClass::Sand, ProfileHeading::Up)
        .iter()
        .map(|p| p.0)
        .collect();
    for (k, slope) in slopes.iter().enumerate() {
        s.push_str(&format!("{slope:>9}"));
        for t in TerrainClass::ALL {
            let cell: Vec<String> = ProfileHeading::ALL
                .iter()
                .map(|&h| {
                    let v = profile.curve(t, h).get(k).map_or(f64::NAN, |p| p.1);
                    format!("{:>6.1}", 100.0 * v.min(1.0))
                })
                .collect();
            s.push_str(&format!("  {}", cell.join(" ")));
        }
        s.push('\n');
    }
    s
}
