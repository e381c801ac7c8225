//! The Helicopter Base Station (HBS) co-processor model (paper 000 §6-§7, Fig. 17-19).
//!
//! The rover's RAD750 writes the localization input file (`MOB_WRITE_ONBD_INPUT_FILE`) and sends
//! it, with the post-drive images and map tiles, to the HBS over a serial link; each file
//! crosses it at its flight size ([`HbsFile::link_bytes`]), at [`HbsSettings::link_bytes_per_s`]
//! (~30 min at the flown 10 KB/s, paper 000 §4). The HBS runs the
//! localization, reboots, runs it again; the two result files come back and must match byte for
//! byte; every file carries an MD5 checksum that is checked at every stage; timeouts catch stalls;
//! `MOB_APPLY_ONBD_LOCALIZATION` applies the result only if all of that passed and the result's
//! own validity checks pass.
//!
//! The HBS has no ECC RAM (paper 000 Table 1: ~4,300 upsets/day/device), so radiation upsets are
//! an injectable fault here: a bit flip in an input file in storage, in the input's in-memory copy
//! during one run, or in a result file — and a stall. [`run_activity`] must never apply a
//! corrupted result; the returned [`ActivityLog`] says why a localization was lost.
//!
//! ## References
//! Paper 000 §6 (the 10 KB/s link, Table 1), §7 (run twice with a reboot, checksums, timeouts,
//! Fig. 17-19, the `MOB_*` commands).

use md5::{Digest, Md5};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

/// Co-processor settings (plain struct; every field has a unit and a default).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct HbsSettings {
    /// Serial link rate, bytes per second (default: 10,000 — "10KB/s", paper 000 §6; "up to
    /// 40KB/s could become possible with an RCE flight software update", ibid.). A KB is
    /// 1,000 bytes here.
    pub link_bytes_per_s: f64,
    /// One localization run on the HBS, seconds (default: 32, paper 000 §8).
    pub run_s: f64,
    /// HBS reboot between the runs, seconds (default: 120).
    pub reboot_s: f64,
    /// A run longer than this is a stall and is aborted, seconds (default: 300).
    pub run_timeout_s: f64,
    /// Probability that a stored input file takes a bit flip before a run (default: 0).
    pub p_flip_storage: f64,
    /// Probability that the input's in-memory copy takes a bit flip during one run (default: 0).
    pub p_flip_memory: f64,
    /// Probability that a result file takes a bit flip after it is written (default: 0).
    pub p_flip_output: f64,
    /// Probability that a run stalls (an upset in the kernel or a library) (default: 0).
    pub p_stall: f64,
}

impl Default for HbsSettings {
    fn default() -> Self {
        Self {
            link_bytes_per_s: 10_000.0,
            run_s: 32.0,
            reboot_s: 120.0,
            run_timeout_s: 300.0,
            p_flip_storage: 0.0,
            p_flip_memory: 0.0,
            p_flip_output: 0.0,
            p_stall: 0.0,
        }
    }
}

/// A file with the MD5 checksum taken when it was written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct HbsFile {
    /// File name (for the log).
    pub name: String,
    /// Contents.
    pub bytes: Vec<u8>,
    /// MD5 of the contents when written.
    pub md5: [u8; 16],
    /// Bytes that cross the serial link for this file, as flown: its length, unless it
    /// stands in for a flight product of another size ([`HbsFile::with_link_bytes`]).
    pub link_bytes: usize,
}

impl HbsFile {
    /// A file and its checksum; it crosses the link at its own length.
    #[must_use]
    pub fn new(name: impl Into<String>, bytes: Vec<u8>) -> Self {
        let md5 = md5_of(&bytes);
        let link_bytes = bytes.len();
        Self {
            name: name.into(),
            bytes,
            md5,
            link_bytes,
        }
    }

    /// The same file crossing the link as `link_bytes` bytes: a simulated stand-in for a
    /// flight product of that size (the post-drive NavCam images, from which the HBS builds
    /// the orthomosaic the simulator renders directly).
    #[must_use]
    pub fn with_link_bytes(mut self, link_bytes: usize) -> Self {
        self.link_bytes = link_bytes;
        self
    }

    /// Whether the contents still match the checksum.
    #[must_use]
    pub fn intact(&self) -> bool {
        md5_of(&self.bytes) == self.md5
    }
}

