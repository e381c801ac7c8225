//! Issue 26, finding 7: physically absurd rates and lengths passed the loaders.
//! `rover.drive_rate_m_per_h = 5e-324` drove 523-537 m in one sol with `drive_time_s: null`
//! (the rate underflowed to 0 m/s, each step's time was infinite, the drive time NaN, and a
//! NaN time budget never ran out); `rover.step_m = 5e-324` gave drive sols of 0 m. Every rate
//! and length of a scenario or campaign file now has a physical range
//! (beside each setting: `sim::rover::autonav::RoverSettings::STEP_RANGE_M`, …, and
//! `study::ranges`; README "Input formats"): 0 where it is no value, subnormals,
//! negatives, NaN, infinities and huge values are refused with the field named, and
//! `sim::Settings::validate` holds settings built in code to the same ranges.

use std::path::Path;

use crate::common::{assert_bad_input, root, scenario_copy, solsim};

fn validate(base: &str, edit: impl Fn(String) -> String) -> std::process::Output {
    let (path, _d) = scenario_copy(base, edit);
    solsim().arg("validate").arg(&path).output().expect("runs")
}

#[test]
fn a_drive_rate_of_5e_324_m_per_h_is_refused() {
    let o = validate("crater-floor-passage.toml", |t| {
        t.replace("drive_rate_m_per_h = 100.0", "drive_rate_m_per_h = 5e-324")
    });
    assert_bad_input(
        &o,
        &[
            "rover.drive_rate_m_per_h",
            "expected 1 ..= 1000 metres per hour",
            "got 5e-324",
        ],
    );
}

#[test]
fn a_step_of_5e_324_m_is_refused() {
    let o = validate("crater-floor-passage.toml", |t| {
        t.replace("step_m = 2.0", "step_m = 5e-324")
    });
    assert_bad_input(
        &o,
        &["rover.step_m", "expected 0.25 ..= 10 metres", "got 5e-324"],
    );
}

/// The flown HBS slowdown (the default, 1758.2) may be written out: the old range stopped at
/// 1000, below its own default.
#[test]
fn the_default_hbs_slowdown_may_be_written_out() {
    let o = validate("crater-floor-passage.toml", |t| {
        t.replace(
            "localizer = \"census\"",
            "localizer = \"census\"\nhbs_slowdown = 1758.2",
        )
    });
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// The mechanism, for a campaign built in code (no loader in front of it): the simulator's
/// own validation names the rate and the step, and a rate that underflows to 0 m/s drives
/// nothing, with finite times, instead of driving without a time limit.
#[test]
fn a_campaign_built_in_code_is_held_to_the_rover_ranges() {
    let scenario =
        study::Scenario::load(&root().join("scenarios/crater-floor-passage.toml")).expect("loads");
    for (field, set) in [
        (
            "rover.drive_rate_m_per_h",
            (|r: &mut sim::rover::autonav::RoverSettings, v| r.drive_rate_m_per_h = v)
                as fn(&mut sim::rover::autonav::RoverSettings, f64),
        ),
        ("rover.step_m", |r, v| r.step_m = v),
        ("rover.waypoint_tolerance_m", |r, v| {
            r.waypoint_tolerance_m = v
        }),
    ] {
        for v in [5e-324, 0.0, -1.0, f64::NAN, f64::INFINITY, 1e300] {
            let mut c = scenario.settings.clone();
            set(&mut c.rover, v);
            let e = c.validate().expect_err(&format!("{field} = {v:e}"));
            assert!(
                e.to_string().starts_with(&format!("{field}: expected ")),
                "{e}"
            );
        }
    }
    let mut s = scenario.clone();
    s.settings.rover.drive_rate_m_per_h = 5e-324;
    let outcome = s.run(sim::Strategy::Ground, s.seeds());
    for sol in &outcome.sols {
        assert_eq!(sol.distance_m, 0.0, "sol {}", sol.sol);
        assert!(sol.drive_time_s.is_finite(), "sol {}", sol.sol);
    }
}

/// A value for a field, and whether the loader must refuse it.
#[derive(Clone, Copy)]
enum Want {
    Refused,
    Accepted,
}

/// One rate or length: where it is, what else the file needs for it to be read, its range.
struct Field {
    /// `section.key`, `section[i].key`: the TOML path, as errors name it.
    path: &'static str,
    /// Other settings the field needs (`onboard_localization.localizer = "ekf"`).
    context: &'static [(&'static str, toml::Value)],
    min: f64,
    max: f64,
    /// Whether `min` and `max` themselves load (false where another field's check meets
    /// them first, e.g. `p99_error_m` > 1.05 × `mean_error_m`).
    bounds_load: bool,
}

