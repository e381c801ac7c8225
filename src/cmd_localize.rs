//! `solsim localize-bench`: the synthetic benchmark set of onboard global localization (the size
//! of paper 000 §4's 264 panoramas) run with census, NCC and mutual information, one accuracy
//! table per method, and with the other localizers side by side
//! ([`crate::localizer_comparison`]).

use std::fmt::Write as _;

use localization::benchmark_set::{
    BenchmarkMaps, BenchmarkReport, ErrorStats, PAPER_CASE_COUNT, benchmark_cases,
};
use localization::matcher::{MatchParams, Method};

use crate::localizer_comparison::{Candidate, compare, table as comparison_table};

use crate::progress::Progress;

/// Arguments of `solsim localize-bench`.
#[derive(Debug, clap::Args)]
pub struct LocalizeBenchArgs {
    /// Number of synthetic post-drive panoramas (rocky, plain and dune terrain in thirds).
    #[arg(long, default_value_t = PAPER_CASE_COUNT)]
    pub cases: usize,
    /// Seed of the cases (positions, priors, lighting, wedges, noise).
    #[arg(long, default_value_t = 2024)]
    pub seed: u64,
    /// Seed of the three procedural benchmark maps.
    #[arg(long, default_value_t = 1)]
    pub map_seed: u64,
    /// Localizers to run, comma-separated: census, ncc, mi (image matching, one accuracy table
    /// each), statistical (the flight-statistics model), particle (paper 002's filter), ekf
    /// (paper 004's filter, orbiter ranging); `all` for the six. With more than one, a
    /// side-by-side table follows.
    #[arg(long, default_value = "census,ncc,mi", value_delimiter = ',')]
    pub methods: Vec<String>,
    /// Print only the side-by-side table, as Markdown (what BENCHMARKS.md holds).
    #[arg(long, conflicts_with = "json")]
    pub markdown: bool,
    /// Print JSON (the matchers' full reports and the side-by-side rows) instead of tables.
    #[arg(long)]
    pub json: bool,
}

fn row(name: &str, e: &ErrorStats) -> String {
    format!(
        "  {name:<14} {:>5} {:>8.3} {:>9.3} {:>7.3} {:>7.3} {:>6} {:>6}\n",
        e.count, e.mean_m, e.median_m, e.p99_m, e.max_m, e.over_1m, e.over_2m
    )
}

/// The accuracy table of one method.
#[must_use]
pub fn table(method: Method, r: &BenchmarkReport) -> String {
    let mut s = format!("method: {}\n", method.name());
    s.push_str("  cases              n   mean_m  median_m   p99_m   max_m  >1_m  >2_m\n");
    s.push_str(&row("all", &r.all));
    s.push_str(&row("accepted", &r.accepted));
    for (kind, e) in &r.by_terrain {
        s.push_str(&row(kind.name(), e));
    }
    let rejected: usize = r.rejections.iter().map(|(_, n)| n).sum();
    let reasons = if r.rejections.is_empty() {
        String::new()
    } else {
        let each: Vec<String> = r
            .rejections
            .iter()
            .map(|(name, n)| format!("{} {n}", name.replace('_', " ")))
            .collect();
        format!(" ({})", each.join(", "))
    };
    let _ = writeln!(
        s,
        "  rejected by validity checks: {rejected}{reasons}; could not run: {}",
        r.failures
    );
    s
}

/// The localizers `--methods` names, in its order (`all` expands to the six).
fn candidates(methods: &[String]) -> anyhow::Result<Vec<Candidate>> {
    let mut out = Vec::new();
    for m in methods {
        if m == "all" {
            out.extend(Candidate::ALL);
            continue;
        }
        out.push(Candidate::from_name(m).ok_or_else(|| {
            anyhow::anyhow!(
                "--methods: expected census, ncc, mi, statistical, particle, ekf or all, got {m:?}"
            )
        })?);
    }
    out.dedup();
    Ok(out)
}

