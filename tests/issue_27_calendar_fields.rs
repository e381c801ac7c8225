//! Issue 27's new scenario fields refuse bad input with one line naming the file and the field:
//! `[calendar]` (the mission, Pasadena clock times, hours, holidays) and the per-sol historic
//! drive window. And a computed calendar over a sol number out of range is an error, not a
//! panic (it indexed past the computed sols: `sol = 4294967295`).

use crate::common::{assert_bad_input, scenario_copy, solsim};

fn validate(edit: impl Fn(String) -> String) -> std::process::Output {
    let (path, _d) = scenario_copy("sol717-719.toml", edit);
    solsim().arg("validate").arg(&path).output().expect("runs")
}

fn in_calendar(line: &'static str) -> impl Fn(String) -> String {
    move |t: String| {
        t.replacen(
            "mission = \"mars2020\"",
            &format!("mission = \"mars2020\"\n{line}"),
            1,
        )
    }
}

#[test]
fn calendar_fields_are_checked() {
    assert_bad_input(
        &validate(|t| t.replacen("mission = \"mars2020\"", "mission = \"msl\"", 1)),
        &["case.toml: calendar.mission", "mars2020"],
    );
    assert_bad_input(
        &validate(in_calendar("shift_latest_start_pt = \"25:00\"")),
        &["calendar.shift_latest_start_pt", "HH:MM"],
    );
    assert_bad_input(
        &validate(in_calendar("shift_earliest_start_pt = \"18:00\"")),
        &[
            "calendar.shift_latest_start_pt",
            "at or after shift_earliest_start_pt",
        ],
    );
    assert_bad_input(
        &validate(in_calendar("relay_latency_h = nan")),
        &["calendar.relay_latency_h", "hours"],
    );
    assert_bad_input(
        &validate(in_calendar("light_time_min = 300.0")),
        &["calendar.light_time_min", "minutes"],
    );
    assert_bad_input(
        &validate(in_calendar("holidays = [\"2023-02-30\"]")),
        &["calendar.holidays[0]", "YYYY-MM-DD"],
    );
    assert_bad_input(
        &validate(in_calendar("relay_pass_lmst = \"17:0\"")),
        &["calendar.relay_pass_lmst", "HH:MM"],
    );
}

#[test]
fn historic_window_is_checked() {
    // Replace (or drop) the first sol's window end.
    let first_end = |with: &'static str| {
        move |t: String| {
            let start = t.find("historic_drive_end_lmst = ").expect("a window");
            let end = start + t[start..].find('\n').expect("line") + 1;
            format!("{}{with}{}", &t[..start], &t[end..])
        }
    };
    assert_bad_input(
        &validate(first_end("historic_drive_end_lmst = \"00:01\"\n")),
        &[
            "sols[0].historic_drive_end_lmst",
            "a time after the drive's start",
        ],
    );
    assert_bad_input(
        &validate(first_end("")),
        &[
            "sols[0].historic_drive_end_lmst",
            "whenever historic_drive_start_lmst is given",
        ],
    );
}

#[test]
fn a_computed_calendar_past_its_range_is_an_error_not_a_panic() {
    let o = validate(|t| t.replacen("sol = 717\n", "sol = 4294967295\n", 1));
    assert_bad_input(&o, &["sols[0].sol", "within 20000 of landing"]);
}
