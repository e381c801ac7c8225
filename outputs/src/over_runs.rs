//! `solsim compare SCENARIO --runs N`: under the one-run table, each strategy against `ground`
//! over N seeded runs, with intervals.
//!
//! The runs are a sweep held in memory ([`sweep::engine::summary_in_memory`]); this module only
//! prints what the sweep's [`Summary`] holds, so the numbers are those of `solsim sweep` with
//! the same scenario, seed and runs (its `summary.json`): paired differences from ground with
//! their seeded 95 % bootstrap intervals, and rates with 95 % Wilson intervals.

use std::fmt::Write as _;

use serde::Serialize;
use sweep::engine::Summary;
use sweep::stats::PairedDifference;
use sweep::summary::{Metric, RateKind, Statistics};

/// Fewest runs `compare --runs` takes: one run is `compare` itself, and the spread of the
/// runs needs at least two.
pub const MIN_RUNS: u64 = 2;

/// `compare --runs N --json`: the one-run documents (what `compare --json` prints) and the
/// summary over the runs (what `solsim sweep` writes to `summary.json`).
#[derive(Serialize)]
pub struct CompareRunsJson<'a> {
    /// One document per strategy for the scenario's seed, as `compare --json` prints them.
    pub one_run: Vec<serde_json::Value>,
    /// The sweep's summary over run indices `0..N`.
    pub over_runs: &'a Summary,
}

/// The summary as `solsim sweep` writes `summary.json`: pretty JSON with a trailing newline.
#[must_use]
pub fn summary_json(summary: &Summary) -> String {
    let mut s =
        serde_json::to_string_pretty(summary).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"));
    s.push('\n');
    s
}

/// A signed number with a real minus sign.
pub(crate) fn signed(x: f64, decimals: usize) -> String {
    format!("{x:+.decimals$}").replace('-', "−")
}

/// A percentage with its Wilson interval: `12.5 % [3.5, 36.0]`.
fn rate_text(st: &Statistics, strategy: &str, rate: RateKind) -> String {
    st.strategy(strategy)
        .and_then(|s| s.rate(rate.name()))
        .map_or("-".into(), |r| {
            format!(
                "{:.1} % [{:.1}, {:.1}]",
                100.0 * r.rate,
                100.0 * r.interval.lo,
                100.0 * r.interval.hi
            )
        })
}

/// How a figure is printed: its `runs.parquet` name, the scale from its unit to the printed
/// one, the printed unit and the decimals.
struct Shown {
    figure: Metric,
    scale: f64,
    unit: &'static str,
    decimals: usize,
}

impl Shown {
    fn number(&self, x: f64) -> String {
        format!("{:.d$}", x * self.scale, d = self.decimals)
    }

    fn value(&self, x: f64) -> String {
        format!("{}{}", self.number(x), self.unit_suffix())
    }

    fn unit_suffix(&self) -> String {
        if self.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", self.unit)
        }
    }

    fn difference(&self, d: &PairedDifference) -> String {
        let k = self.scale;
        format!(
            "{}{} [{}, {}]",
            signed(d.mean * k, self.decimals),
            self.unit_suffix(),
            signed(d.interval.lo * k, self.decimals),
            signed(d.interval.hi * k, self.decimals)
        )
    }
}