/// Run the benchmark and print the tables (or JSON).
pub fn run(args: &LocalizeBenchArgs, out: &mut dyn std::io::Write) -> anyhow::Result<()> {
    let candidates = candidates(&args.methods)?;
    if args.cases == 0 {
        anyhow::bail!("--cases: expected at least 1 case, got 0");
    }
    let maps = BenchmarkMaps::generate(args.map_seed);
    let cases = benchmark_cases(args.cases, args.seed);
    let start = std::time::Instant::now();
    let label: Vec<&str> = candidates.iter().map(|c| c.name()).collect();
    let progress = Progress::new(false, &label.join(","), "cases", cases.len() as u64);
    let comparison = compare(&cases, &maps, &candidates, &|n| {
        progress.update(n, cases.len() as u64);
    });
    progress.finish();
    let elapsed_s = start.elapsed().as_secs_f64();
    if args.json {
        let reports: Vec<_> = comparison
            .matcher_reports
            .iter()
            .map(
                |(method, report)| serde_json::json!({ "method": method.name(), "report": report }),
            )
            .collect();
        let doc = serde_json::json!({
            "cases": args.cases,
            "seed": args.seed,
            "map_seed": args.map_seed,
            "matchers": reports,
            "comparison": comparison.rows,
        });
        writeln!(out, "{}", serde_json::to_string_pretty(&doc)?)?;
        return Ok(());
    }
    if args.markdown {
        write!(out, "{}", comparison_table(&comparison.rows, true))?;
        return Ok(());
    }
    for (method, report) in &comparison.matcher_reports {
        writeln!(out, "{}", table(*method, report))?;
    }
    if candidates.len() > 1 || comparison.matcher_reports.is_empty() {
        writeln!(
            out,
            "side by side (accuracy of the accepted results, metres; the localizer's own time per case):"
        )?;
        write!(out, "{}", comparison_table(&comparison.rows, false))?;
    }
    writeln!(
        out,
        "({} cases, seed {}, map seed {}, in {elapsed_s:.1} s)",
        args.cases, args.seed, args.map_seed
    )?;
    Ok(())
}

/// Arguments of `solsim seu-campaign`.
#[derive(Debug, clap::Args)]
pub struct SeuArgs {
    /// Onboard-localization activities to run, each with upsets drawn from its own seed.
    #[arg(long, default_value_t = 1000)]
    pub runs: u32,
    /// Master seed of the upset draws.
    #[arg(long, default_value_t = 7)]
    pub seed: u64,
    /// Probability that a stored input file takes a bit flip before a run.
    #[arg(long, default_value_t = 0.05)]
    pub p_storage: f64,
    /// Probability that the input's in-memory copy takes a bit flip during a run.
    #[arg(long, default_value_t = 0.10)]
    pub p_memory: f64,
    /// Probability that a result file takes a bit flip.
    #[arg(long, default_value_t = 0.05)]
    pub p_output: f64,
    /// Probability that a run stalls.
    #[arg(long, default_value_t = 0.02)]
    pub p_stall: f64,
    /// Print JSON: `{"runs", "seed", "probabilities": {...}, "counts": {...}, "seconds"}`.
    #[arg(long)]
    pub json: bool,
}

