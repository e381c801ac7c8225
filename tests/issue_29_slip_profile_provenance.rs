//! Issue 29 (found in review): moving the soil model to `sim::rover::physics::soil` changed the
//! provenance line `solsim slip-profile` writes, while the bundled table the simulator reads,
//! `sim/data/slip_profile.csv` (that command's output, committed), still named
//! `sim::physics::soil`. The existing test compares only the table's numbers, so nothing saw the
//! two drift apart. The bundled file's comment lines are now what the command writes.

use sim::rover::slip_profile::{BUNDLED_CSV, ProfileSettings};

#[test]
fn the_bundled_profile_names_what_slip_profile_writes() {
    // The bundled table was measured with the command's defaults (its first line says so).
    let written: Vec<String> = study::slip_profile::provenance(&ProfileSettings::default())
        .lines()
        .map(|l| format!("# {l}"))
        .collect();
    let bundled: Vec<&str> = BUNDLED_CSV.lines().filter(|l| l.starts_with('#')).collect();
    assert_eq!(bundled, written);
    // And each module it names exists under that path (this file would not build otherwise).
    let _: Option<sim::rover::physics::soil::Soil> = None;
}