fn field(path: &'static str, min: f64, max: f64) -> Field {
    Field {
        path,
        context: &[],
        min,
        max,
        bounds_load: true,
    }
}

/// Every rate and length a scenario holds, with the range the README documents. A field missing
/// here is caught by [`every_number_of_the_scenario_schema_is_listed`].
fn scenario_fields() -> Vec<Field> {
    let ekf: &'static [(&'static str, toml::Value)] = Box::leak(Box::new([(
        "onboard_localization.localizer",
        toml::Value::from("ekf"),
    )]));
    let statistical: &'static [(&'static str, toml::Value)] = Box::leak(Box::new([
        (
            "onboard_localization.localizer",
            toml::Value::from("statistical"),
        ),
        ("onboard_localization.p99_error_m", toml::Value::from(0.93)),
    ]));
    let georef: &'static [(&'static str, toml::Value)] = Box::leak(Box::new([(
        "map.origin_m",
        toml::Value::Array(vec![0.0.into(), 1200.0.into()]),
    )]));
    let segment: &'static [(&'static str, toml::Value)] = Box::leak(Box::new([(
        "study_segment.from_sol",
        toml::Value::from(383),
    )]));
    let coordinate = maps::zone::MAX_COORDINATE_M;
    vec![
        field("rover.drive_rate_m_per_h", 1.0, 1000.0),
        field("rover.step_m", 0.25, 10.0),
        field("rover.waypoint_tolerance_m", 0.01, 100.0),
        field("rover.footprint_radius_m", 0.0, 10.0),
        field("rover.edge_buffer_m", 0.0, 1000.0),
        field("grid.resolution_m", 0.01, 50.0),
        field("map.dem_datum_m", -100_000.0, 100_000.0),
        Field {
            context: georef,
            ..field("map.resolution_m_per_px", 0.01, 1000.0)
        },
        Field {
            context: Box::leak(Box::new([
                ("map.resolution_m_per_px", toml::Value::from(1.0)),
                georef[0].clone(),
            ])),
            ..field("map.origin_m[0]", -coordinate, coordinate)
        },
        field("route.waypoints[1][0]", -coordinate, coordinate),
        field("errors.ground_localization_sigma_m", 0.0, 1000.0),
        field("uncertainty.k_vo", 0.0, 1.0),
        field("uncertainty.k_novo", 0.0, 1.0),
        field("uncertainty.initial_margin_m", 0.0, 1000.0),
        field("operations.passage_margin_m", 0.0, 1000.0),
        field("onboard_localization.operator_margin_m", 0.0, 1000.0),
        field("onboard_localization.hbs_slowdown", 1.0, 100_000.0),
        field("onboard_localization.hbs_link_rate_kb_per_s", 1.0, 1000.0),
        Field {
            context: &statistical[..1],
            bounds_load: false,
            ..field("onboard_localization.mean_error_m", 0.01, 1000.0)
        },
        Field {
            context: &statistical[..1],
            bounds_load: false,
            ..field("onboard_localization.p99_error_m", 0.01, 1000.0)
        },
        Field {
            context: statistical,
            ..field("onboard_localization.reported_sigma_m", 0.0, 1000.0)
        },
        Field {
            context: ekf,
            ..field("onboard_localization.range_sigma_m", 0.01, 100.0)
        },
        Field {
            context: ekf,
            ..field("onboard_localization.image_resolution_m", 0.01, 100.0)
        },
        Field {
            context: Box::leak(Box::new([(
                "sols[0].historic_novo_m",
                toml::Value::from(0.0),
            )])),
            ..field("sols[0].historic_distance_m", 0.0, 10_000.0)
        },
        Field {
            bounds_load: false, // at most historic_distance_m
            ..field("sols[0].historic_novo_m", 0.0, 10_000.0)
        },
        Field {
            context: segment,
            ..field("study_segment.distance_m", 1.0, 1e8)
        },
    ]
}

