//! `solsim localize-bench`: the synthetic benchmark set of onboard global localization (the size
//! of paper 000 §4's 264 panoramas) run with census, NCC and mutual information, one accuracy
//! table per method, and with the other localizers side by side
//! ([`study::localizer_comparison`]); and `solsim seu-campaign`
//! ([`localization::upset_campaign`]).

use localization::benchmark_set::PAPER_CASE_COUNT;
use localization::upset_campaign::UpsetCampaign;
use study::localizer_comparison::{BenchmarkRun, Candidate, compare, table};

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
    let bench = BenchmarkRun {
        cases: args.cases,
        seed: args.seed,
        map_seed: args.map_seed,
    };
    let (maps, cases) = bench.generate();
    let start = std::time::Instant::now();
    let label: Vec<&str> = candidates.iter().map(|c| c.name()).collect();
    let total = cases.len() as u64;
    let progress = Progress::new(false, &label.join(","), "cases", total);
    let comparison = compare(&cases, &maps, &candidates, &|n| progress.update(n, total));
    progress.finish();
    if args.json {
        writeln!(
            out,
            "{}",
            serde_json::to_string_pretty(&bench.json(&comparison))?
        )?;
    } else if args.markdown {
        write!(out, "{}", table(&comparison.rows, true))?;
    } else {
        write!(
            out,
            "{}",
            bench.text(&comparison, start.elapsed().as_secs_f64())
        )?;
    }
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
    let campaign = UpsetCampaign {
        runs: args.runs,
        seed: args.seed,
        p_storage: args.p_storage,
        p_memory: args.p_memory,
        p_output: args.p_output,
        p_stall: args.p_stall,
    };
    let scene = campaign.scene()?;
    let start = std::time::Instant::now();
    let progress = Progress::new(false, "seu-campaign", "runs", u64::from(args.runs));
    let c = campaign.run(&scene, |n| {
        progress.update(u64::from(n), u64::from(args.runs))
    });
    progress.finish();
    let seconds = start.elapsed().as_secs_f64();
    if args.json {
        writeln!(
            out,
            "{}",
            serde_json::to_string_pretty(&campaign.json(&c, seconds))?
        )?;
    } else {
        write!(out, "{}", campaign.text(&c, seconds))?;
    }
    if c.corrupted_applied > 0 {
        anyhow::bail!("{} corrupted results were applied", c.corrupted_applied);
    }
    Ok(())
}