/// The section under the one-run comparison: each strategy against the baseline (`ground`)
/// over the sweep's runs. Empty when the sweep has no baseline.
///
/// Per strategy: sols to cover the study segment (with a segment), drive sols, metres driven,
/// drive time, peak uncertainty and uplinks that needed a drive plan, each as the strategy's
/// mean against ground's and the mean paired difference with its 95 % bootstrap interval; the
/// NO_PATH and any-fault rates of the strategy and of ground with 95 % Wilson intervals.
///
/// `segment_sols_left`: the sols from the segment's first sol to the calendar's end; a run that
/// did not cover the segment needs more than that many, which is said where `ground` never did.
#[must_use]
pub fn against_ground_over_runs(summary: &Summary, segment_sols_left: Option<u32>) -> String {
    let st = &summary.statistics;
    let Some(base) = st.baseline.as_deref() else {
        return String::new();
    };
    let runs = summary.runs;
    let mean = |strategy: &str, f: Metric| st.strategy(strategy).and_then(|s| s.figure(f.name()));
    let paired = |strategy: &str, f: Metric| {
        st.paired(strategy, f.name())
            .and_then(|p| p.difference.as_ref())
    };
    let mut s = String::new();
    let _ = writeln!(
        s,
        "\nAgainst {base} over {runs} runs (run indices 0..{runs} from seed {}; run 0 is the run \
         above; the\nothers are other worlds, each driven by every strategy):",
        summary.seed
    );
    let _ = writeln!(
        s,
        "  X against Y: the strategy's mean over the runs against {base}'s. Difference: the mean \
         of\n  (strategy − {base}) run by run [95 % bootstrap interval, {} resamples]. Rates: % \
         of runs\n  [95 % Wilson interval].",
        st.bootstrap_resamples
    );
    let sols = Shown {
        figure: Metric::SegmentSols,
        scale: 1.0,
        unit: "sols",
        decimals: 2,
    };
    let covered = |strategy: &str| mean(strategy, Metric::SegmentSols).map_or(0, |sp| sp.n);
    if let Some(g) = &summary.segment {
        let _ = writeln!(
            s,
            "  study segment ({:.0} m from sol {}): {base}: covered in {} of {runs} runs{}",
            g.distance_m,
            g.from_sol,
            covered(base),
            mean(base, Metric::SegmentSols).map_or_else(
                || segment_sols_left.map_or(String::new(), |left| format!(
                    " (a run that did not cover it needs more than the {left} sols to the \
                     calendar's end)"
                )),
                |sp| format!(", in {} on average", sols.value(sp.mean))
            )
        );
    }
    let lines = [
        ("drive sols", Metric::DriveSols, 1.0, "sols", 2),
        ("distance", Metric::DistanceM, 1.0, "m", 1),
        ("drive time", Metric::DriveTimeS, 1.0 / 3600.0, "h", 2),
        ("peak r", Metric::MaxUncertaintyM, 1.0, "m", 2),
    ];
    for ss in st.strategies.iter().filter(|x| x.strategy != base) {
        let name = ss.strategy.as_str();
        let _ = writeln!(s, "  {name}:");
        if let Some(g) = &summary.segment {
            let average = mean(name, sols.figure).map_or(String::new(), |a| {
                format!(
                    ", in {} on average{}",
                    sols.value(a.mean),
                    mean(base, sols.figure).map_or(String::new(), |b| format!(
                        " ({base} {})",
                        sols.value(b.mean)
                    ))
                )
            });
            let none_for_base = match segment_sols_left {
                Some(left) if covered(base) == 0 => {
                    format!("{base}: more than {left} in every run")
                }
                _ => "no run where both covered it".into(),
            };
            let diff = paired(name, sols.figure).map_or(none_for_base, |d| {
                format!(
                    "difference {} over the {} runs where both covered it",
                    sols.difference(d),
                    d.n
                )
            });
            let _ = writeln!(
                s,
                "    study segment: covered in {} of {runs} runs ({base} {}){average}; {diff}",
                covered(name),
                covered(base)
            );
            let metres = Shown {
                figure: Metric::SegmentDistanceM,
                scale: 1.0,
                unit: "m",
                decimals: 1,
            };
            let _ = writeln!(
                s,
                "    distance from sol {}: {}",
                g.from_sol,
                figure_line(&metres, name, base, st)
            );
        }
        for (label, figure, scale, unit, decimals) in lines {
            let shown = Shown {
                figure,
                scale,
                unit,
                decimals,
            };
            let _ = writeln!(s, "    {label}: {}", figure_line(&shown, name, base, st));
        }
        let _ = writeln!(
            s,
            "    NO_PATH: in {} of runs against {}",
            rate_text(st, name, RateKind::NoPath),
            rate_text(st, base, RateKind::NoPath),
        );
        let _ = writeln!(
            s,
            "    any fault: in {} of runs against {}",
            rate_text(st, name, RateKind::Fault),
            rate_text(st, base, RateKind::Fault)
        );
        let uplinks = Shown {
            figure: Metric::DrivePlanUplinks,
            scale: 1.0,
            unit: "",
            decimals: 2,
        };
        let _ = writeln!(
            s,
            "    uplinks that needed a drive plan: {}",
            figure_line(&uplinks, name, base, st)
        );
    }
    s
}

/// The over-runs part of a strategy's clause in `solsim compare`'s verdict
/// ([`crate::verdict::verdict`]): `over 200 runs: +1.99 drive sols [+1.95, +2.02], +399.2 m
/// [+385.0, +412.2], study segment covered in 197 of 200 runs against ground's 0` — the mean
/// paired differences from the baseline with their 95 % bootstrap intervals, as the section
/// under the table prints them. `None` without a baseline or without the strategy.
#[must_use]
pub fn verdict_over_runs(summary: &Summary, strategy: &str) -> Option<String> {
    let st = &summary.statistics;
    let base = st.baseline.as_deref()?;
    st.strategy(strategy)?;
    let difference = |shown: &Shown| {
        st.paired(strategy, shown.figure.name())
            .and_then(|p| p.difference.as_ref())
            .map(|d| shown.difference(d))
    };
    let mut parts = vec![format!("over {} runs:", summary.runs)];
    let sols = Shown {
        figure: Metric::DriveSols,
        scale: 1.0,
        unit: "drive sols",
        decimals: 2,
    };
    let metres = Shown {
        figure: Metric::DistanceM,
        scale: 1.0,
        unit: "m",
        decimals: 1,
    };
    let mut figures: Vec<String> = [difference(&sols), difference(&metres)]
        .into_iter()
        .flatten()
        .collect();
    if summary.segment.is_some() {
        let segment = Shown {
            figure: Metric::SegmentSols,
            scale: 1.0,
            unit: "sols",
            decimals: 2,
        };
        let covered = |s: &str| {
            st.strategy(s)
                .and_then(|x| x.figure(Metric::SegmentSols.name()))
                .map_or(0, |sp| sp.n)
        };
        let paired = st
            .paired(strategy, segment.figure.name())
            .and_then(|p| p.difference.as_ref());
        figures.push(match paired {
            Some(d) => format!(
                "study segment {} over the {} runs where both covered it",
                segment.difference(d),
                d.n
            ),
            None => format!(
                "study segment covered in {} of {} runs against {base}'s {}",
                covered(strategy),
                summary.runs,
                covered(base)
            ),
        });
    }
    parts.push(figures.join(", "));
    Some(parts.join(" "))
}

/// `X against Y; difference D [lo, hi]` for a figure every run has.
fn figure_line(shown: &Shown, strategy: &str, base: &str, st: &Statistics) -> String {
    let mean = |s: &str| {
        st.strategy(s)
            .and_then(|x| x.figure(shown.figure.name()))
            .map(|sp| sp.mean)
    };
    let means = format!(
        "{} against {}",
        mean(strategy).map_or("-".into(), |a| shown.value(a)),
        mean(base).map_or("-".into(), |b| shown.value(b))
    );
    let diff = st
        .paired(strategy, shown.figure.name())
        .and_then(|p| p.difference.as_ref())
        .map_or("-".into(), |d| shown.difference(d));
    format!("{means}; difference {diff}")
}