/// The science fields (on `scenarios/self-reliant-campaign.toml`, which has a state-based
/// campaign as `science.campaigns[2]`).
fn science_fields() -> Vec<Field> {
    let coordinate = maps::zone::MAX_COORDINATE_M;
    vec![
        field("science.targets[0].within_m", 0.1, 1000.0),
        Field {
            bounds_load: false, // the map's extent is checked when the maps are read
            ..field("science.targets[0].position_m[0]", -coordinate, coordinate)
        },
        Field {
            bounds_load: false, // 1 m over the route is more instances than a plan holds
            ..field("science.campaigns[2].every_m", 1.0, 100_000.0)
        },
        field("science.campaigns[2].tolerance_m", 0.0, 100_000.0),
    ]
}

/// The rates and lengths of a `solsim plan` campaign file (`scenarios/plans/…`, whose
/// `activities[3]` is a drive).
fn campaign_file_fields() -> Vec<Field> {
    vec![
        Field {
            bounds_load: false, // 10 cm is shorter than the split points; 100 km too long
            ..field("activities[3].drive.length_m", 0.1, 100_000.0)
        },
        Field {
            bounds_load: false, // 225 m at 1 m/h is longer than 3 sols
            ..field("activities[3].drive.rate_m_per_h", 1.0, 1000.0)
        },
    ]
}

/// The values that probe a range: out of it (refused), its bounds (accepted).
fn probes(f: &Field) -> Vec<(f64, Want)> {
    let mut v = vec![
        (f64::NAN, Want::Refused),
        (f64::INFINITY, Want::Refused),
        (f64::NEG_INFINITY, Want::Refused),
        (1e300, Want::Refused),
        (-1e300, Want::Refused),
        (f.max * 1.5 + 1.0, Want::Refused),
        (f.min - 1.0, Want::Refused),
    ];
    if f.min > 0.0 {
        // 0 and a subnormal are no value of a positive rate or length.
        v.extend([
            (0.0, Want::Refused),
            (5e-324, Want::Refused),
            (-5e-324, Want::Refused),
            (f.min / 2.0, Want::Refused),
        ]);
    } else if f.min == 0.0 {
        v.push((-5e-324, Want::Refused));
    }
    if f.bounds_load {
        v.extend([(f.min, Want::Accepted), (f.max, Want::Accepted)]);
    }
    v
}

/// `doc` with `path` (`a.b[1].c`, `a[1][0]`) set to `value`, creating tables on the way.
fn set(doc: &mut toml::Table, path: &str, value: toml::Value) {
    let mut parts: Vec<(String, Vec<usize>)> = Vec::new();
    for part in path.split('.') {
        let (key, rest) = part.split_once('[').unwrap_or((part, ""));
        let indices = rest
            .split(['[', ']'])
            .filter(|s| !s.is_empty())
            .map(|s| s.parse().expect("index"))
            .collect();
        parts.push((key.to_owned(), indices));
    }
    let mut table = doc;
    let last = parts.len() - 1;
    for (k, (key, indices)) in parts.into_iter().enumerate() {
        let mut slot = table
            .entry(key)
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        for i in indices {
            slot = &mut slot.as_array_mut().expect("array")[i];
        }
        if k == last {
            *slot = value;
            return;
        }
        table = slot.as_table_mut().expect("table");
    }
}

/// Loads `base` with each field set to each probe, through `load` (the library loader: no maps
/// are read, so the sweep stays fast), and checks refused values name the field.
fn sweep(base: &str, fields: &[Field], load: impl Fn(&Path, &str) -> Result<(), String>) -> usize {
    let path = root().join(base);
    let text = std::fs::read_to_string(&path).expect("read");
    let doc: toml::Table = text.parse().expect("TOML");
    let mut checked = 0;
    for f in fields {
        for (v, want) in probes(f) {
            let mut d = doc.clone();
            for (p, c) in f.context {
                set(&mut d, p, c.clone());
            }
            set(&mut d, f.path, toml::Value::Float(v));
            let edited = toml::to_string(&d).expect("serialize");
            let got = load(&path, &edited);
            match (want, got) {
                (Want::Refused, Err(e)) => {
                    // A coordinate may be named by its point (`position_m`, not `position_m[0]`).
                    let point = f.path.rsplit_once('[').map_or(f.path, |(p, _)| p);
                    assert!(
                        e.contains(&format!(": {}: expected ", f.path))
                            || f.path.ends_with(']')
                                && e.contains(&format!(": {point}: expected ")),
                        "{} = {v:e}: the error does not name the field: {e}",
                        f.path
                    );
                    assert!(!e.contains('\n'), "{e}");
                }
                (Want::Refused, Ok(())) => panic!("{} = {v:e} was accepted", f.path),
                (Want::Accepted, Err(e)) => panic!("{} = {v:e} was refused: {e}", f.path),
                (Want::Accepted, Ok(())) => {}
            }
            checked += 1;
        }
    }
    checked
}