fn md5_of(bytes: &[u8]) -> [u8; 16] {
    Md5::digest(bytes).into()
}

/// A radiation upset that was injected.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum Upset {
    /// Bit flip in a stored input file.
    Storage,
    /// Bit flip in the input's in-memory copy during run 1 or 2.
    Memory,
    /// Bit flip in a result file.
    Output,
    /// A run stalled.
    Stall,
}

/// Why a localization was not applied.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub enum LossReason {
    /// An input file failed its checksum before a run.
    InputChecksum {
        /// The file.
        file: String,
        /// Before which run (1 or 2).
        run: u8,
    },
    /// A run exceeded its timeout.
    Timeout {
        /// Which run.
        run: u8,
    },
    /// A result file failed its checksum on the rover.
    OutputChecksum {
        /// Which run's result.
        run: u8,
    },
    /// The two result files differ.
    ResultsDiffer,
    /// The result failed the localizer's own validity checks.
    Invalid {
        /// What the check said.
        reason: String,
    },
}

impl std::fmt::Display for LossReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LossReason::InputChecksum { file, run } => {
                write!(f, "input file {file} failed its MD5 check before run {run}")
            }
            LossReason::Timeout { run } => write!(f, "run {run} timed out (HBS stall)"),
            LossReason::OutputChecksum { run } => {
                write!(f, "result file of run {run} failed its MD5 check")
            }
            LossReason::ResultsDiffer => write!(f, "the two result files differ"),
            LossReason::Invalid { reason } => write!(f, "validity checks failed: {reason}"),
        }
    }
}

/// A step of the onboard localization activity (paper 000 Fig. 19): the rover's flight
/// commands and the co-processor steps between them, in the order they run. Serialised and
/// displayed as the flight-style name ([`HbsStep::name`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub enum HbsStep {
    /// `MOB_WRITE_ONBD_INPUT_FILE`: the rover writes the input files and their checksums.
    #[serde(rename = "MOB_WRITE_ONBD_INPUT_FILE")]
    WriteInputFile,
    /// `TRANSFER_TO_HBS`: the inputs cross the serial link to the co-processor.
    #[serde(rename = "TRANSFER_TO_HBS")]
    TransferToHbs,
    /// `RUN_1`: the first localization run.
    #[serde(rename = "RUN_1")]
    Run1,
    /// `REBOOT`: the co-processor reboots between the runs.
    #[serde(rename = "REBOOT")]
    Reboot,
    /// `RUN_2`: the second localization run.
    #[serde(rename = "RUN_2")]
    Run2,
    /// `TRANSFER_TO_RCE`: the two result files come back to the rover computer.
    #[serde(rename = "TRANSFER_TO_RCE")]
    TransferToRce,
    /// `COMPARE`: the rover checks the result checksums and compares the two results.
    #[serde(rename = "COMPARE")]
    Compare,
    /// `MOB_APPLY_ONBD_LOCALIZATION`: the rover applies the result if its validity checks pass.
    #[serde(rename = "MOB_APPLY_ONBD_LOCALIZATION")]
    ApplyLocalization,
}

impl HbsStep {
    /// The flight-style name (`MOB_WRITE_ONBD_INPUT_FILE`, `TRANSFER_TO_HBS`, `RUN_1`, …).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            HbsStep::WriteInputFile => "MOB_WRITE_ONBD_INPUT_FILE",
            HbsStep::TransferToHbs => "TRANSFER_TO_HBS",
            HbsStep::Run1 => "RUN_1",
            HbsStep::Reboot => "REBOOT",
            HbsStep::Run2 => "RUN_2",
            HbsStep::TransferToRce => "TRANSFER_TO_RCE",
            HbsStep::Compare => "COMPARE",
            HbsStep::ApplyLocalization => "MOB_APPLY_ONBD_LOCALIZATION",
        }
    }
}

impl std::fmt::Display for HbsStep {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.pad(self.name())
    }
}

/// One step of the activity, for the sol log.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct HbsEvent {
    /// Seconds since the activity started.
    pub t_s: f64,
    /// The step: a flight command or a co-processor step.
    pub step: HbsStep,
    /// What happened.
    pub detail: String,
}

