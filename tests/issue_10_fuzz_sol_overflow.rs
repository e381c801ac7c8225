//! Issue 10, found by `tests/fuzz_parsers.rs`: a scenario whose `[[sols]]` entry has
//! `sol = 4294967295` (`u32::MAX`) followed by another entry panicked while checking that sols
//! are consecutive (`study/src/scenario.rs`: `attempt to add with overflow` on
//! `raw.sols[i - 1].sol + 1`; in a release build the sum wrapped to 0 and the error asked for
//! "sol 0"). The check now runs in `u64`: the file is refused with one error naming
//! `sols[1].sol` and the sol it expected.

use std::path::Path;

use study::ScenarioError;
use study::scenario::ScenarioSpec;

fn bundled(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenarios")
        .join(name);
    std::fs::read_to_string(&path).expect("bundled scenario")
}

#[test]
fn a_sol_number_of_u32_max_before_another_sol_is_an_error_not_a_panic() {
    // A typed calendar: the next sol would overflow.
    let text = bundled("crater-floor-717.toml").replace("sol = 717\n", "sol = 4294967295\n");
    let path = Path::new("scenarios/crater-floor-717.toml");
    let err = ScenarioSpec::from_toml_str(path, &text).expect_err("sols not consecutive");
    match &err {
        ScenarioError::Field {
            field, expected, ..
        } => {
            assert_eq!(field, "sols[1].sol", "{err}");
            assert!(expected.contains("4294967296"), "{err}");
        }
        other => panic!("expected a field error, got {other}"),
    }
    // A calendar computed from Mars time: tests/issue_27_calendar_fields.rs.
}

#[test]
fn consecutive_sols_still_load() {
    let text = bundled("sol717-719.toml");
    let path = Path::new("scenarios/sol717-719.toml");
    let spec = ScenarioSpec::from_toml_str(path, &text).expect("bundled scenario is valid");
    assert_eq!(spec.calendar.sols.len(), 3);
}
