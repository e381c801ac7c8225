//! # planner — campaign intents and an anytime branch-and-bound activity scheduler
//!
//! Lays out one sol of rover activities under time, energy and data-volume limits so as to
//! best satisfy the operators' campaign intents (paper 003 §2–§3). The crate knows
//! activities and resources, not rovers.
//!
//! | Item | What it is |
//! |---|---|
//! | [`Problem`], [`Activity`], [`Drive`], [`Campaign`] | the serde (JSON) description of a sol |
//! | [`Instance`] | a validated problem with drives split into [`Task`]s |
//! | [`plan`], [`plan_from`] | branch and bound from the start of the sol, or from a [`State`] (replanning) |
//! | [`SearchSettings`], [`BoundKind`] | budgets and the optimistic bound |
//! | [`PlanOutcome`], [`Plan`], [`Value`] | the best plan, its lexicographic value, the best bound and the gap |
//! | [`Timeline`] | the main sequencing timeline and the HBS link: an activity on the link alone runs in parallel with main-timeline ones |
//! | [`validate_plan`], [`step_resources`] | an independent checker listing every [`Violation`]; its re-simulation step by step |
//! | [`repair`], [`RepairOutcome`], [`Blocker`] | shift a plan after a slip, or say why a replan is needed |
//! | [`periodic_instances`], [`state_based_instances`], [`clip_to_window`] | build periodic and state-based campaign instances; clip them to the sol |
//! | [`generate`] | seeded random instances |
//! | [`optimistic_bound`] | the bound the search prunes with, for tests and comparison |
//!
//! ```
//! use planner::{Activity, Problem, SearchSettings, State, Instance, plan, validate_plan};
//!
//! let mut comm = Activity::task("relay", 600, [43_200, 43_200], 10.0, 0.0);
//! comm.mandatory = true;
//! comm.downlink_mb = 300.0;
//! let mut pancam = Activity::task("pancam", 1_800, [36_000, 50_000], 30.0, 5.0);
//! pancam.data_mb = 200.0;
//! let problem = Problem {
//!     start_s: 32_400,
//!     end_s: 61_200,
//!     battery_capacity_wh: 100.0,
//!     initial_energy_wh: 60.0,
//!     recharge_w: 5.0,
//!     data_capacity_mb: 250.0,
//!     initial_data_mb: 0.0,
//!     activities: vec![comm, pancam, Activity::task("tau", 300, [36_000, 36_900], 8.0, 1.0)],
//!     campaigns: vec![],
//! };
//! let outcome = plan(&problem, &SearchSettings::default())?;
//! assert!(outcome.is_proven_optimal());
//! assert_eq!(outcome.value.points(1), 6.0);
//! let instance = Instance::new(&problem)?;
//! assert!(validate_plan(&instance, &State::initial(&instance), &outcome.plan).is_empty());
//! # Ok::<(), planner::PlanError>(())
//! ```
//!
//! ## What is modelled, what is simplified
//!
//! | Aspect | Modelled | Simplified / missing |
//! |---|---|---|
//! | Time | integer seconds after midnight; one activity at a time per [`Timeline`]: the main one, and the HBS link, whose activities run in parallel with main-timeline ones (preconditions wait for their predecessors' ends) | no other parallel resource |
//! | Waiting | a task starts at the earliest second its window, its predecessor and the battery allow (waiting to recharge included); complete for this model, see [`State`] | on two timelines, a task the battery cannot carry while another runs waits for that one's end, then for recharge (a rule, not a search over waits) |
//! | Energy | battery with capacity (recharge clipped), constant net recharge `recharge_w`, constant power per activity (overlapping activities' powers add), never below 0 | no solar profile over the sol, no regenerative-sleep activity |
//! | Data | produced at an activity's end, freed by downlinks (comm passes) | downlink at the pass's end, not during it |
//! | Mandatory | tasks every plan must hold (comm passes at fixed times) | — |
//! | Auxiliary | preconditions (heating before a drive) | no maximum gap between heating and use |
//! | Drives | pre-split into `k` equal segments (or at given distances) run in order; the drive's utility shared among the segments by length, so a plan earns it in proportion to the metres driven | split points fixed before search |
//! | Goal set | utility by count with `min_count`, `max_count`, decay | utility does not depend on which members |
//! | Periodic | instances at absolute due times ± tolerance | cadence not relative to the previous instance |
//! | State-based | instances allowed only while metres driven ∈ `k·every ± tolerance` | — |
//! | Tiers | lexicographic [`Value`] of exact integers per tier (up to 4 tiers) | — |
//!
//! ## The two optimistic bounds
//! [`BoundKind::Knapsack`] (fractional knapsacks on time, energy and data, each alone but
//! under nested deadline / release rows, and capped utility sums) and [`BoundKind::Lp`] (one clarabel LP over all three resources with
//! deadline, release, precedence and campaign-cap rows, certified by weak duality so solver
//! inaccuracy cannot make it inadmissible). Both are admissible: `tests/exhaustive.rs`
//! checks every tier of each against the exhaustive optimum on ~1 200 random nodes (initial
//! states and random partial plans of instances of ≤ 8 tasks). Measured with
//! `examples/bound_compare.rs` (generated instances, wall clock via `Instant` summed over the
//! search; release build on a loaded 2-core machine, so ratios matter more than absolute
//! times) and `examples/plan_generated.rs`:
//!
//! | | Knapsack | LP |
//! |---|---|---|
//! | mean excess over the optimum at random nodes, ≤ 8 tasks (points, all tiers) | 5.1 | 4.3 |
//! | root excess over the best value found, 8 / 16 / 25 optional activities (points) | 16.2 / 28.9 / 44.2 | 13.8 / 26.3 / 35.8 |
//! | one root evaluation, 8 / 16 / 25 optional | 3 / 8 / 19 µs | 0.46 / 1.4 / 2.7 ms |
//! | search time per expanded node, 8 / 16 / 25 optional | 6 / 8 / 12 µs | 150 / 180 / 270 µs |
//! | mean nodes to prove optimality, 8 / 16 optional | 49 / 3 663 | 44 / 3 302 |
//! | 86-task instance (80 optional, seed 80): tier-1 gap | 12.8 after 20 000 nodes (3.7 s) | 6.2 after 200 nodes (5.0 s, `Both`) |
//!
//! The table above predates the B6 work (2026-11-25). Since then the knapsack bound has
//! nested deadline and release rows, rounding to the utility grain (whole points), a
//! Lagrangian coupling of tied tiers, precomputed density orders, precedences priced in (part
//! of a task's utility moves to its undone precondition: `u·x ≤ u·x + μ(x_q − x_i)` on every
//! completion) and exact 0/1 time knapsacks solved by a dynamic program over the nested rows
//! when the fractional ones leave a node undecided. The LP still holds rows the knapsacks lack
//! (all resources at once, window and campaign rows), so it is not uniformly looser or
//! tighter; on the B6 instances ([`b6_problem`], 20/40/80 optional activities) `Knapsack`
//! proves optimality in 0.5–142 ms; on the 40- and 80-activity ones it is 38–71× faster than
//! [`BoundKind::Both`] (the knapsack first, LPs only for nodes it cannot prune), which expands
//! from 21 % fewer to twice as many nodes (`examples/b6_solve.rs`, bound 0 against 2).
//! `Knapsack` is therefore the default; BENCHMARKS.md, "Activity planner (B6)", compares it
//! with OR-Tools CP-SAT.
//!
//! Issue 16 added to `Knapsack` (and `Both`) a *time-indexed* bound: the main timeline as a
//! longest path over one-minute slots with every candidate inside its window, the
//! "at most once" and precedence constraints priced by Lagrange multipliers tuned at the root
//! (`bound::indexed`). Knapsacks see how much time tasks need, not whether their windows
//! collide; on B6 n = 160 seed 3 the root bound falls from 114 to 102 points (optimum 99). The
//! search uses it after an opening dive of [`SearchSettings::dive_nodes`] expansions, then goes
//! best-first; [`optimistic_bound`] includes it.
//!
//! ## References
//! Paper 003 §2 (architecture: goal planner, executive), §3 (campaign intent, Fig. 2),
//! §3.1 (branch and bound, anytime, repair, Fig. 3), §5 (illustrative scenario: replanning
//! after new goals and drive delays).
#![warn(missing_docs)]

mod bound;
mod campaign;
mod curve;
mod error;
mod generate;
mod instance;
mod instance_checks;
mod plan;
mod problem;
mod repair;
mod search;
mod state;
mod validate;
mod value;

pub use bound::optimistic_bound;
pub use campaign::{clip_to_window, periodic_instances, state_based_instances};
pub use curve::CampaignCurve;
pub use error::PlanError;
pub use generate::{GeneratorSettings, b6_problem, generate};
pub use instance::{Instance, Task, TaskId};
pub use plan::{BoundKind, Plan, PlanOutcome, PlanStatus, PlanStep, SearchSettings, SearchStats};
pub use problem::{Activity, ActivityKind, Campaign, CampaignIntent, Drive, Problem, Timeline};
pub use repair::{RepairOutcome, repair};
pub use search::{plan, plan_from};
pub use state::{Blocker, DATA_EPS_MB, DISTANCE_EPS_M, ENERGY_EPS_WH, Running, State};
pub use validate::{StepResources, Violation, step_resources, validate_plan};
pub use value::{MAX_TASKS, MAX_TIERS, MAX_UTILITY, MICRO_PER_POINT, Value};
