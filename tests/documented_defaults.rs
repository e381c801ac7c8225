//! Every default the README states is the default the code uses (rapier's docs drifted from its
//! `Default`; this test keeps ours honest). Each pair is (text in README.md, value in code).

use localization::onboard::{
    FLIGHT_NAVCAM_IMAGES_BYTES, FLIGHT_SIZE_MAP_BYTES, MEASURED_FLIGHT_SIZE_RUN_S, OnboardSettings,
};
use sim::grid::planning_grid::GridSettings;
use sim::localizers::{OnboardLocalizer, StatisticalLocalizer};
use sim::rover::autonav::{ProfileSlip, RoverSettings};
use sim::rover::uncertainty::UncertaintyModel;

#[test]
fn readme_defaults_match_the_code() {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md"))
        .expect("README.md");
    let rover = RoverSettings::default();
    let slip = ProfileSlip::default();
    let grid = GridSettings::default();
    let model = UncertaintyModel::default();
    let loc = StatisticalLocalizer::default();
    let stated: &[(&str, f64, f64)] = &[
        ("`k_vo` (0.05)", 0.05, model.k_vo),
        ("`k_novo` (0.50)", 0.50, model.k_novo),
        ("`initial_margin_m` (0)", 0.0, model.initial_margin_m),
        (
            "`footprint_radius_m` (default 1.5)",
            1.5,
            grid.footprint_radius_m,
        ),
        (
            "`drive_rate_m_per_h` (default 100)",
            100.0,
            rover.drive_rate_m_per_h,
        ),
        ("`step_m` (default 2)", 2.0, rover.step_m),
        ("`slip_limit` (default 0.5", 0.5, slip.slip_limit),
        ("`max_tilt_deg` (default 25)", 25.0, slip.max_tilt_deg),
        ("0.25 with the defaults", 0.25, slip.avoid_slip_above),
        (
            "`waypoint_tolerance_m` (default 2)",
            2.0,
            rover.waypoint_tolerance_m,
        ),
        ("`resolution_m` (default 1)", 1.0, grid.resolution_m),
        ("(default 25)", 25.0, grid.max_slope_deg),
        (
            "`slip_fraction` (0.12 / 0.04 / 0.02)",
            0.12,
            rover.errors.slip_fraction.sand,
        ),
        (
            "`slip_fraction` (0.12 / 0.04 / 0.02)",
            0.04,
            rover.errors.slip_fraction.soil,
        ),
        (
            "`slip_fraction` (0.12 / 0.04 / 0.02)",
            0.02,
            rover.errors.slip_fraction.bedrock,
        ),
        (
            "`slip_sigma_relative` (0.5)",
            0.5,
            rover.errors.slip_sigma_relative,
        ),
        (
            "`vo_failure` (sand 0.00316, soil 0.000316, bedrock 0.000158)",
            0.00316,
            rover.errors.vo_failure.sand,
        ),
        (
            "`vo_failure` (sand 0.00316, soil 0.000316, bedrock 0.000158)",
            0.000316,
            rover.errors.vo_failure.soil,
        ),
        (
            "`vo_failure` (sand 0.00316, soil 0.000316, bedrock 0.000158)",
            0.000158,
            rover.errors.vo_failure.bedrock,
        ),
        (
            "`heading_sigma_deg` (0.5)",
            0.5,
            rover.errors.heading_sigma_deg,
        ),
        ("`vo_scale_sigma` (0.01)", 0.01, rover.errors.vo_scale_sigma),
        (
            "`vo_noise_fraction` (0.01)",
            0.01,
            rover.errors.vo_noise_fraction,
        ),
        (
            "`ground_localization_sigma_m` (0.25)",
            0.25,
            rover.errors.ground_localization_sigma_m,
        ),
        ("`terrain_cost` (1.3 / 1 / 1)", 1.3, rover.terrain_cost.sand),
        ("`terrain_cost` (1.3 / 1 / 1)", 1.0, rover.terrain_cost.soil),
        ("`edge_buffer_m` (5)", 5.0, rover.edge_buffer_m),
        ("`mean_error_m` (0.36)", 0.36, loc.mean_error_m),
        ("`p99_error_m` (0.93)", 0.93, loc.p99_error_m),
        ("`failure_rate` (0.02)", 0.02, loc.failure_rate),
        ("`reported_sigma_m` (0.93)", 0.93, loc.reported_sigma_m),
    ];
    for (text, documented, actual) in stated {
        assert!(readme.contains(text), "README no longer states {text:?}");
        // The README prints each value to three significant figures or fewer.
        assert!(
            (documented - actual).abs() <= 1e-12 * documented.abs().max(1e-300),
            "README says {text:?} but the code default is {actual}"
        );
    }
    // The image localizers' co-processor timing.
    let onboard = OnboardSettings::default();
    assert_eq!(
        onboard.hbs.link_bytes_per_s,
        1_000.0 * study::scenario::DEFAULT_HBS_LINK_RATE_KB_PER_S
    );
    assert_eq!(loc.hbs, onboard.hbs);
    let thousands = |n: usize| {
        let s = n.to_string();
        let mut out = String::new();
        for (i, c) in s.chars().enumerate() {
            if i > 0 && (s.len() - i).is_multiple_of(3) {
                out.push(',');
            }
            out.push(c);
        }
        out
    };
    let (images, chip) = (
        thousands(FLIGHT_NAVCAM_IMAGES_BYTES),
        thousands(FLIGHT_SIZE_MAP_BYTES),
    );
    for text in [
        format!(
            "`hbs_slowdown` (image localizers and the particle filter; default {:.1})",
            onboard.hbs_slowdown
        ),
        format!("development machine, {MEASURED_FLIGHT_SIZE_RUN_S} s"),
        "(default `\"statistical\"`)".to_string(),
        // The HBS link: the default rate, and the calibrated flight sizes of what crosses it.
        format!(
            "`hbs_link_rate_kb_per_s` (default {}; 1 to 1000; 1 KB = 1000 bytes)",
            study::scenario::DEFAULT_HBS_LINK_RATE_KB_PER_S
        ),
        format!("({images} bytes: the paper gives no size"),
        format!("the orbital map chip ({chip} bytes at the 30 m search radius"),
        format!(
            "({} m minimum, {} m maximum)",
            onboard.min_search_radius_m, onboard.max_search_radius_m
        ),
    ] {
        assert!(readme.contains(&text), "README no longer states {text:?}");
    }
    // Scenario-level defaults live in study's scenario loader (`[onboard_localization]`,
    // `[operations]`); loading a scenario without them uses them.
    for text in [
        "`operator_margin_m` (1.0)",
        "(default 11:00 / 15:00",
        "`post_drive_imaging_s` (default 1800)",
    ] {
        assert!(readme.contains(text), "README no longer states {text:?}");
    }
    let rules = sim::operations::policy::OperationsRules::default();
    assert_eq!(rules.max_extension_sols, None);
    for text in [
        "`max_extension_sols` (default none".to_string(),
        format!(
            "`max_drive_sols_per_plan` (default {})",
            rules.max_drive_sols_per_plan
        ),
        format!(
            "`extension_plan_sols` (default {})",
            rules.extension_plan_sols
        ),
        format!("`passage_margin_m` (default {})", rules.passage_margin_m),
        format!(
            "`preemptive_shortening` (default {})",
            rules.preemptive_shortening
        ),
    ] {
        assert!(readme.contains(&text), "README no longer states {text:?}");
    }
}

