//! Where a starter scenario (`solsim init`, `solsim route import`) is written and what is said
//! about it: the scenario file and its map folder (`NAME.map/`), the checks before anything is
//! written (the options, the name, files in the way), the map seeds tried, and the summary.
//!
//! The writing itself is the caller's (the command writes the map folder as one output set and
//! the scenario file last, so a scenario file never names a map that is not there): this
//! module decides and describes, [`crate::starter`] makes the texts.

use std::path::{Path, PathBuf};

use maps::MemoryBudget;

use crate::ScenarioError;
use crate::starter::{
    MAP_MARGIN_EXPECTED, MAP_MARGIN_RANGE_M, Starter, StarterOptions, TrackPoint,
};

/// Map seeds tried, from the scenario's seed on, before the route is reported as blocked.
pub const MAP_SEED_ATTEMPTS: u64 = 8;

/// Why a starter scenario cannot be written.
#[derive(Debug, thiserror::Error)]
pub enum StarterError {
    /// The scenario file's name does not end in `.toml`.
    #[error("{}: expected a scenario file name ending in .toml", path.display())]
    NotToml {
        /// The scenario file asked for.
        path: PathBuf,
    },
    /// An option is out of range.
    #[error("{option}: expected {expected}, got {got}")]
    Option {
        /// The option, e.g. `--map-margin-m`.
        option: &'static str,
        /// What is allowed.
        expected: &'static str,
        /// What was given.
        got: String,
    },
    /// `--name` is not a usable scenario name.
    #[error("--name: expected {expected}")]
    Name {
        /// What a name must be.
        expected: String,
    },
    /// Without `--name`, the file name makes the scenario name, and it is not a usable one.
    #[error("{}: the file name makes the scenario name: expected {expected} (or give --name)", path.display())]
    FileName {
        /// The scenario file asked for.
        path: PathBuf,
        /// What a name must be.
        expected: String,
    },
    /// A file or folder to be written exists, and `--force` was not given.
    #[error("{}: expected a new file, but it exists; pass --force to replace it", path.display())]
    Exists {
        /// The file or folder.
        path: PathBuf,
    },
    /// The scenario file asked for is a directory.
    #[error("{}: expected a file, found a directory", path.display())]
    Directory {
        /// The scenario file asked for.
        path: PathBuf,
    },
    /// Every map seed tried puts a waypoint where the map blocks it.
    #[error(
        "{}: the procedural maps of seeds {first}..={last} all block the route ({rejected}); move the points, or try another --seed",
        track.display()
    )]
    Blocked {
        /// The track file.
        track: PathBuf,
        /// The first seed tried.
        first: u64,
        /// The last seed tried.
        last: u64,
        /// Each seed with the field of the first error it gave, `; `-separated.
        rejected: String,
    },
    /// The track cannot be placed on a map.
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
}

/// What a starter scenario was asked, besides its track: the options of `solsim init` and
/// `solsim route import`.
#[derive(Clone, Debug, PartialEq)]
pub struct StarterRequest {
    /// Replace an existing scenario file and map folder.
    pub force: bool,
    /// Scenario name (default: the file name without `.toml`).
    pub name: Option<String>,
    /// Scenario seed, and the procedural map's (default: the first sol).
    pub seed: Option<u64>,
    /// Map margin around the route's bounding box, metres.
    pub map_margin_m: f64,
    /// First sol of the computed calendar.
    pub first_sol: u32,
    /// What the route came from, for the scenario's header and the summary.
    pub source: String,
    /// Add one example keep-out beside the route.
    pub example_keep_out: bool,
}

/// The companions of scenario file `scenario`: its map folder (`NAME.map/`).
///
/// # Errors
/// A path that does not end in `.toml`.
pub fn map_dir_of(scenario: &Path) -> Result<PathBuf, StarterError> {
    let is_toml = scenario
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("toml"));
    let Some(stem) = scenario.file_stem().filter(|_| is_toml) else {
        return Err(StarterError::NotToml {
            path: scenario.to_path_buf(),
        });
    };
    let mut name = stem.to_os_string();
    name.push(".map");
    Ok(scenario.with_file_name(name))
}

/// A starter scenario placed and checked, ready to be written: the scenario file, its map
/// folder and the [`Starter`] that makes their texts.
#[derive(Clone, Debug)]
pub struct StarterFiles {
    /// The scenario file to write.
    pub scenario: PathBuf,
    /// Its map folder.
    pub map_dir: PathBuf,
    /// The map folder's name, as the scenario file names it.
    pub map_name: String,
    /// The texts.
    pub starter: Starter,
}

