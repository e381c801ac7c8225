//! `solsim plan`: plan one sol from a campaign file with the branch-and-bound planner
//! (paper 003 §3.1) and print the timeline, the utility per campaign and per tier, the proof
//! status and the independent validator's verdict.
//!
//! The campaign file format lives in [`study::campaign_file`]; the search and its report are
//! [`outputs::plan_report`], the table and JSON [`outputs::plan_table`]. This module holds the
//! arguments.
//!
//! ## References
//! Paper 003 §3 (campaign intents: goal set, temporally periodic, state-based), §3.1
//! (anytime branch and bound), §5 (the illustrative scenario).

use std::io::Write;
use std::path::PathBuf;

pub use outputs::plan_report::DEFAULT_NODE_BUDGET;
use outputs::plan_report::{PlanBudget, plan_file};
use outputs::plan_table::{report_json, report_table};

/// `solsim plan` arguments.
#[derive(Debug, clap::Args)]
pub struct PlanArgs {
    /// Campaign file (TOML): the sol window, resources, activities and campaigns.
    pub campaign: PathBuf,
    /// Print JSON on standard output instead of the table (same content).
    #[arg(long)]
    pub json: bool,
    /// Most search nodes to expand. The search is deterministic under a node budget alone:
    /// two runs print identical bytes.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_NODE_BUDGET,
          value_parser = clap::value_parser!(u64).range(1..))]
    pub nodes: u64,
    /// Also stop after this many milliseconds of search. Optional; when it binds, the plan,
    /// bound and node count depend on the machine and may vary between runs.
    #[arg(long, value_name = "MS", value_parser = clap::value_parser!(u64).range(1..))]
    pub time_budget_ms: Option<u64>,
}

/// Run `solsim plan` and print the table or JSON.
///
/// # Errors
/// A malformed file ([`study::PlanFileError`]) or a failed write.
pub fn run(args: &PlanArgs, out: &mut dyn Write) -> anyhow::Result<()> {
    let budget = PlanBudget {
        nodes: args.nodes,
        time_budget_ms: args.time_budget_ms,
    };
    let report = plan_file(&args.campaign, budget)?;
    if args.json {
        let mut s = serde_json::to_string_pretty(&report_json(&report))?;
        s.push('\n');
        out.write_all(s.as_bytes())?;
    } else {
        out.write_all(report_table(&report).as_bytes())?;
    }
    Ok(())
}
