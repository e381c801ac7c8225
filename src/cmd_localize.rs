//! `solsim localize-bench`: the synthetic benchmark set of onboard global localization (the size
//! of paper 000 §4's 264 panoramas) run with census, NCC and mutual information, one accuracy
//! table per method.

use std::fmt::Write as _;

use localization::benchmark_set::{
    BenchmarkMaps, BenchmarkReport, ErrorStats, PAPER_CASE_COUNT, benchmark_cases, run_benchmark,
};
use localization::matcher::{MatchParams, Method};

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
    /// Methods to run: census, ncc, mi (comma-separated).
    #[arg(long, default_value = "census,ncc,mi", value_delimiter = ',')]
    pub methods: Vec<String>,
    /// Print JSON (the full reports, one per method) instead of the tables.
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
        s.push_str(&row(&format!("{kind:?}").to_lowercase(), e));
    }
    let rejected: usize = r.rejections.iter().map(|(_, n)| n).sum();
    let _ = writeln!(
        s,
        "  rejected by validity checks: {rejected} {:?}; could not run: {}",
        r.rejections, r.failures
    );
    s
}

/// Run the benchmark and print the tables (or JSON).
pub fn run(args: &LocalizeBenchArgs, out: &mut dyn std::io::Write) -> anyhow::Result<()> {
    let methods = args
        .methods
        .iter()
        .map(|m| {
            Method::from_name(m)
                .ok_or_else(|| anyhow::anyhow!("--methods: expected census, ncc or mi, got {m:?}"))
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    if args.cases == 0 {
        anyhow::bail!("--cases: expected at least 1 case, got 0");
    }
    let maps = BenchmarkMaps::generate(args.map_seed);
    let cases = benchmark_cases(args.cases, args.seed);
    let mut docs = Vec::new();
    for method in methods {
        let params = MatchParams {
            method,
            ..MatchParams::default()
        };
        let start = std::time::Instant::now();
        let report = run_benchmark(&cases, |k| maps.get(k), &params);
        if args.json {
            docs.push(serde_json::json!({ "method": method.name(), "report": report }));
        } else {
            write!(out, "{}", table(method, &report))?;
            writeln!(
                out,
                "  ({} cases in {:.1} s)\n",
                args.cases,
                start.elapsed().as_secs_f64()
            )?;
        }
    }
    if args.json {
        writeln!(out, "{}", serde_json::to_string_pretty(&docs)?)?;
    }
    Ok(())
}
