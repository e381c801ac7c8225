//! Issue 12: with the rapid traverse's calibrated 88.2 m/h, the ground strategy's sol-402 plan
//! came out infeasible. The drive's length is `rate × window / 3600`; the planner turned it
//! back into `ceil(3600 × length / rate)` seconds, and the floating-point round trip landed
//! one ulp above the window for 566 of the windows between 5000 s and 10 000 s (5241 s → 5242 s),
//! one second too long for the drive to end before the panorama pass.

use planner::Drive;

fn drive(length_m: f64, rate_m_per_h: f64) -> Drive {
    Drive {
        length_m,
        rate_m_per_h,
        min_segment_s: 1,
        max_segments: 1,
        split_at_m: Vec::new(),
        latest_end_s: None,
    }
}

#[test]
fn a_window_turned_into_metres_and_back_is_the_same_window() {
    for rate in [88.2, 91.9, 100.0, 60.0, 137.3] {
        for window_s in 1..20_000_i64 {
            let length_m = rate * window_s as f64 / 3_600.0;
            assert_eq!(
                drive(length_m, rate).duration_s(),
                window_s,
                "{rate} m/h, {window_s} s"
            );
        }
    }
}

#[test]
fn a_drive_a_fraction_of_a_second_longer_still_takes_the_next_second() {
    // 100 m at 100 m/h is 3600 s; 1 mm more is 0.036 s more, a whole extra second.
    assert_eq!(drive(100.0, 100.0).duration_s(), 3_600);
    assert_eq!(drive(100.001, 100.0).duration_s(), 3_601);
}
