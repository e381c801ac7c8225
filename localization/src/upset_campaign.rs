//! A seeded radiation-upset campaign on a real onboard localization (`solsim seu-campaign`):
//! census matching on a synthetic post-drive scene, run again and again through the
//! co-processor model ([`crate::hbs`]) with bit flips injected into its stored inputs, its
//! memory and its results, and stalls; the counts of what was caught, lost, harmless — and
//! applied although corrupted, which must never happen.

use std::fmt::Write as _;

use crate::benchmark_set::{BenchmarkMaps, TerrainKind};
use crate::hbs::{HbsFile, HbsSettings, SeuCounts, seu_campaign};
use crate::matcher::{MatchSettings, OrbitalMap, RoverImages, localize};
use crate::onboard::{decode_u8, encode_u8};
use crate::synthetic::{
    OrbitalSettings, RoverImagingSettings, SyntheticError, render_orbital, render_rover,
    truth_patch,
};

/// The settings of a campaign, named as `solsim seu-campaign`'s options.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UpsetCampaign {
    /// Onboard-localization activities to run, each with upsets drawn from its own stream.
    pub runs: u32,
    /// Master seed of the upset draws.
    pub seed: u64,
    /// Probability that a stored input file takes a bit flip before a run (`--p-storage`).
    pub p_storage: f64,
    /// Probability that the input's in-memory copy takes a bit flip during a run
    /// (`--p-memory`).
    pub p_memory: f64,
    /// Probability that a result file takes a bit flip (`--p-output`).
    pub p_output: f64,
    /// Probability that a run stalls (`--p-stall`).
    pub p_stall: f64,
}

/// Why a campaign could not run.
#[derive(Debug, thiserror::Error)]
pub enum UpsetCampaignError {
    /// A probability outside 0 ..= 1.
    #[error("{option}: expected a probability between 0 and 1, got {got}")]
    Probability {
        /// The option (`--p-storage`, `--p-memory`, `--p-output`, `--p-stall`).
        option: &'static str,
        /// The value given.
        got: f64,
    },
    /// The synthetic scene could not be rendered.
    #[error(transparent)]
    Scene(#[from] SyntheticError),
}

/// The scene every activity of a campaign localizes in: the co-processor's input files (the
/// prior, the orthomosaic, the map tile) and the georeference of the two images.
#[derive(Clone, Debug)]
pub struct UpsetScene {
    inputs: Vec<HbsFile>,
    map_geo: maps::GeoTransform,
    ortho_geo: maps::GeoTransform,
}

impl UpsetCampaign {
    /// Checks the settings and renders the scene (a rocky benchmark map, the rover 7.2 m from
    /// its prior).
    ///
    /// # Errors
    /// A probability outside 0 ..= 1; a scene that cannot be rendered.
    pub fn scene(&self) -> Result<UpsetScene, UpsetCampaignError> {
        for (option, p) in [
            ("--p-storage", self.p_storage),
            ("--p-memory", self.p_memory),
            ("--p-output", self.p_output),
            ("--p-stall", self.p_stall),
        ] {
            if !(0.0..=1.0).contains(&p) {
                return Err(UpsetCampaignError::Probability { option, got: p });
            }
        }
        let maps = BenchmarkMaps::generate(1);
        let layers = maps.get(TerrainKind::Rocky);
        let truth = [300.0, 300.0];
        let patch = truth_patch(layers, truth, 80.0, 11)?;
        let orbital = render_orbital(&patch, &OrbitalSettings::default(), 12)?;
        let rover = render_rover(&patch, truth, &RoverImagingSettings::default(), 13)?;
        let prior = [truth[0] + 6.0, truth[1] - 4.0];
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
        Ok(UpsetScene {
            inputs,
            map_geo: orbital.appearance.geo,
            ortho_geo: rover.ortho.geo,
        })
    }

    /// Runs the campaign in `scene`; `done(n)` is called after activity `n` (1-based).
    #[must_use]
    pub fn run(&self, scene: &UpsetScene, done: impl Fn(u32)) -> SeuCounts {
        let (map_geo, ortho_geo) = (scene.map_geo, scene.ortho_geo);
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
            let map = OrbitalMap {
                appearance: &map,
                dem: None,
            };
            match localize(&map, &rover, prior, &MatchSettings::default()) {
                Ok(m) => format!(
                    "x_m={:.4} y_m={:.4} sigma_m={:.4} rejection={:?}\n",
                    m.position_m[0], m.position_m[1], m.sigma_m, m.rejection
                )
                .into_bytes(),
                Err(e) => format!("error: {e}\n").into_bytes(),
            }
        };
        let params = HbsSettings {
            p_flip_storage: self.p_storage,
            p_flip_memory: self.p_memory,
            p_flip_output: self.p_output,
            p_stall: self.p_stall,
            ..HbsSettings::default()
        };
        // MOB_APPLY_ONBD_LOCALIZATION's validity checks: a well-formed, accepted localization.
        let validate = |result: &[u8]| -> Result<(), String> {
            let text = std::str::from_utf8(result).map_err(|_| "result is not text".to_string())?;
            if text.starts_with("x_m=") && text.trim_end().ends_with("rejection=None") {
                Ok(())
            } else {
                Err(format!("not an accepted localization: {}", text.trim()))
            }
        };
        seu_campaign(
            self.runs,
            self.seed,
            &params,
            &scene.inputs,
            algorithm,
            validate,
            done,
        )
    }

    /// The counts as JSON: `{"runs", "seed", "probabilities": {...}, "counts": {...},
    /// "seconds"}`, `seconds` the wall time.
    #[must_use]
    pub fn json(&self, c: &SeuCounts, seconds: f64) -> serde_json::Value {
        serde_json::json!({
            "runs": c.runs,
            "seed": self.seed,
            "probabilities": {
                "storage": self.p_storage,
                "memory": self.p_memory,
                "output": self.p_output,
                "stall": self.p_stall,
            },
            "counts": c,
            "seconds": seconds,
        })
    }

    /// The counts as text, `seconds` the wall time.
    #[must_use]
    pub fn text(&self, c: &SeuCounts, seconds: f64) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "HBS upset-injection campaign: {} onboard localizations (census on a synthetic post-drive scene), seed {}",
            c.runs, self.seed
        );
        let _ = writeln!(
            s,
            "  upsets injected:                  {}",
            c.upsets_injected
        );
        let _ = writeln!(
            s,
            "  activities with an upset:         {}",
            c.runs_with_upsets
        );
        let _ = writeln!(
            s,
            "  caught (checksum, compare, timeout or validity check): {}",
            c.caught
        );
        let _ = writeln!(s, "  harmless (result unchanged):       {}", c.harmless);
        let _ = writeln!(s, "  localizations lost:               {}", c.lost);
        let _ = writeln!(
            s,
            "  corrupted results applied:        {}",
            c.corrupted_applied
        );
        let _ = writeln!(s, "  ({seconds:.1} s)");
        s
    }
}
