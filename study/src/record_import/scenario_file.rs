//! The text of an imported scenario: the scenario file, every number with where it comes from
//! ([`ScenarioFile`]), and the procedural map's recipe ([`recipe_toml`]).

use std::fmt::Write as _;

use maps::MapAnchor;
use sim::operations::sol_plan::SolPlanSettings;

use super::polyline::round1;
use super::{ImportOptions, ImportedSol, file_names};

/// The procedural map's recipe of an import: `size_m` (width, height) at `resolution` metres a
/// pixel, the recorded path's first point `first_lonlat` at its map position `anchor`.
pub(super) fn recipe_toml(
    opts: &ImportOptions,
    size_m: [f64; 2],
    resolution: f64,
    anchor: &MapAnchor,
    first_lonlat: [f64; 2],
) -> String {
    let (first, last) = (*opts.sols.start(), *opts.sols.end());
    let [width_m, height_m] = size_m;
    let width_px = (width_m / resolution).ceil() as usize;
    let height_px = (height_m / resolution).ceil() as usize;
    let mut recipe = String::new();
    let _ = writeln!(
        recipe,
        "# Procedural stand-in for the ground around sols {first}-{last} of the record (a modelling"
    );
    let _ = writeln!(
        recipe,
        "# choice: the record has no map). Written by `solsim record import`."
    );
    let _ = writeln!(
        recipe,
        "dem_datum_m = 0.0\n\n[terrain]\nseed = {}",
        opts.seed
    );
    let _ = writeln!(recipe, "width_px = {width_px}\nheight_px = {height_px}");
    let _ = writeln!(
        recipe,
        "geo = {{ origin_m = [0.0, {}], resolution_m_per_px = {resolution} }}",
        round1(height_px as f64 * resolution)
    );
    let _ = writeln!(
        recipe,
        "base_height_m = 120.0\nrelief_m = 12.0\ncrater_density_per_km2 = 1.5\ncrater_radius_min_m = 8.0\ncrater_radius_max_m = 30.0\nridge_count = 2\nridge_height_m = 2.0\nsand_fraction = 0.12\nbedrock_fraction = 0.30\nsun_azimuth_deg = 250.0\nsun_elevation_deg = 35.0"
    );
    let _ = writeln!(
        recipe,
        "\n# The recorded path's first point, {:.8}° E {:.8}° N, at its map position.",
        first_lonlat[0], first_lonlat[1]
    );
    let _ = writeln!(
        recipe,
        "[georeference]\nanchor_m = [{}, {}]\nlon_deg = {}\nlat_deg = {}",
        anchor.anchor_m[0], anchor.anchor_m[1], anchor.lon_deg, anchor.lat_deg
    );

    recipe
}

/// What an import's scenario file says, and where each number comes from.
pub(super) struct ScenarioFile<'a> {
    /// The record's layer name.
    pub(super) layer_name: &'a str,
    /// The import's options.
    pub(super) opts: &'a ImportOptions,
    /// The sols, imported.
    pub(super) sols: &'a [ImportedSol],
    /// What the record held besides plain drives.
    pub(super) findings: &'a [String],
    /// The record's mean speed, m/h, and the metres, hours and drives it is measured over.
    pub(super) drive_rate: (f64, f64, f64, usize),
    /// The median drive window of the range, LMST.
    pub(super) drive_window: (String, String),
    /// The route, map metres.
    pub(super) waypoints: &'a [[f64; 2]],
}

