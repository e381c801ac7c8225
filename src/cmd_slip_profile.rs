//! `solsim slip-profile`: measure the slip-versus-slope tables with the rapier rover and write
//! them with their figure.

use std::io::Write;
use std::path::PathBuf;

use sim::physics::RoverBody;
use sim::slip_profile::{ProfileSettings, SlipProfile};

use crate::output_set::OutputSet;
use crate::progress::Progress;

/// Arguments of `solsim slip-profile`.
#[derive(clap::Args, Debug)]
pub struct SlipProfileArgs {
    /// Output directory (a new or empty one, or an earlier slip-profile output): it receives
    /// slip_profile.csv, slip_profile.svg and slip_profile.json.
    #[arg(long, default_value = "solsim-out/slip-profile")]
    pub out: PathBuf,
    /// Slope step, degrees (0.5 to 10).
    #[arg(long, default_value_t = 2.0)]
    pub slope_step_deg: f64,
    /// Steepest slope, degrees (2 to 45).
    #[arg(long, default_value_t = 30.0)]
    pub max_slope_deg: f64,
    /// Length of each run, seconds (4 to 60); slip is measured over its second half.
    #[arg(long, default_value_t = 20.0)]
    pub duration_s: f64,
    /// Print the table as JSON instead of text.
    #[arg(long)]
    pub json: bool,
}

/// What produced a table: the comment lines of its CSV.
#[must_use]
pub fn provenance(settings: &ProfileSettings) -> String {
    let body = RoverBody::default();
    format!(
        "solsim slip-profile {}: the rapier rover (six wheels, {:.1} kg, wheel radius {} m, width {} m) \
         driving at {} m/s for {} s per run (slip over the second half)\n\
         soils: sim::physics::soil (sand: Wong dry sand; soil: Wong sandy loam; bedrock: rigid, mu 0.8)\n\
         slip = 1 - progress / commanded; closed_form_slip = the same soil model's steady state (up and down only)",
        env!("CARGO_PKG_VERSION"),
        body.mass_kg(),
        body.wheel_radius_m,
        body.wheel_width_m,
        settings.speed_m_per_s,
        settings.duration_s,
    )
}

fn check(name: &str, value: f64, lo: f64, hi: f64) -> anyhow::Result<()> {
    if value.is_finite() && (lo..=hi).contains(&value) {
        Ok(())
    } else {
        anyhow::bail!("--{name} {value}: expected {lo} to {hi}")
    }
}

/// Run `solsim slip-profile`.
///
/// # Errors
/// Bad arguments (the flag named), a refused output directory, a write that failed.
pub fn run(args: &SlipProfileArgs, stdout: &mut dyn Write) -> anyhow::Result<()> {
    check("slope-step-deg", args.slope_step_deg, 0.5, 10.0)?;
    check("max-slope-deg", args.max_slope_deg, 2.0, 45.0)?;
    check("duration-s", args.duration_s, 4.0, 60.0)?;
    OutputSet::check(&args.out)?;
    let settings = ProfileSettings {
        slope_step_deg: args.slope_step_deg,
        max_slope_deg: args.max_slope_deg,
        duration_s: args.duration_s,
        ..ProfileSettings::default()
    };
    let runs = 9 * settings.slopes_deg().len() as u64;
    let progress = Progress::new(false, "slip-profile", "runs", runs);
    let profile = SlipProfile::measure(&RoverBody::default(), &settings, &|| progress.inc())?;
    progress.finish();
    let csv = profile.to_csv(&provenance(&settings));
    let svg = crate::figures::slip_profile_svg(&profile)?;
    let json = serde_json::to_string_pretty(&profile)?;
    let set = OutputSet::begin(&args.out)?;
    set.write("slip_profile.csv", csv.as_bytes())?;
    set.write("slip_profile.svg", svg.as_bytes())?;
    set.write("slip_profile.json", json.as_bytes())?;
    set.commit()?;
    if args.json {
        writeln!(stdout, "{json}")?;
    } else {
        write!(stdout, "{}", table(&profile))?;
        writeln!(
            stdout,
            "wrote {}/slip_profile.{{csv,svg,json}}",
            args.out.display()
        )?;
    }
    Ok(())
}

/// The text table: slip (%) per slope, one column per terrain class and heading.
#[must_use]
pub fn table(profile: &SlipProfile) -> String {
    use maps::TerrainClass;
    use sim::slip_profile::ProfileHeading;
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