/// What the activity did.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ActivityLog {
    /// The steps in order.
    pub events: Vec<HbsEvent>,
    /// Upsets injected (whether or not they changed anything).
    pub upsets: Vec<Upset>,
    /// Total duration, seconds.
    pub duration_s: f64,
    /// `Ok(result bytes)` if applied, else why the localization was lost.
    #[serde(skip)]
    pub outcome: Result<Vec<u8>, LossReason>,
}

impl ActivityLog {
    fn event(&mut self, step: HbsStep, detail: impl Into<String>) {
        self.events.push(HbsEvent {
            t_s: self.duration_s,
            step,
            detail: detail.into(),
        });
    }
}

/// Flip one random bit of `bytes` (no-op on an empty slice).
fn flip_bit(bytes: &mut [u8], rng: &mut ChaCha8Rng) {
    if bytes.is_empty() {
        return;
    }
    let i = rng.random_range(0..bytes.len());
    let bit = rng.random_range(0..8u32);
    bytes[i] ^= 1 << bit;
}

/// Run the onboard-localization activity of paper 000 Fig. 19 on `inputs`.
///
/// `algorithm` maps the input files to a result file; it must be deterministic (the double run
/// relies on it). `validate` is the rover's validity check on an (uncorrupted) result. The fault
/// draws come from `rng` in a fixed order, so a seed replays a run exactly.
pub fn run_activity(
    inputs: &[HbsFile],
    params: &HbsSettings,
    rng: &mut ChaCha8Rng,
    algorithm: impl Fn(&[HbsFile]) -> Vec<u8>,
    validate: impl Fn(&[u8]) -> Result<(), String>,
) -> ActivityLog {
    let mut log = ActivityLog {
        events: Vec::new(),
        upsets: Vec::new(),
        duration_s: 0.0,
        outcome: Err(LossReason::ResultsDiffer),
    };
    let link_bytes: usize = inputs.iter().map(|f| f.link_bytes).sum();
    log.event(
        HbsStep::WriteInputFile,
        format!("{} files, {link_bytes} bytes, MD5 recorded", inputs.len()),
    );
    log.duration_s += link_bytes as f64 / params.link_bytes_per_s;
    log.event(
        HbsStep::TransferToHbs,
        format!("{link_bytes} bytes at {} B/s", params.link_bytes_per_s),
    );
    let mut stored: Vec<HbsFile> = inputs.to_vec();
    // Files whose checksum is to be checked before the next run: all before run 1; before run
    // 2 only those a storage upset changed since (the others passed run 1's check unchanged).
    let mut unchecked: Vec<usize> = (0..stored.len()).collect();

    let mut results: Vec<HbsFile> = Vec::with_capacity(2);
    for run in 1..=2u8 {
        if run == 2 {
            log.duration_s += params.reboot_s;
            log.event(HbsStep::Reboot, "HBS rebooted between runs");
        }
        // Storage upsets strike the stored files before this run reads them.
        if rng.random::<f64>() < params.p_flip_storage {
            let k = rng.random_range(0..stored.len().max(1));
            if let Some(f) = stored.get_mut(k) {
                flip_bit(&mut f.bytes, rng);
                log.upsets.push(Upset::Storage);
                unchecked.push(k);
            }
        }
        let step = if run == 1 {
            HbsStep::Run1
        } else {
            HbsStep::Run2
        };
        unchecked.sort_unstable();
        unchecked.dedup();
        let bad = unchecked.iter().map(|&k| &stored[k]).find(|f| !f.intact());
        unchecked.clear();
        if let Some(bad) = bad {
            log.event(
                step,
                format!("{} failed its MD5 check; run not started", bad.name),
            );
            log.outcome = Err(LossReason::InputChecksum {
                file: bad.name.clone(),
                run,
            });
            return log;
        }
        if rng.random::<f64>() < params.p_stall {
            log.upsets.push(Upset::Stall);
            log.duration_s += params.run_timeout_s;
            log.event(
                step,
                format!("no result after {} s: aborted", params.run_timeout_s),
            );
            log.outcome = Err(LossReason::Timeout { run });
            return log;
        }
        // The run works on an in-memory copy that may take an upset after the checksum check
        // (copied only when it does: otherwise it equals the stored files).
        let bytes = if rng.random::<f64>() < params.p_flip_memory {
            let mut memory = stored.clone();
            let k = rng.random_range(0..memory.len().max(1));
            if let Some(f) = memory.get_mut(k) {
                flip_bit(&mut f.bytes, rng);
                log.upsets.push(Upset::Memory);
            }
            algorithm(&memory)
        } else {
            algorithm(&stored)
        };
        let result = HbsFile::new(format!("onbd_result_{run}.dat"), bytes);
        log.duration_s += params.run_s;
        log.event(
            step,
            format!("result {} bytes, MD5 recorded", result.bytes.len()),
        );
        results.push(result);
    }

    let out_bytes: usize = results.iter().map(|f| f.bytes.len()).sum();
    for r in &mut results {
        if rng.random::<f64>() < params.p_flip_output {
            flip_bit(&mut r.bytes, rng);
            log.upsets.push(Upset::Output);
        }
    }
    log.duration_s += out_bytes as f64 / params.link_bytes_per_s;
    log.event(HbsStep::TransferToRce, format!("{out_bytes} bytes"));
    for (run, r) in (1u8..).zip(&results) {
        if !r.intact() {
            log.event(HbsStep::Compare, format!("{} failed its MD5 check", r.name));
            log.outcome = Err(LossReason::OutputChecksum { run });
            return log;
        }
    }
    if results[0].bytes != results[1].bytes {
        log.event(HbsStep::Compare, "result files differ: not applied");
        log.outcome = Err(LossReason::ResultsDiffer);
        return log;
    }
    log.event(HbsStep::Compare, "result files identical");
    let result = results.swap_remove(0).bytes;
    match validate(&result) {
        Ok(()) => {
            log.event(
                HbsStep::ApplyLocalization,
                "validity checks passed: applied",
            );
            log.outcome = Ok(result);
        }
        Err(reason) => {
            log.event(
                HbsStep::ApplyLocalization,
                format!("validity checks failed: {reason}"),
            );
            log.outcome = Err(LossReason::Invalid { reason });
        }
    }
    log
}