impl ScenarioFile<'_> {
    /// The scenario file (TOML): a header saying where each number comes from, the settings,
    /// one `[[sols]]` entry per sol and an `[[expect]]` per sol of the record.
    pub(super) fn toml(&self) -> String {
        let (opts, sols, findings) = (self.opts, self.sols, self.findings);
        let (first, last) = (*opts.sols.start(), *opts.sols.end());
        let (drive_rate, metres, hours, n) = self.drive_rate;
        let (default_start, default_end) = &self.drive_window;
        let waypoints = self.waypoints;
        let drove: Vec<u32> = sols
            .iter()
            .filter(|x| x.distance_m > 0.0)
            .map(|x| x.sol)
            .collect();
        let total_drive: f64 = sols.iter().map(|x| x.distance_m).sum();
        let mut t = String::new();
        // The header: where each number comes from.
        let header = [
            format!(
                "# Sols {first}-{last} replayed from the public record of Perseverance's drives: NASA's"
            ),
            format!(
                "# Mars 2020 MMGIS layer {} (data/m20/M20_traverse.json). Written by",
                self.layer_name
            ),
            format!(
                "# `solsim record import --sols {first}-{last}`. {} drive sols, {total_drive:.1} m.",
                drove.len()
            ),
            "#\n# Where each number comes from:".to_owned(),
            "# - historic input (the record): which sols drove; each sol's distance (historic_source says".to_owned(),
            "#   whether it is the record's length or paper 000's odometry); each drive's window in LMST".to_owned(),
            "#   from the spacecraft clock (Mars24); the route, the recorded path in map metres (Jezero".to_owned(),
            format!(
                "#   equirectangular CRS), on for {:.0} m past the range along the record's later drives.",
                opts.route_beyond_m
            ),
            "# - historic input (paper 000): the odometry it quotes, a NO_PATH fault, a sol without a relay".to_owned(),
            "#   pass; metres without VO derived from the radii it gives (historic_novo_m).".to_owned(),
            "# - historic science stops: idle sols of the record the computed calendar does not explain".to_owned(),
            "#   (drive = false).".to_owned(),
            "# - computed: the calendar ([calendar]: Mars time and the team's rules, sim::operations::ops_calendar).".to_owned(),
            "# - measured: each drive's speed, its distance over its window (the AutoNav rate of that sol for"
                .to_owned(),
            format!("#   every strategy); their mean, {drive_rate} m/h = {metres:.1} m over {hours:.2} h of the {n} drives with a whole"),
            "#   window, for the other sols ([rover]).".to_owned(),
            "# - modelling choice: the procedural map and the passages (keep-out pairs) of the zones file, by".to_owned(),
            format!(
                "#   the import rule: where the replay, run without them, is {} m into every drive sol planned from a known position, at least {} m apart,",
                opts.passage_into_sol_m, opts.passage_spacing_m
            ),
            format!(
                "#   clearance {} m; at a historic NO_PATH, 20 m past the paper's distance into the sol, closing at paper 000's radius.",
                opts.passage_clearance_m
            ),
            "# - emergent: every skip, fault, radius and sol count of the what-if strategies.".to_owned(),
            "#\n# What the record held besides plain drives:".to_owned(),
        ];
        for line in header {
            let _ = writeln!(t, "{line}");
        }
        for f in findings {
            let _ = writeln!(t, "# - {f}");
        }
        let _ = writeln!(t, "name = {:?}", opts.name);
        let _ = writeln!(
            t,
            "description = {:?}",
            format!(
                "Sols {first}-{last} from the public drive record: {} drive sols, {total_drive:.0} m",
                drove.len()
            )
        );
        let _ = writeln!(t, "seed = {}\n", opts.seed);
        let (_, zones_file, map_dir) = file_names(&opts.name);
        let _ = writeln!(
            t,
            "[map]\nappearance = \"{map_dir}/appearance.tif\"\ndem = \"{map_dir}/dem.tif\"\nterrain = \"{map_dir}/terrain.tif\"\nzones = {zones_file:?}\n"
        );
        let _ = writeln!(t, "[grid]\nresolution_m = 2.0\nmax_slope_deg = 25.0\n");
        let _ = writeln!(
            t,
            "[rover]\nfootprint_radius_m = {}\n# The record's mean speed (see the header): the AutoNav rate of sols without a window of\n# their own. Each historic drive sol drives at its own speed, its distance over its window.\ndrive_rate_m_per_h = {drive_rate}\nstep_m = 2.0\n",
            opts.footprint_radius_m
        );
        let _ = writeln!(
            t,
            "[operations]\n# The median window of the range's drives, for sols without one of their own."
        );
        let _ = writeln!(
            t,
            "drive_start_lmst = {default_start:?}\ndrive_end_lmst = {default_end:?}\npost_drive_imaging_s = {}\n",
            SolPlanSettings::default().imaging_s
        );
        let _ = writeln!(
            t,
            "[calendar]\n# Uplinks, weekend plans and restricted sols from Mars time and the team's rules.\nmission = \"mars2020\"\n"
        );
        let wp: Vec<String> = waypoints
            .iter()
            .map(|p| format!("[{}, {}]", p[0], p[1]))
            .collect();
        let _ = writeln!(t, "[route]\nwaypoints = [{}]\n", wp.join(", "));
        for x in sols {
            let _ = writeln!(t, "[[sols]]\nsol = {}", x.sol);
            if x.science_stop {
                let _ = writeln!(t, "drive = false");
            }
            if x.no_relay_pass {
                let _ = writeln!(t, "downlink = false");
            }
            let _ = writeln!(t, "historic_distance_m = {}", x.distance_m);
            if x.distance_m > 0.0 {
                if let Some(novo) = x.novo_m {
                    let _ = writeln!(t, "historic_novo_m = {novo}");
                }
                if x.no_path {
                    let _ = writeln!(t, "historic_fault = \"NO_PATH\"");
                }
                if let Some((start, end)) = &x.window {
                    if let Some(start) = start {
                        let _ = writeln!(t, "historic_drive_start_lmst = {start:?}");
                    }
                    let _ = writeln!(t, "historic_drive_end_lmst = {end:?}");
                }
                let _ = writeln!(t, "historic_source = {:?}", x.source);
            }
            if !x.note.is_empty() {
                let _ = writeln!(t, "note = {:?}", x.note);
            }
            t.push('\n');
        }
        for x in sols {
            if x.distance_m > 0.0 && !x.no_path {
                let _ = writeln!(
                    t,
                    "[[expect]]\nwhat = \"sol {}: {} m ({})\"\nstrategy = \"replay\"\nsol = {}\ndistance_m = [{}, {}]\n",
                    x.sol,
                    x.distance_m,
                    if x.source.starts_with("paper") {
                        "paper 000"
                    } else {
                        "the record"
                    },
                    x.sol,
                    round1(x.distance_m - 0.1),
                    round1(x.distance_m + 0.1)
                );
            } else if x.no_path {
                let _ = writeln!(
                    t,
                    "[[expect]]\nwhat = \"sol {}: NO_PATH ({})\"\nstrategy = \"replay\"\nsol = {}\nfault = \"NO_PATH\"\n",
                    x.sol, x.source, x.sol
                );
            } else if x.distance_m == 0.0 {
                let _ = writeln!(
                    t,
                    "[[expect]]\nwhat = \"sol {}: no drive, as the record\"\nstrategy = \"replay\"\nsol = {}\ndrove = false\n",
                    x.sol, x.sol
                );
            }
        }
        t
    }
}
