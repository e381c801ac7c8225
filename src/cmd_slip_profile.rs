//! `solsim slip-profile`: measure the slip-versus-slope tables with the rapier rover and write
//! them with their figure (provenance and table: [`study::slip_profile`]).

use std::io::Write;
use std::path::PathBuf;

use sim::rover::physics::RoverBody;
use sim::rover::slip_profile::{ProfileSettings, SlipProfile};
use study::slip_profile::{provenance, table};

use crate::progress::Progress;
use outputs::output_set::OutputSet;

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
    let svg = outputs::figures::slip_profile_svg(&profile)?;
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
