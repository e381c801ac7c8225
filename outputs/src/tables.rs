//! The terminal tables: one run sol by sol ([`sol_table`], `solsim run`) and the strategies
//! side by side ([`compare_table`], `solsim compare`), with the science campaigns when there
//! are any.

use std::fmt::Write as _;

use sim::CampaignOutcome;

/// The per-sol table of one run.
#[must_use]
pub fn sol_table(outcome: &CampaignOutcome) -> String {
    let mut s = format!("strategy: {}\n", outcome.strategy);
    let faults: Vec<String> = outcome
        .sols
        .iter()
        .map(|r| {
            r.fault.as_ref().map_or(String::new(), |f| {
                format!(
                    "{} after {:.1} m at r={:.2} m",
                    f.kind.name(),
                    f.after_m,
                    f.uncertainty_m
                )
            })
        })
        .collect();
    // Wide enough for every fault, so the note column starts in one place.
    let fault_w = faults
        .iter()
        .map(|f| f.chars().count())
        .max()
        .unwrap_or(0)
        .max(28);
    let _ = writeln!(
        s,
        "{:>5}  {:>10}  {:>11}  {:>11}  {:>11}  {:>12}  {:<fault_w$}  note",
        "sol", "distance_m", "start_r_m", "end_r_m", "d_novo_m", "passage_m", "fault"
    );
    for (r, fault) in outcome.sols.iter().zip(faults) {
        // In the order things happened: the ground's fix with the uplink, why the sol did not
        // drive or why its drive ended, then the onboard localization after it.
        let mut note: Vec<String> = Vec::new();
        if r.ground_localization.is_some() {
            note.push("ground-localized".into());
        }
        if let Some(why) = r.skip_reason {
            note.push(format!("skipped: {why}"));
        }
        if let Some(end) = r.drive_end {
            note.push(end.to_string());
        }
        if let Some(l) = &r.onboard_localization {
            let when = match (&l.start_lmst, l.duration_s) {
                (Some(start), Some(d)) => format!(" {start} +{:.0} min", d / 60.0),
                _ => String::new(),
            };
            let ellipse = l.ellipse.map_or(String::new(), |e| {
                format!(
                    ", 1σ {:.2}×{:.2} m az {:.0}°",
                    e.semi_major_m, e.semi_minor_m, e.azimuth_deg
                )
            });
            note.push(if l.applied {
                format!(
                    "onboard loc ({}{when}{ellipse}) → r={:.2} m",
                    l.localizer, l.uncertainty_after_m
                )
            } else {
                format!(
                    "onboard loc ({}{when}) lost: {}",
                    l.localizer,
                    l.reason
                        .as_ref()
                        .map(ToString::to_string)
                        .unwrap_or_default()
                )
            });
        }
        let note = note.join("; ");
        let _ = writeln!(
            s,
            "{:>5}  {:>10.2}  {:>11.2}  {:>11.2}  {:>11.2}  {:>12}  {:<fault_w$}  {}",
            r.sol,
            r.distance_m,
            r.start_uncertainty_m,
            r.end_uncertainty_m,
            r.d_novo_m,
            r.passage_clearance_m
                .map_or("-".into(), |c| format!("{c:.2}")),
            fault,
            note
        );
    }
    let t = &outcome.totals;
    let _ = writeln!(
        s,
        "totals: {:.1} m in {} drive sols of {}; sols to goal {}; {} NO_PATH / {} faults; max r {:.2} m; localizations: {} ground, {} onboard applied, {} rejected; truth outside disc on {} sols",
        t.distance_m,
        t.drive_sols,
        t.sols,
        t.sols_to_goal
            .map_or("not reached".into(), |n| n.to_string()),
        t.no_path_faults,
        t.faults,
        t.max_uncertainty_m,
        t.ground_localizations,
        t.onboard_localizations_applied,
        t.onboard_localizations_rejected,
        t.truth_outside_disc
    );
    if !t.science.is_empty() {
        let tally: Vec<String> = t
            .science
            .iter()
            .map(|(c, n)| format!("{c} {} done, {} failed", n.done, n.failed))
            .collect();
        let _ = writeln!(s, "science: {}", tally.join("; "));
    }
    s
}

/// The side-by-side table of `solsim compare`.
#[must_use]
pub fn compare_table(outcomes: &[CampaignOutcome]) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<18}  {:>11}  {:>10}  {:>10}  {:>11}  {:>7}  {:>7}  {:>9}  {:>16}  {:>12}",
        "strategy",
        "sols_to_goal",
        "drive_sols",
        "distance_m",
        "m_per_drive",
        "NO_PATH",
        "faults",
        "max_r_m",
        "onboard_loc a/r",
        "ground_loc"
    );
    for o in outcomes {
        let t = &o.totals;
        let per = metres_per_drive_sol(t);
        let _ = writeln!(
            s,
            "{:<18}  {:>11}  {:>10}  {:>10.1}  {:>11.1}  {:>7}  {:>7}  {:>9.2}  {:>16}  {:>12}",
            o.strategy,
            t.sols_to_goal.map_or("-".into(), |n| n.to_string()),
            t.drive_sols,
            t.distance_m,
            per,
            t.no_path_faults,
            t.faults,
            t.max_uncertainty_m,
            format!(
                "{}/{}",
                t.onboard_localizations_applied, t.onboard_localizations_rejected
            ),
            t.ground_localizations
        );
    }
    science_table(outcomes, &mut s);
    s
}

/// Metres driven per drive sol (0 without a drive sol): the compare table's `m_per_drive`.
#[must_use]
pub fn metres_per_drive_sol(t: &sim::Totals) -> f64 {
    if t.drive_sols > 0 {
        t.distance_m / f64::from(t.drive_sols)
    } else {
        0.0
    }
}

/// Science campaigns side by side (`done/failed` per campaign), if the scenario has any.
fn science_table(outcomes: &[CampaignOutcome], s: &mut String) {
    let Some(first) = outcomes.iter().find(|o| !o.totals.science.is_empty()) else {
        return;
    };
    let campaigns: Vec<&String> = first.totals.science.keys().collect();
    let _ = write!(
        s,
        "\nscience campaigns, members done/failed:\n{:<18}",
        "strategy"
    );
    for c in &campaigns {
        let _ = write!(s, "  {c:>12}");
    }
    let _ = writeln!(s, "  {:>16}", "plan_replans");
    for o in outcomes {
        let _ = write!(s, "{:<18}", o.strategy);
        for c in &campaigns {
            let n = o.totals.science.get(*c).copied().unwrap_or_default();
            let _ = write!(s, "  {:>12}", format!("{}/{}", n.done, n.failed));
        }
        let replans = o
            .sols
            .iter()
            .filter_map(|r| r.activity_plan.as_ref())
            .flat_map(|p| &p.changes)
            .filter(|c| c.ends_with("replanned"))
            .count();
        let _ = writeln!(s, "  {replans:>16}");
    }
}