impl StarterFiles {
    /// Places `track` (read from `track_path`) for the scenario file `scenario`: checks the
    /// options and the name, makes the [`Starter`], and checks that nothing is in the way
    /// (without `force`, an existing scenario file or map folder; a directory where the
    /// scenario file goes).
    ///
    /// # Errors
    /// Any of [`StarterError`]'s, but [`StarterError::Blocked`].
    pub fn plan(
        scenario: &Path,
        track_path: &Path,
        track: &[TrackPoint],
        request: &StarterRequest,
        budget: MemoryBudget,
    ) -> Result<Self, StarterError> {
        let map_dir = map_dir_of(scenario)?;
        if !MAP_MARGIN_RANGE_M.contains(&request.map_margin_m) {
            return Err(StarterError::Option {
                option: "--map-margin-m",
                expected: MAP_MARGIN_EXPECTED,
                got: request.map_margin_m.to_string(),
            });
        }
        let name = match &request.name {
            Some(n) => {
                crate::scenario::check_name(n)
                    .map_err(|expected| StarterError::Name { expected })?;
                n.clone()
            }
            None => {
                let stem = scenario
                    .file_stem()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_default();
                crate::scenario::check_name(&stem).map_err(|expected| StarterError::FileName {
                    path: scenario.to_path_buf(),
                    expected,
                })?;
                stem
            }
        };
        let mut options = StarterOptions::new(&name, &request.source);
        options.first_sol = request.first_sol;
        options.seed = request.seed.unwrap_or(u64::from(request.first_sol));
        options.map_margin_m = request.map_margin_m;
        options.example_keep_out = request.example_keep_out;
        let starter = Starter::new(track_path, track, &options, budget)?;

        // Nothing is replaced without --force; with it, the map folder only if solsim wrote
        // it (the caller's output set checks that).
        for p in [scenario, map_dir.as_path()] {
            if p.symlink_metadata().is_ok() && !request.force {
                return Err(StarterError::Exists {
                    path: p.to_path_buf(),
                });
            }
        }
        if scenario.is_dir() {
            return Err(StarterError::Directory {
                path: scenario.to_path_buf(),
            });
        }
        let map_name = map_dir
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        Ok(Self {
            scenario: scenario.to_path_buf(),
            map_dir,
            map_name,
            starter,
        })
    }

    /// The map seeds to try, in order: [`MAP_SEED_ATTEMPTS`] from the scenario's seed on.
    pub fn map_seeds(&self) -> impl Iterator<Item = u64> + use<> {
        let seed = self.starter.options.seed;
        (0..MAP_SEED_ATTEMPTS).map(move |attempt| seed.wrapping_add(attempt))
    }

    /// The error when every map seed blocks the route; `rejected` holds each seed with the
    /// field of its first error.
    #[must_use]
    pub fn blocked(&self, track_path: &Path, rejected: &[String]) -> StarterError {
        let seed = self.starter.options.seed;
        StarterError::Blocked {
            track: track_path.to_path_buf(),
            first: seed,
            last: seed.wrapping_add(MAP_SEED_ATTEMPTS - 1),
            rejected: rejected.join("; "),
        }
    }

    /// The scenario file's text, on the map of `map_seed` in the map folder.
    #[must_use]
    pub fn scenario_toml(&self, map_seed: u64) -> String {
        let map = &self.map_name;
        self.starter
            .scenario_toml(map, &format!("{map}/zones.geojson"), map_seed)
    }

    /// What was written, on the map of `map_seed` after `seeds_rejected` seeds blocked the
    /// route, and the next three commands.
    #[must_use]
    pub fn summary(&self, map_seed: u64, seeds_rejected: usize) -> String {
        let (starter, options) = (&self.starter, &self.starter.options);
        let [w, h] = starter.map_px;
        let r = starter.resolution_m_per_px;
        let mut t = format!(
            "wrote {} (+ {}/: map, recipe.toml, zones.geojson): {} waypoints, {:.0} m of route from {}\n",
            self.scenario.display(),
            self.map_dir.display(),
            starter.route_m.len(),
            starter.route_length_m,
            options.source,
        );
        t.push_str(&format!(
            "  map: {:.0} × {:.0} m at {r} m/px, {} m around the route, procedural (seed {map_seed}{}); CRS {}\n",
            w as f64 * r,
            h as f64 * r,
            options.map_margin_m,
            if seeds_rejected == 0 {
                String::new()
            } else {
                format!(
                    "; seed{} {} put a waypoint where the map blocks it",
                    if seeds_rejected == 1 { "" } else { "s" },
                    (options.seed..map_seed)
                        .map(|s| s.to_string())
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            },
            starter.crs.name()
        ));
        if (starter.easting_scale - 1.0).abs() > 0.01 {
            t.push_str(&format!(
                "  note: the track lies far from 18.4663° N, where the projection is true to scale: east-west map metres are {:.3} ground metres\n",
                1.0 / starter.easting_scale
            ));
        }
        t.push_str(&format!(
            "  calendar: Mars 2020 sols {}-{}, computed (uplinks, weekends, restricted sols); zones: {}\n",
            starter.sols.start(),
            starter.sols.end(),
            if options.example_keep_out {
                "one example keep-out"
            } else {
                "none yet (add keep-outs to zones.geojson)"
            }
        ));
        let s = self.scenario.display();
        t.push_str(&format!(
            "next:\n  solsim validate {s}\n  solsim compare {s}\n  solsim compare {s} --runs 100 --report\n"
        ));
        t
    }
}