fn load_scenario(path: &Path, text: &str) -> Result<(), String> {
    study::scenario::ScenarioSpec::from_toml_str(path, text)
        .map(drop)
        .map_err(|e| e.to_string())
}

#[test]
fn every_scenario_rate_and_length_refuses_absurd_values_with_the_field_named() {
    let n = sweep(
        "scenarios/crater-floor-passage.toml",
        &scenario_fields(),
        load_scenario,
    );
    let m = sweep(
        "scenarios/self-reliant-campaign.toml",
        &science_fields(),
        load_scenario,
    );
    assert!(n + m > 250, "{n} + {m} cases");
}

#[test]
fn every_campaign_file_rate_and_length_refuses_absurd_values_with_the_field_named() {
    let n = sweep(
        "scenarios/plans/self-reliant-campaign.toml",
        &campaign_file_fields(),
        |path, text| {
            study::CampaignFile::from_toml_str(path, text)
                .map(drop)
                .map_err(|e| e.to_string())
        },
    );
    assert!(n > 15, "{n} cases");
}

/// The lists above cover the format: every number of the scenario schema whose name is a rate
/// or a length (`_m`, `_m_per_h`, `_m_per_px`, `_kb_per_s`, `k_vo`, `k_novo`, `hbs_slowdown`)
/// is one of them, except the `[[expect]]` ranges (expected outcomes, not parameters).
#[test]
fn every_number_of_the_scenario_schema_is_listed() {
    let schema = study::schema::scenario();
    let mut names = Vec::new();
    collect_numbers(&schema, &schema, "", &mut names);
    let listed: Vec<String> = scenario_fields()
        .iter()
        .chain(&science_fields())
        .map(|f| {
            f.path
                .rsplit('.')
                .next()
                .expect("key")
                .split('[')
                .next()
                .expect("key")
                .to_owned()
        })
        .collect();
    let rate_or_length = |n: &str| {
        n.ends_with("_m")
            || n.contains("_m_per_")
            || n.ends_with("_kb_per_s")
            || n.ends_with("_m_per_px")
            || matches!(n, "k_vo" | "k_novo" | "hbs_slowdown" | "waypoints")
    };
    let mut missing: Vec<&String> = names
        .iter()
        .filter(|n| rate_or_length(n) && !listed.contains(n))
        .collect();
    missing.sort();
    missing.dedup();
    assert!(
        missing.is_empty(),
        "rates or lengths without a case: {missing:?}"
    );
    assert!(names.len() > 30, "{names:?}");
}

/// Property names under which the schema has a number (`"type": "number"`), outside the
/// `[[expect]]` entries.
fn collect_numbers(
    root: &serde_json::Value,
    node: &serde_json::Value,
    name: &str,
    out: &mut Vec<String>,
) {
    use serde_json::Value;
    match node {
        Value::Object(map) => {
            if let Some(Value::String(r)) = map.get("$ref") {
                if r.contains("Expectation") {
                    return;
                }
                let key = r.rsplit('/').next().expect("ref");
                if let Some(def) = root["$defs"].get(key) {
                    collect_numbers(root, def, name, out);
                }
            }
            let is_number = |t: &Value| match t {
                Value::String(s) => s == "number",
                Value::Array(a) => a.iter().any(|x| x == "number"),
                _ => false,
            };
            if map.get("type").is_some_and(is_number) && !name.is_empty() {
                out.push(name.to_owned());
            }
            for (k, v) in map {
                match k.as_str() {
                    "properties" => {
                        for (p, s) in v.as_object().expect("properties") {
                            if p != "expect" {
                                collect_numbers(root, s, p, out);
                            }
                        }
                    }
                    "$defs" | "$ref" => {}
                    _ => collect_numbers(root, v, name, out),
                }
            }
        }
        Value::Array(items) => {
            for v in items {
                collect_numbers(root, v, name, out);
            }
        }
        _ => {}
    }
}