/// Counts of a seeded upset-injection campaign (see [`seu_campaign`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct SeuCounts {
    /// Activities run.
    pub runs: u32,
    /// Upsets injected.
    pub upsets_injected: u32,
    /// Activities with at least one upset.
    pub runs_with_upsets: u32,
    /// Activities whose upset was caught (checksum, comparison, timeout or validity check).
    pub caught: u32,
    /// Activities with an upset that changed nothing (e.g. the flipped bit was never read) and
    /// whose result, identical to the fault-free one, was applied.
    pub harmless: u32,
    /// Localizations lost (not applied) for any reason.
    pub lost: u32,
    /// Results applied that differ from the fault-free result. Must be zero.
    pub corrupted_applied: u32,
}

/// Run `runs` activities with upsets injected, from `seed`, and count what happened. `validate`
/// is the rover's validity check on a result (as in [`run_activity`]). Every applied result is
/// compared with the fault-free result of the same inputs. `done(n)` is called after run `n`
/// (1-based), for a progress bar.
pub fn seu_campaign(
    runs: u32,
    seed: u64,
    params: &HbsSettings,
    inputs: &[HbsFile],
    algorithm: impl Fn(&[HbsFile]) -> Vec<u8>,
    validate: impl Fn(&[u8]) -> Result<(), String>,
    done: impl Fn(u32),
) -> SeuCounts {
    use rand::SeedableRng;
    let golden = algorithm(inputs);
    let mut c = SeuCounts {
        runs,
        ..Default::default()
    };
    for run in 0..runs {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(u64::from(run));
        let log = run_activity(inputs, params, &mut rng, &algorithm, &validate);
        c.upsets_injected += log.upsets.len() as u32;
        let upset = !log.upsets.is_empty();
        c.runs_with_upsets += u32::from(upset);
        match &log.outcome {
            Ok(result) if *result != golden => c.corrupted_applied += 1,
            Ok(_) => c.harmless += u32::from(upset),
            Err(_) => {
                c.lost += 1;
                c.caught += u32::from(upset);
            }
        }
        done(run + 1);
    }
    c
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    fn inputs() -> Vec<HbsFile> {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let image: Vec<u8> = (0..20_000).map(|_| rng.random()).collect();
        vec![
            HbsFile::new("pose.txt", b"x=1 y=2 r=20".to_vec()),
            HbsFile::new("ortho.bin", image),
        ]
    }

    /// A stand-in algorithm that reads every input byte (a digest of them).
    fn algorithm(files: &[HbsFile]) -> Vec<u8> {
        let mut h = Md5::new();
        for f in files {
            h.update(&f.bytes);
        }
        h.finalize().to_vec()
    }

    #[test]
    fn nominal_run_applies_and_times_the_link() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let p = HbsSettings::default();
        let log = run_activity(&inputs(), &p, &mut rng, algorithm, |_| Ok(()));
        assert_eq!(log.outcome, Ok(algorithm(&inputs())));
        assert!(log.upsets.is_empty());
        let bytes = 20_000.0 + 12.0;
        let expected = bytes / 10_000.0 + 2.0 * 32.0 + 120.0 + 32.0 / 10_000.0;
        assert!(
            (log.duration_s - expected).abs() < 1e-9,
            "{}",
            log.duration_s
        );
        let steps: Vec<_> = log.events.iter().map(|e| e.step).collect();
        assert_eq!(
            steps,
            [
                HbsStep::WriteInputFile,
                HbsStep::TransferToHbs,
                HbsStep::Run1,
                HbsStep::Reboot,
                HbsStep::Run2,
                HbsStep::TransferToRce,
                HbsStep::Compare,
                HbsStep::ApplyLocalization
            ]
        );
        let names: Vec<String> = steps.iter().map(ToString::to_string).collect();
        assert_eq!(
            names,
            [
                "MOB_WRITE_ONBD_INPUT_FILE",
                "TRANSFER_TO_HBS",
                "RUN_1",
                "REBOOT",
                "RUN_2",
                "TRANSFER_TO_RCE",
                "COMPARE",
                "MOB_APPLY_ONBD_LOCALIZATION"
            ]
        );
    }

    #[test]
    fn each_upset_kind_is_caught() {
        let cases = [
            (
                HbsSettings {
                    p_flip_storage: 1.0,
                    ..Default::default()
                },
                "InputChecksum",
            ),
            (
                HbsSettings {
                    p_flip_memory: 1.0,
                    ..Default::default()
                },
                "ResultsDiffer",
            ),
            (
                HbsSettings {
                    p_flip_output: 1.0,
                    ..Default::default()
                },
                "OutputChecksum",
            ),
            (
                HbsSettings {
                    p_stall: 1.0,
                    ..Default::default()
                },
                "Timeout",
            ),
        ];
        for (p, kind) in cases {
            let mut rng = ChaCha8Rng::seed_from_u64(9);
            let log = run_activity(&inputs(), &p, &mut rng, algorithm, |_| Ok(()));
            let err = log.outcome.clone().unwrap_err();
            assert!(format!("{err:?}").starts_with(kind), "{kind}: got {err:?}");
            assert!(
                !log.events
                    .iter()
                    .any(|e| e.step == HbsStep::ApplyLocalization)
            );
        }
    }

    #[test]
    fn invalid_results_are_not_applied() {
        let mut rng = ChaCha8Rng::seed_from_u64(2);
        let log = run_activity(
            &inputs(),
            &HbsSettings::default(),
            &mut rng,
            algorithm,
            |_| Err("ambiguous peak".into()),
        );
        assert_eq!(
            log.outcome,
            Err(LossReason::Invalid {
                reason: "ambiguous peak".into()
            })
        );
    }

    /// Paper 000 §7's promise: a corrupted run is caught and never applied — over 2,000 seeded
    /// activities with every kind of upset injected at high rates.
    #[test]
    fn no_corrupted_result_is_ever_applied() {
        let p = HbsSettings {
            p_flip_storage: 0.1,
            p_flip_memory: 0.2,
            p_flip_output: 0.1,
            p_stall: 0.05,
            ..Default::default()
        };
        let c = seu_campaign(2000, 42, &p, &inputs(), algorithm, |_| Ok(()), |_| {});
        assert_eq!(c.corrupted_applied, 0, "{c:?}");
        assert!(c.upsets_injected > 500, "{c:?}");
        assert_eq!(c.caught + c.harmless, c.runs_with_upsets, "{c:?}");
        assert_eq!(c.lost, c.caught, "{c:?}");
        // Same seed, same counts.
        assert_eq!(
            c,
            seu_campaign(2000, 42, &p, &inputs(), algorithm, |_| Ok(()), |_| {})
        );
    }
}
