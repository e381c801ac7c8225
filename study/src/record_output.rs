//! What `solsim record import` does with an import ([`Imported`]) besides writing its files:
//! the passage rule's starting points, from the replay of the scenario as staged, and the
//! texts — the import report beside the scenario and the printed summary.

use std::fmt::Write as _;
use std::path::Path;

use crate::Scenario;
use crate::record_import::{Imported, along, project_onto};

impl Imported {
    /// Where each sol starts along the route, metres: 0, then where the replay of `staged` —
    /// the imported scenario as written, without passages — ends each sol (the passages are
    /// placed where the replay starts each sol: the rule of [`crate::record_import`]).
    #[must_use]
    pub fn passage_starts(&self, staged: &Scenario) -> Vec<f64> {
        let replay = staged.run_index(sim::Strategy::Replay, 0);
        let route_cum = along(&self.route_m);
        let mut starts = vec![0.0];
        starts.extend(
            replay
                .sols
                .iter()
                .map(|s| project_onto(&self.route_m, &route_cum, s.end_position_m)),
        );
        starts
    }

    /// `import-report.txt`: what the record held besides plain drives, and the passages
    /// placed.
    #[must_use]
    pub fn report_text(&self, passages: usize) -> String {
        let mut report = String::new();
        for f in &self.findings {
            report.push_str(f);
            report.push('\n');
        }
        report.push_str(&format!("{passages} passages placed by the import rule\n"));
        report
    }

    /// The printed summary of an import of the record `layer_name` written as `scenario`
    /// (with `zones_file` and `map_dir` beside it): the sols, each with its metres, window and
    /// source (or why it did not drive), the findings and the passages placed.
    #[must_use]
    pub fn summary(
        &self,
        layer_name: &str,
        scenario: &Path,
        zones_file: &str,
        map_dir: &str,
        passages: usize,
    ) -> String {
        let mut t = String::new();
        let drove = self.sols.iter().filter(|x| x.distance_m > 0.0).count();
        let total: f64 = self.sols.iter().map(|x| x.distance_m).sum();
        let sols = &self.options.sols;
        let _ = writeln!(
            t,
            "wrote {} (+ {zones_file}, {map_dir}/): sols {}-{} of {layer_name}: {drove} drive sols, {total:.1} m; route {:.0} m; AutoNav rate {} m/h (the record's mean speed; each historic drive sol drives at its own)",
            scenario.display(),
            sols.start(),
            sols.end(),
            self.route_length_m,
            self.drive_rate_m_per_h
        );
        let _ = writeln!(
            t,
            "{:>5}  {:>9}  {:<13}  source / why not",
            "sol", "metres", "window LMST"
        );
        for x in &self.sols {
            let window = x.window.as_ref().map_or_else(String::new, |(s, e)| {
                format!("{}-{e}", s.as_deref().unwrap_or("?"))
            });
            let why = if x.distance_m > 0.0 {
                &x.source
            } else {
                &x.note
            };
            let _ = writeln!(
                t,
                "{:>5}  {:>9.2}  {window:<13}  {why}",
                x.sol, x.distance_m
            );
        }
        for f in &self.findings {
            let _ = writeln!(t, "note: {f}");
        }
        let _ = writeln!(
            t,
            "note: {passages} passages placed by the import rule (a modelling choice: the record has no zones)"
        );
        t
    }
}