/// Run the seeded upset-injection campaign on a real localization (census on a synthetic
/// post-drive scene) through the HBS model and print the counts.
pub fn seu(args: &SeuArgs, out: &mut dyn std::io::Write) -> anyhow::Result<()> {
    use localization::hbs::{HbsFile, HbsParams, seu_campaign};
    use localization::matcher::{OrbitalMap, RoverImages, localize};
    use localization::onboard::{decode_u8, encode_u8};
    use localization::synthetic::{
        OrbitalParams, RoverImagingParams, render_orbital, render_rover, truth_patch,
    };
    for (flag, p) in [
        ("--p-storage", args.p_storage),
        ("--p-memory", args.p_memory),
        ("--p-output", args.p_output),
        ("--p-stall", args.p_stall),
    ] {
        if !(0.0..=1.0).contains(&p) {
            anyhow::bail!("{flag}: expected a probability between 0 and 1, got {p}");
        }
    }
    let maps = BenchmarkMaps::generate(1);
    let layers = maps.get(localization::benchmark_set::TerrainKind::Rocky);
    let truth = [300.0, 300.0];
    let patch = truth_patch(layers, truth, 80.0, 11)?;
    let orbital = render_orbital(&patch, &OrbitalParams::default(), 12)?;
    let rover = render_rover(&patch, truth, &RoverImagingParams::default(), 13)?;
    let prior = [truth[0] + 6.0, truth[1] - 4.0];
    let (map_geo, ortho_geo) = (orbital.appearance.geo, rover.ortho.geo);
    let inputs = vec![
        HbsFile::new(
            "onbd_input.txt",
            format!("prior_x_m={} prior_y_m={}\n", prior[0], prior[1]).into_bytes(),
        ),
        HbsFile::new("ortho.bin", encode_u8(&rover.ortho, &rover.valid)),
        HbsFile::new(
            "map_tile.bin",
            encode_u8(
                &orbital.appearance,
                &vec![true; orbital.appearance.data.len()],
            ),
        ),
    ];
    let algorithm = |files: &[HbsFile]| -> Vec<u8> {
        let (Some((ortho, valid)), Some((map, _))) = (
            decode_u8(&files[1].bytes, ortho_geo),
            decode_u8(&files[2].bytes, map_geo),
        ) else {
            return b"error: unreadable image file".to_vec();
        };
        let prior = std::str::from_utf8(&files[0].bytes).ok().and_then(|t| {
            let v: Vec<f64> = t
                .split_whitespace()
                .filter_map(|kv| kv.split_once('=')?.1.parse().ok())
                .collect();
            (v.len() == 2).then(|| [v[0], v[1]])
        });
        let Some(prior) = prior else {
            return b"error: unreadable input file".to_vec();
        };
        let rover = RoverImages {
            ortho: &ortho,
            ortho_valid: &valid,
            dem: None,
        };
        match localize(
            &OrbitalMap {
                appearance: &map,
                dem: None,
            },
            &rover,
            prior,
            &MatchParams::default(),
        ) {
            Ok(m) => format!(
                "x_m={:.4} y_m={:.4} sigma_m={:.4} rejection={:?}\n",
                m.position_m[0], m.position_m[1], m.sigma_m, m.rejection
            )
            .into_bytes(),
            Err(e) => format!("error: {e}\n").into_bytes(),
        }
    };
    let params = HbsParams {
        p_flip_storage: args.p_storage,
        p_flip_memory: args.p_memory,
        p_flip_output: args.p_output,
        p_stall: args.p_stall,
        ..HbsParams::default()
    };
    let start = std::time::Instant::now();
    // MOB_APPLY_ONBD_LOCALIZATION's validity checks: a well-formed, accepted localization.
    let validate = |result: &[u8]| -> Result<(), String> {
        let text = std::str::from_utf8(result).map_err(|_| "result is not text".to_string())?;
        if text.starts_with("x_m=") && text.trim_end().ends_with("rejection=None") {
            Ok(())
        } else {
            Err(format!("not an accepted localization: {}", text.trim()))
        }
    };
    let progress = Progress::new(false, "seu-campaign", "runs", u64::from(args.runs));
    let c = seu_campaign(
        args.runs,
        args.seed,
        &params,
        &inputs,
        algorithm,
        validate,
        |n| progress.update(u64::from(n), u64::from(args.runs)),
    );
    progress.finish();
    if args.json {
        let doc = serde_json::json!({
            "runs": c.runs,
            "seed": args.seed,
            "probabilities": {
                "storage": args.p_storage,
                "memory": args.p_memory,
                "output": args.p_output,
                "stall": args.p_stall,
            },
            "counts": c,
            "seconds": start.elapsed().as_secs_f64(),
        });
        writeln!(out, "{}", serde_json::to_string_pretty(&doc)?)?;
    } else {
        seu_text(&c, args.seed, start, out)?;
    }
    if c.corrupted_applied > 0 {
        anyhow::bail!("{} corrupted results were applied", c.corrupted_applied);
    }
    Ok(())
}

fn seu_text(
    c: &localization::hbs::SeuCounts,
    seed: u64,
    start: std::time::Instant,
    out: &mut dyn std::io::Write,
) -> anyhow::Result<()> {
    writeln!(
        out,
        "HBS upset-injection campaign: {} onboard localizations (census on a synthetic post-drive scene), seed {}",
        c.runs, seed
    )?;
    writeln!(
        out,
        "  upsets injected:                  {}",
        c.upsets_injected
    )?;
    writeln!(
        out,
        "  activities with an upset:         {}",
        c.runs_with_upsets
    )?;
    writeln!(
        out,
        "  caught (checksum, compare, timeout or validity check): {}",
        c.caught
    )?;
    writeln!(out, "  harmless (result unchanged):       {}", c.harmless)?;
    writeln!(out, "  localizations lost:               {}", c.lost)?;
    writeln!(
        out,
        "  corrupted results applied:        {}",
        c.corrupted_applied
    )?;
    writeln!(out, "  ({:.1} s)", start.elapsed().as_secs_f64())?;
    Ok(())
}