#[test]
fn scenario_level_defaults_apply_when_fields_are_omitted() {
    // crater-floor-717.toml sets no [onboard_localization] or post-drive imaging: the defaults apply.
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/crater-floor-717.toml");
    let s = study::Scenario::load(&path).expect("loads");
    assert_eq!(s.settings.operator_margin_m, 1.0);
    assert_eq!(s.settings.sol_plan.imaging_s, 1800);
    assert_eq!(
        s.settings.rules,
        sim::operations::policy::OperationsRules::default()
    );
    match &s.settings.localizer {
        OnboardLocalizer::Statistical(l) => assert_eq!(*l, StatisticalLocalizer::default()),
        other => panic!(
            "the default localizer is the statistical one, not {}",
            other.name()
        ),
    }
    assert_eq!(s.settings.model, UncertaintyModel::default());
}

#[test]
fn the_filter_localizers_defaults_are_the_readmes() {
    let readme =
        std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md"))
            .expect("README");
    let pf = localization::particle::ParticleSettings::default();
    let ekf = localization::ekf::ParkedSettings::default();
    for text in [
        format!("`particle_count` ({}; 100 to", pf.particle_count),
        format!("`range_sigma_m` ({:.1}, Table 1", ekf.range_sigma_m),
        format!("`pass_duration_s` ({}; 60 to 3600)", ekf.pass_duration_s),
        format!("`elevation_mask_deg` ({})", ekf.elevation_mask_deg),
    ] {
        assert!(readme.contains(&text), "README no longer states {text:?}");
    }
    assert_eq!(
        ekf.image_resolution_m, None,
        "README: `image_resolution_m` (unset"
    );
}
