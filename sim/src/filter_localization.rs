//! The filter localizers at the end of a drive sol: the particle filter of paper 002 and the
//! EKF of paper 004 ([`crate::localizer::ParticleLocalizer`], [`crate::localizer::EkfLocalizer`]).
//!
//! Both start from the rover's uncertainty disc read as a 3σ bound around its estimate, and
//! both end with a 2×2 position covariance. That covariance becomes the disc the keep-out
//! zones grow by **conservatively**: its radius is 3 × the 1σ semi-major axis, so the disc
//! holds the whole 3σ ellipse (≥ 98.9 % of a Gaussian belief whatever its shape, against
//! 98.9 % for the 3σ ellipse itself). The disc is the localizer's σ in
//! [`crate::uncertainty::UncertaintyState::reset_onboard`], plus the operator margin, as the
//! statistical model's p99 is. The 1σ ellipse goes to the sol log ([`PositionEllipse`]).
//!
//! A filter result is applied only if it gains: its disc must be smaller than the radius the
//! rover had, and the particle belief must have one mode. Neither filter runs on the
//! co-processor's fault model; their activity keeps the chain's planned durations.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use crate::autonav::RoverState;
use crate::campaign::Campaign;
use crate::localizer::{EkfLocalizer, ParticleLocalizer};
use crate::outcome::{LocalizationEvent, PositionEllipse, RejectionReason};
use crate::seeds::{Purpose, stream_seed};
use crate::time::SolSeconds;
use localization::onboard::{LostReason, OnboardRequest, render_activity_imagery};
use localization::particle::{PanoramaFix, localize_panorama, no_gain};

/// Apply a filter's posterior (mean `mean_m`, 1σ ellipse) if its disc is smaller than the
/// radius `prior_r_m` the rover had; otherwise reject it for no gain.
fn apply_if_gain(
    event: &mut LocalizationEvent,
    c: &Campaign,
    state: &mut RoverState,
    prior_r_m: f64,
    mean_m: [f64; 2],
    ellipse: PositionEllipse,
) {
    let truth = state.truth.position_m;
    event.matched_error_m = Some((mean_m[0] - truth.x).hypot(mean_m[1] - truth.y));
    event.ellipse = Some(ellipse);
    if ellipse.disc_radius_m < prior_r_m {
        state.estimate.position_m = nalgebra::Vector2::new(mean_m[0], mean_m[1]);
        state
            .uncertainty
            .reset_onboard(ellipse.disc_radius_m, c.operator_margin_m);
        state.clear_path();
        event.applied = true;
        event.error_m = event.matched_error_m;
        event.sigma_m = Some(ellipse.disc_radius_m);
    } else {
        event.reason = Some(RejectionReason::Filter(no_gain(
            ellipse.disc_radius_m,
            prior_r_m,
        )));
    }
}

/// Paper 002's particle filter on this sol's post-drive imagery.
pub(crate) fn particle_localization(
    loc: &ParticleLocalizer,
    c: &Campaign,
    state: &mut RoverState,
    start: SolSeconds,
    sol_seed: u64,
) -> LocalizationEvent {
    let mut event = LocalizationEvent::pending_onboard("particle", start.lmst());
    let truth = state.truth.position_m;
    let estimate = state.estimate.position_m;
    let r = state.uncertainty.radius_m(&c.model);
    let window_m = r.clamp(
        loc.settings.min_search_radius_m,
        loc.settings.max_search_radius_m,
    );
    event.search_radius_m = Some(window_m);
    let request = OnboardRequest {
        truth_m: [truth.x, truth.y],
        prior_m: [estimate.x, estimate.y],
        uncertainty_m: r,
        truth_seed: stream_seed(c.seed, Purpose::WorldTruth, 0).seed,
        orbital_seed: stream_seed(c.seed, Purpose::WorldOrbital, 0).seed,
        sol_seed,
    };
    let mut sol_rng = ChaCha8Rng::seed_from_u64(sol_seed);
    let rover_seed = rand::RngExt::random::<u64>(&mut sol_rng);
    let filter_seed = rand::RngExt::random::<u64>(&mut sol_rng);
    let imagery = match render_activity_imagery(
        &loc.layers,
        Some(&loc.cache),
        &request,
        &loc.settings,
        window_m,
        rover_seed,
    ) {
        Ok(imagery) => imagery,
        Err(e) => {
            event.reason = Some(RejectionReason::Onboard(LostReason::NoImagery(e)));
            event.uncertainty_after_m = r;
            return event;
        }
    };
    let outcome = localize_panorama(
        [estimate.x, estimate.y],
        r,
        &imagery.orbital_map(),
        &imagery.rover_images(),
        &loc.settings.matcher,
        &loc.fix,
        filter_seed,
    );
    match outcome {
        Err(e) => event.reason = Some(RejectionReason::Filter(e.to_string())),
        Ok(PanoramaFix::Rejected { reason, posterior }) => {
            if let Some(post) = posterior {
                event.matched_error_m =
                    Some((post.mean_m[0] - truth.x).hypot(post.mean_m[1] - truth.y));
                event.ellipse = Some(PositionEllipse::from_ellipse(post.ellipse));
            }
            event.reason = Some(RejectionReason::Filter(reason));
        }
        Ok(PanoramaFix::Accepted(post)) => {
            let ellipse = PositionEllipse::from_ellipse(post.ellipse);
            apply_if_gain(&mut event, c, state, r, post.mean_m, ellipse);
        }
    }
    event.uncertainty_after_m = state.uncertainty.radius_m(&c.model);
    event
}

/// Paper 004's EKF: the parked rover ranging to the orbiter through one pass.
pub(crate) fn ekf_localization(
    loc: &EkfLocalizer,
    c: &Campaign,
    state: &mut RoverState,
    start: SolSeconds,
    seed: u64,
) -> LocalizationEvent {
    let mut event = LocalizationEvent::pending_onboard("ekf", start.lmst());
    let r = state.uncertainty.radius_m(&c.model);
    let offset = state.estimate.position_m - state.truth.position_m;
    if r > 0.0 {
        match localization::ekf::parked_fix(&loc.settings, [offset.x, offset.y], r / 3.0, seed) {
            Err(e) => event.reason = Some(RejectionReason::Filter(e.to_string())),
            Ok(fix) => match fix.ellipse().map(PositionEllipse::from_ellipse) {
                Some(ellipse) => {
                    let truth = state.truth.position_m;
                    let mean = [truth.x + fix.error_enu_m[0], truth.y + fix.error_enu_m[1]];
                    apply_if_gain(&mut event, c, state, r, mean, ellipse);
                }
                None => {
                    event.reason = Some(RejectionReason::Filter(
                        "the filter's covariance is not a covariance".into(),
                    ));
                }
            },
        }
    } else {
        event.reason = Some(RejectionReason::Filter(
            "no gain: the rover's uncertainty is already 0 m".into(),
        ));
    }
    event.uncertainty_after_m = state.uncertainty.radius_m(&c.model);
    event
}
