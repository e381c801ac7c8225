//! Issue 26, finding 12: LMST times `"11:+3"`, `"+11:30"` and `" 11:30"` were accepted (the
//! parser trimmed the text and handed each side to integer parsing, which takes a sign). A
//! clock reading is now exactly `HH:MM`: two ASCII digits, a colon, two ASCII digits, from
//! 00:00 to 24:00. Every LMST field of a scenario and of a campaign file refuses anything else
//! with the field named.

use crate::common::{assert_bad_input, root, scenario_copy, solsim};

const LOOSE: [&str; 12] = [
    "11:+3",
    "+11:30",
    " 11:30",
    "11:30 ",
    "11:30\n",
    "9:30",
    "11:3",
    "-1:00",
    "11:-0",
    "11 :30",
    "١١:٣٠", // Arabic-Indic digits
    "11:30:00",
];

#[test]
fn scenario_lmst_fields_take_hh_mm_only() {
    let path = root().join("scenarios/crater-floor-passage.toml");
    let base = std::fs::read_to_string(&path).expect("read");
    for loose in LOOSE {
        let quoted = toml::Value::from(loose).to_string();
        for (field, from) in [
            (
                "operations.drive_start_lmst",
                "drive_start_lmst = \"11:30\"",
            ),
            ("operations.drive_end_lmst", "drive_end_lmst = \"14:15\""),
        ] {
            let key = from.split(' ').next().expect("key");
            let text = base.replace(from, &format!("{key} = {quoted}"));
            let e = study::scenario::ScenarioSpec::from_toml_str(&path, &text)
                .expect_err(loose)
                .to_string();
            assert!(e.contains(&format!("{field}: expected")), "{loose:?}: {e}");
            assert!(e.contains("\"HH:MM\""), "{e}");
        }
    }
    // And through the command line, as the issue found it.
    let (path, _d) = scenario_copy("crater-floor-passage.toml", |t| {
        t.replace(
            "drive_start_lmst = \"11:30\"",
            "drive_start_lmst = \"11:+3\"",
        )
    });
    let o = solsim().arg("validate").arg(&path).output().expect("runs");
    assert_bad_input(
        &o,
        &["operations.drive_start_lmst", "\"HH:MM\"", "got \"11:+3\""],
    );
}

#[test]
fn sol_downlink_and_campaign_file_lmst_take_hh_mm_only() {
    let base =
        std::fs::read_to_string(root().join("scenarios/self-reliant-campaign.toml")).expect("read");
    let plan = root().join("scenarios/plans/self-reliant-campaign.toml");
    let plan_text = std::fs::read_to_string(&plan).expect("read");
    for loose in LOOSE {
        let quoted = toml::Value::from(loose).to_string();
        let text = base.replacen(
            "downlink_lmst = \"16:00\"",
            &format!("downlink_lmst = {quoted}"),
            1,
        );
        let e = study::scenario::ScenarioSpec::from_toml_str(
            &root().join("scenarios/self-reliant-campaign.toml"),
            &text,
        )
        .expect_err(loose)
        .to_string();
        assert!(e.contains("].downlink_lmst: expected"), "{loose:?}: {e}");
        let text = plan_text.replacen(
            "start_lmst = \"09:00\"",
            &format!("start_lmst = {quoted}"),
            1,
        );
        let e = study::CampaignFile::from_toml_str(&plan, &text)
            .expect_err(loose)
            .to_string();
        assert!(e.contains("sol.start_lmst: expected"), "{loose:?}: {e}");
    }
}

#[test]
fn two_digit_clock_readings_still_load() {
    for (start, end) in [("00:00", "24:00"), ("09:05", "17:59"), ("11:30", "14:15")] {
        let (path, _d) = scenario_copy("crater-floor-passage.toml", |t| {
            t.replace(
                "drive_start_lmst = \"11:30\"",
                &format!("drive_start_lmst = \"{start}\""),
            )
            .replace(
                "drive_end_lmst = \"14:15\"",
                &format!("drive_end_lmst = \"{end}\""),
            )
        });
        let o = solsim().arg("validate").arg(&path).output().expect("runs");
        assert_eq!(
            o.status.code(),
            Some(0),
            "{start}-{end}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}
