//! The Slurm submit script of `solsim sweep slurm` ([`SlurmJob::script`]): a job array with one
//! shard per task, then a merge job that runs once every shard has succeeded.
//!
//! Every value that enters the script is single-quoted for bash ([`sh`]), and the job scripts
//! it writes are quoted again, so no path can end a quote, a line or a here-document and become
//! code. The paths must already be absolute and free of control characters (the binary checks
//! what the user typed).

use std::fmt::Write as _;

use sim::Strategy;
use sweep::engine::SweepSpec;

/// Quotes `s` for bash (single quotes): every byte inside is data, none is code.
#[must_use]
pub fn sh(s: &str) -> String {
    format!("'{}'", s.replace('\'', r"'\''"))
}

/// What a Slurm submit script runs: every path absolute, UTF-8 and free of control characters.
pub struct SlurmJob<'a> {
    /// Scenario name, for the script's opening comment.
    pub name: &'a str,
    /// The solsim binary the jobs run.
    pub solsim: &'a str,
    /// The scenario file.
    pub scenario: &'a str,
    /// The directory of the shards, the merged sweep and the logs.
    pub out: &'a str,
    /// The sweep.
    pub spec: &'a SweepSpec,
    /// Shards: array tasks `0..shards`.
    pub shards: u64,
    /// Threads per array task (`sbatch --cpus-per-task`).
    pub threads_per_task: u64,
    /// `sbatch` options beside the fixed ones (`--partition=…`, `--time=…`), each already
    /// checked to be letters, digits and `-_:.=`.
    pub sbatch_extra: String,
}

impl SlurmJob<'_> {
    /// The submit script. The two job scripts it writes are each one `printf '%s\n'` of
    /// single-quoted lines whose values are single-quoted again: no path can end a quote, a
    /// line or a here-document and become code.
    #[must_use]
    pub fn script(&self) -> String {
        let m = self.shards;
        let spec = self.spec;
        let strategies = spec
            .strategies
            .iter()
            .map(|s| s.name())
            .collect::<Vec<_>>()
            .join(",");
        let baseline = spec.baseline.map_or("none", Strategy::name);
        let (solsim, scen, outq) = (sh(self.solsim), sh(self.scenario), sh(self.out));
        let extra = &self.sbatch_extra;
        let shard_job = [
            "#!/usr/bin/env bash".to_string(),
            "set -euo pipefail".to_string(),
            format!(
                "exec {solsim} sweep {scen} --runs {} --strategies {strategies} --seed {} --baseline {baseline} \
                 --threads {} --shard \"$SLURM_ARRAY_TASK_ID/{m}\" --out {outq}/\"shard-$SLURM_ARRAY_TASK_ID-of-{m}\" --resume --quiet",
                spec.runs, spec.seed, self.threads_per_task
            ),
        ];
        let merge_job = [
            "#!/usr/bin/env bash".to_string(),
            "set -euo pipefail".to_string(),
            format!("exec {solsim} sweep merge {outq}/shard-*-of-{m} --out {outq}/merged --quiet"),
        ];
        let printf = |lines: &[String], file: &str| {
            let quoted: Vec<String> = lines.iter().map(|l| sh(l)).collect();
            format!(
                "printf '%s\\n' \\\n  {} \\\n  > \"$out/slurm/{file}\"",
                quoted.join(" \\\n  ")
            )
        };
        let mut s = String::new();
        let _ = writeln!(s, "#!/usr/bin/env bash");
        let _ = writeln!(
            s,
            "# solsim sweep of {} on Slurm: runs 0..{} of {strategies} (seed {}), in {m} shards —\n\
             # one array task per shard (`solsim sweep --shard K/{m}`), then a merge job that runs\n\
             # once every task has succeeded. Submit from a login node: bash THIS_FILE.\n\
             # Shards write {outq}/shard-K-of-{m}, the merge {outq}/merged, Slurm logs {outq}/slurm.\n\
             # A task that is requeued or re-run resumes its shard (--resume).",
            sh(self.name),
            spec.runs,
            spec.seed,
        );
        let _ = writeln!(s, "set -euo pipefail");
        let _ = writeln!(s, "out={outq}");
        let _ = writeln!(s, "mkdir -p \"$out/slurm\"");
        // sbatch reads `%` in an --output path as a filename pattern (`%j`: the job id);
        // `%%` is a literal one.
        let _ = writeln!(
            s,
            "logs={}/slurm  # $out/slurm for sbatch --output",
            sh(&self.out.replace('%', "%%"))
        );
        let _ = writeln!(s, "{}", printf(&shard_job, "shard.sh"));
        let _ = writeln!(s, "{}", printf(&merge_job, "merge.sh"));
        let _ = writeln!(
            s,
            "array=$(sbatch --parsable --job-name=solsim-sweep --array=0-{} --cpus-per-task={}{extra} \\\n  \
             --output=\"$logs/shard-%a.log\" \"$out/slurm/shard.sh\")",
            m - 1,
            self.threads_per_task
        );
        let _ = writeln!(s, "array=${{array%%;*}}");
        let _ = writeln!(
            s,
            "merge=$(sbatch --parsable --job-name=solsim-merge --dependency=afterok:\"$array\"{extra} \\\n  \
             --output=\"$logs/merge.log\" \"$out/slurm/merge.sh\")"
        );
        let _ = writeln!(s, "echo \"array job $array\"");
        let _ = writeln!(s, "echo \"merge job ${{merge%%;*}}\"");
        s
    }
}
