//! Every integration test of the `solsim` package, in one test binary.
//!
//! Each file in `tests/` is a module here (`tests/issue_<N>_<symptom>.rs` stays its own file);
//! one binary instead of one per file keeps a clean `cargo test` to a fraction of the disk and
//! link time (52 binaries of ~50 MB each filled a CI disk). Run one file's tests with
//! `cargo test --test integration <file name>::`, e.g. `cargo test --test integration cli::`.
//!
//! Three files stay binaries of their own (`[[test]]` entries in Cargo.toml), because they
//! measure the whole process: `fuzz_parsers` and `issue_10_fuzz_tiff_tag_allocation` install a
//! global allocator that counts every allocation, and `issue_10_fuzz_toml_memory` reads the
//! peak memory of every child the process has run.

mod common;

mod browser_harness;
mod calibration_drive_rate;
mod calibration_vo;
mod cli;
mod compare_runs;
mod completions_man;
mod documented_defaults;
mod ekf_filterpy;
mod errors_section;
mod figures;
mod filter_localizers;
mod hbs_chain;
mod issue_10_absurd_values;
mod issue_10_atomic_output_set;
mod issue_10_error_lines;
mod issue_10_fuzz_campaign_tolerance_overflow;
mod issue_10_fuzz_keep_in_union_time;
mod issue_10_fuzz_sol_overflow;
mod issue_10_fuzz_waypoint_on_map_edge;
mod issue_10_memory_budget;
mod issue_10_package_map_edge;
mod issue_10_special_files;
mod issue_11_slurm;
mod issue_12_drive_duration_rounding;
mod issue_13_gantt_lmst_axis;
mod issue_13_gis_gdal;
mod issue_13_json_outputs;
mod issue_13_junit_times;
mod issue_13_no_debug_text;
mod issue_13_progress;
mod issue_13_report_edited_zones;
mod issue_13_report_out_keeps_run;
mod issue_13_validate_nonsense;
mod issue_14_sweep_half_written_manifest;
mod issue_16_unreachable_drive_bound;
mod issue_26_absurd_rates;
mod issue_26_broken_pipe;
mod issue_26_check_then_open_race;
mod issue_26_crater_recipe_cap;
mod issue_26_disk_full_final_step;
mod issue_26_foreign_file_excerpts;
mod issue_26_fuzz_sweep_dirs;
mod issue_26_geojson_shapes;
mod issue_26_junit_control_chars;
mod issue_26_keep_in_sliver;
mod issue_26_lmst_strict;
mod issue_26_long_route_progress;
mod issue_26_number_printing;
mod issue_26_resume_trusts_manifest;
mod issue_26_scenario_name_dots;
mod issue_26_slurm_script_injection;
mod issue_26_sweep_dir_lock;
mod issue_26_sweep_special_files;
mod issue_26_symlinked_chunks_dir;
mod issue_26_terminal_escape;
mod issue_27_calendar_fields;
mod issue_27_ground_skips_driven_sols;
mod issue_28_broken_pipe_completions_man;
mod issue_28_compare_verdict;
mod issue_28_did_you_mean;
mod issue_28_gained_sol_kinds;
mod issue_28_honest_test_command;
mod issue_28_json_flags;
mod issue_28_keep_outs_at_the_moment;
mod issue_28_lost_after_goal;
mod issue_28_own_traverse;
mod issue_28_readme_figures;
mod issue_28_regress_progress;
mod issue_28_report_tables_fit;
mod issue_28_run_drive_end;
mod issue_28_strategy_lines_distinct;
mod issue_28_validate_expectation_count;
mod issue_28_whatif_settings;
mod issue_28_zones_inside_flag;
mod issue_29_architecture;
mod issue_29_architecture_check_blind_spots;
mod issue_29_library_compare;
mod issue_29_slip_profile_provenance;
mod issue_29_subnormal_historic_distance;
mod localize_cli;
mod localizer_comparison;
mod mars_time_mars24;
mod operations_rules;
mod package_cli;
mod plan_cli;
mod planner_cpsat_agreement;
mod record_import;
mod record_scenarios;
mod report_browser;
mod report_html;
mod scenario_expectations;
mod schema_files;
mod slip_aware_routing;
mod slip_profile;
mod sol_plans;
mod sweep_cli;
mod sweep_determinism;
mod sweep_parquet_pyarrow;
mod sweep_resume;
