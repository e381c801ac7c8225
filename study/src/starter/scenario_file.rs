//! The starter's scenario file ([`Starter::scenario_toml`]): every field written with a comment
//! giving its meaning, unit and default, optional settings as commented-out lines at their
//! defaults (the simulator's own, read from its settings structs).

use super::{DRIVE_RATE_M_PER_H, DRIVE_WINDOW_LMST, GRID_RESOLUTION_M, Starter, num};

impl Starter {
    /// The scenario file (TOML), every field commented, with the map's rasters in folder
    /// `map_dir` and the zones in `zones_file` (both relative to the scenario file).
    #[must_use]
    pub fn scenario_toml(&self, map_dir: &str, zones_file: &str, map_seed: u64) -> String {
        let o = &self.options;
        let rover = sim::rover::autonav::RoverSettings::default();
        let grid = sim::grid::planning_grid::GridSettings::default();
        let unc = sim::rover::uncertainty::UncertaintyModel::default();
        let ops = sim::operations::policy::OperationsRules::default();
        let team = sim::operations::ops_calendar::TeamRules::for_mission(
            sim::time::mars_time::MARS_2020,
            2020..=2020,
        );
        let pt = |h: f64| {
            let minutes = (h * 60.0).round() as u32;
            format!("{:02}:{:02}", minutes / 60, minutes % 60)
        };
        let first = *self.sols.start();
        let last = *self.sols.end();
        let mut t = String::new();
        let mut line = |s: &str| {
            t.push_str(s);
            t.push('\n');
        };
        line(&format!(
            "# solsim scenario {:?}: a traverse of your own.\n# Route from {}.",
            o.name, o.source
        ));
        line("# Check it, then run every strategy on it:");
        line("#   solsim validate THIS_FILE");
        line("#   solsim compare THIS_FILE");
        line(
            "# Every field has a comment: its meaning, unit and default. A line `# key = value` is an",
        );
        line(
            "# optional setting shown at its default: remove the `# ` to change it. The reference is",
        );
        line("# README.md, \"Input formats\"; `solsim schema scenario` prints the JSON Schema.");
        line("#");
        line("# Where each number comes from:");
        line(
            "# - the route: the track's points, planetocentric east longitude and north latitude in",
        );
        line(
            "#   degrees on the IAU 2015 Mars sphere, projected into map metres with the map's CRS (the",
        );
        line(
            "#   Jezero equirectangular projection, true to scale at 18.4663° N; solsim's GIS outputs use",
        );
        line("#   the same);");
        line(&format!(
            "# - the map: procedural ({map_dir}/recipe.toml, seed {map_seed}), not a registration to"
        ));
        line(&format!(
            "#   orbital images, {} m wider than the route on every side;",
            o.map_margin_m
        ));
        line(
            "# - the rover's speed and drive window: the public record of Perseverance's sols 379-409",
        );
        line("#   (README.md, \"The historic record\");");
        line(
            "# - the calendar: computed from Mars time and the team's rules (sim::operations::ops_calendar);",
        );
        line("# - everything else: solsim's defaults.");
        line("");
        line("# Scenario name: outputs go to solsim-out/<name>/.");
        line(&format!("name = {:?}", o.name));
        line("# One line printed above the compare table.");
        line(&format!(
            "description = {:?}",
            format!(
                "{} waypoints, {:.0} m, from {}",
                self.route_m.len(),
                self.route_length_m,
                o.source
            )
        ));
        line("# Seed of run 0: the world's draws (heading errors, VO failures, slip, localization");
        line("# errors). `compare --runs N` and `sweep` run indices 0..N from it.");
        line(&format!("seed = {}", o.seed));
        line("");
        line("[map]");
        line(
            "# The map's three rasters, paths relative to this file (GeoTIFF, the map's CRS in their",
        );
        line("# GeoKeys). Orthoimage, 8-bit: what the image localizers match.");
        line(&format!("appearance = \"{map_dir}/appearance.tif\""));
        line("# Heights: 16-bit centimetres above dem_datum_m (or 32-bit float metres).");
        line(&format!("dem = \"{map_dir}/dem.tif\""));
        line(
            "# Terrain class per pixel: 1 sand, 2 soil, 3 bedrock (VO failures, slip, AutoNav costs).",
        );
        line(&format!("terrain = \"{map_dir}/terrain.tif\""));
        line(
            "# Keep-in and keep-out zones: GeoJSON FeatureCollection of Polygons in map metres, each",
        );
        line(
            "# with properties kind (\"keep_in\" or \"keep_out\") and name. Keep-outs grow, keep-ins",
        );
        line(
            "# shrink, by the rover's position uncertainty r; where they meet AutoNav faults NO_PATH.",
        );
        line(&format!("zones = {zones_file:?}"));
        line("# Metres: the DEM's heights are centimetres above this (default 0).");
        line("# dem_datum_m = 0.0");
        line("");
        line("[grid]");
        line(&format!(
            "# Cell of AutoNav's planning grid, metres (default {}; {} searches a quarter of the cells).",
            num(grid.resolution_m),
            num(GRID_RESOLUTION_M)
        ));
        line(&format!("resolution_m = {}", num(GRID_RESOLUTION_M)));
        line("# Steepest slope AutoNav drives, degrees; steeper cells are hazards (default 25).");
        line(&format!("max_slope_deg = {}", num(grid.max_slope_deg)));
        line("");
        line("[rover]");
        line("# Rover radius for clearance from hazards and zones, metres (default 1.5).");
        line(&format!(
            "footprint_radius_m = {}",
            num(grid.footprint_radius_m)
        ));
        line(&format!(
            "# AutoNav driving speed, metres per hour (default {}): {DRIVE_RATE_M_PER_H} is the record's",
            num(rover.drive_rate_m_per_h)
        ));
        line("# mean speed over sols 379-409.");
        line(&format!("drive_rate_m_per_h = {DRIVE_RATE_M_PER_H}"));
        line("# Simulation step along the drive, metres (default 2).");
        line(&format!("step_m = {}", num(rover.step_m)));
        line(&format!(
            "# Metres: a waypoint counts as reached this close (default {}).",
            num(rover.waypoint_tolerance_m)
        ));
        line(&format!(
            "# waypoint_tolerance_m = {}",
            num(rover.waypoint_tolerance_m)
        ));
        line(&format!(
            "# Metres: AutoNav keeps this far from the map's edge (default {}).",
            num(rover.edge_buffer_m)
        ));
        line(&format!("# edge_buffer_m = {}", num(rover.edge_buffer_m)));
        line("");
        line("[errors]");
        line(
            "# The true world's errors: \"calibrated\" (VO failures calibrated to sols 717-719) or",
        );
        line(
            "# \"stress\" (larger errors than the uncertainty disc is sized for). Default \"calibrated\".",
        );
        line("model = \"calibrated\"");
        line("");
        line("[uncertainty]");
        line("# Growth of the uncertainty radius r, metres per metre driven with Visual Odometry");
        line(&format!("# (default {}: paper 000's 5 %).", num(unc.k_vo)));
        line(&format!("k_vo = {}", num(unc.k_vo)));
        line(&format!(
            "# The same without VO, metres per metre (default {}).",
            num(unc.k_novo)
        ));
        line(&format!("k_novo = {}", num(unc.k_novo)));
        line(&format!(
            "# Metres: r at the start (default {}).",
            num(unc.initial_margin_m)
        ));
        line(&format!(
            "# initial_margin_m = {}",
            num(unc.initial_margin_m)
        ));
        line("");
        line("[onboard_localization]");
        line(
            "# How `onboard` and `extension+onboard` localize after a drive: \"statistical\" (draws the",
        );
        line(
            "# published accuracy; fast, the default), \"census\", \"ncc\" or \"mi\" (image matching on",
        );
        line("# the map), \"particle\" or \"ekf\".");
        line("localizer = \"statistical\"");
        line("# Metres added to the localizer's sigma to give r after an onboard fix (default 1).");
        line("# operator_margin_m = 1.0");
        line("");
        line("[operations]");
        line(
            "# Start of the drive window, LMST \"HH:MM\" (default 11:00-15:00): the record's median",
        );
        line("# window of sols 379-409.");
        line(&format!("drive_start_lmst = {:?}", DRIVE_WINDOW_LMST.0));
        line("# End of the drive window, LMST \"HH:MM\".");
        line(&format!("drive_end_lmst = {:?}", DRIVE_WINDOW_LMST.1));
        let imaging_s = sim::operations::sol_plan::SolPlanSettings::default().imaging_s;
        line(&format!(
            "# Seconds of imaging after a drive, before its data can go down (default {imaging_s})."
        ));
        line(&format!("post_drive_imaging_s = {imaging_s}"));
        line(&format!(
            "# Sols: most drive sols one ground or onboard plan commands (default {}).",
            ops.max_drive_sols_per_plan
        ));
        line(&format!(
            "# max_drive_sols_per_plan = {}",
            ops.max_drive_sols_per_plan
        ));
        line(&format!(
            "# Sols of breadcrumbs one extension plan lays (default {}).",
            ops.extension_plan_sols
        ));
        line(&format!(
            "# extension_plan_sols = {}",
            ops.extension_plan_sols
        ));
        line(&format!(
            "# Sols ground drives blind by opportunistic extension, 0 for none (default {}).",
            ops.ground_extension_sols
        ));
        line(&format!(
            "# ground_extension_sols = {}",
            ops.ground_extension_sols
        ));
        line(&format!(
            "# Plans ground looks ahead when it chooses which sols to drive, 1 to 12 (default {}).",
            ops.ground_lookahead_plans
        ));
        line(&format!(
            "# ground_lookahead_plans = {}",
            ops.ground_lookahead_plans
        ));
        line(&format!(
            "# Plans stop short of a passage their predicted r would close (default {}).",
            ops.preemptive_shortening
        ));
        line(&format!(
            "# preemptive_shortening = {}",
            ops.preemptive_shortening
        ));
        line(&format!(
            "# Metres: plans shorten a drive when predicted r comes this close to a passage's clearance (default {}).",
            num(ops.passage_margin_m)
        ));
        line(&format!(
            "# passage_margin_m = {}",
            num(ops.passage_margin_m)
        ));
        line("");
        line("[calendar]");
        line(
            "# Uplinks, weekend plans and restricted sols computed from Mars time and the team's rules",
        );
        line("# in Pasadena for these sols of Mars 2020 (the only mission solsim knows).");
        line("mission = \"mars2020\"");
        line(&format!(
            "# LMST \"HH:MM\": a sol's plan must be aboard by then, less the light time (default {}).",
            team.uplink_lmst.lmst()
        ));
        line(&format!("# uplink_lmst = {:?}", team.uplink_lmst.lmst()));
        line(&format!(
            "# Minutes of one-way light time allowed for (default {}).",
            num(team.light_time_min)
        ));
        line(&format!("# light_time_min = {}", num(team.light_time_min)));
        line(&format!(
            "# LMST \"HH:MM\" of the relay pass that takes a sol's data down (default {}).",
            team.relay_pass_lmst.lmst()
        ));
        line(&format!(
            "# relay_pass_lmst = {:?}",
            team.relay_pass_lmst.lmst()
        ));
        line(&format!(
            "# Hours from the pass to the data on the ground, besides light time (default {}).",
            num(team.relay_latency_h)
        ));
        line(&format!(
            "# relay_latency_h = {}",
            num(team.relay_latency_h)
        ));
        line(&format!(
            "# Pasadena \"HH:MM\": the earliest and latest start of a planning shift (default {}, {}).",
            pt(team.shift_earliest_start_pt_h),
            pt(team.shift_latest_start_pt_h)
        ));
        line(&format!(
            "# shift_earliest_start_pt = {:?}",
            pt(team.shift_earliest_start_pt_h)
        ));
        line(&format!(
            "# shift_latest_start_pt = {:?}",
            pt(team.shift_latest_start_pt_h)
        ));
        line(&format!(
            "# Hours a planning shift takes (default {}).",
            num(team.shift_hours)
        ));
        line(&format!("# shift_hours = {}", num(team.shift_hours)));
        line("# Days without a shift besides weekends and US federal holidays, \"YYYY-MM-DD\".");
        line("# holidays = []");
        line("");
        line(
            "# Optional: [study_segment] with from_sol and distance_m times every strategy over that",
        );
        line(
            "# stretch of the route; [science] plans observations; [[expect]] entries are checked by",
        );
        line("# `solsim regress` (README.md, \"Input formats\").");
        line("");
        line("[route]");
        line(
            "# Waypoints in map metres (x east, y north of the map's origin), the start first; each",
        );
        line("# line's comment is the track point it came from.");
        line("waypoints = [");
        for (p, ll) in self.route_m.iter().zip(&self.route_lonlat_deg) {
            line(&format!(
                "  [{}, {}],  # {:.9}° E {:.9}° N",
                num(p[0]),
                num(p[1]),
                ll[0],
                ll[1]
            ));
        }
        line("]");
        line("");
        line(&format!(
            "# One [[sols]] entry per sol, consecutive: sols {first}-{last}, one per 100 m of route and 3 more"
        ));
        line(
            "# (at least a week). Each may set uplink, restricted, downlink (false: no relay pass that",
        );
        line(
            "# sol), drive (false: a science stop) and note; a typed value overrides the calendar's.",
        );
        for sol in self.sols.clone() {
            line(&format!("[[sols]]\nsol = {sol}"));
        }
        t
    }
}
