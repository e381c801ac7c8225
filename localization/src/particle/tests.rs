//! Unit tests of the filter: motion noise against the simulator's disc, the weight update and
//! its guards, resampling, determinism, bad input.
#![allow(clippy::unwrap_used)]

use super::resample::effective_sample_size;
use super::*;
fn params(n: usize) -> ParticleSettings {
    ParticleSettings {
        particle_count: n,
        ..ParticleSettings::default()
    }
}

fn at_point(n: usize, seed: u64) -> ParticleFilter {
    let prior = Prior::Gaussian {
        mean_m: [100.0, 200.0],
        sigma_m: 0.0,
    };
    ParticleFilter::new(&prior, params(n), seed).unwrap()
}

/// Per-axis mean and standard deviation of the displacement from the start, pooled σ over
/// both axes, and the share of particles within `r_m` of the mean displacement.
fn spread(pf: &ParticleFilter, start: [f64; 2], r_m: f64) -> ([f64; 2], f64, f64) {
    let n = pf.len() as f64;
    let d: Vec<[f64; 2]> = pf
        .positions_m()
        .iter()
        .map(|p| [p[0] - start[0], p[1] - start[1]])
        .collect();
    let m = [
        d.iter().map(|v| v[0]).sum::<f64>() / n,
        d.iter().map(|v| v[1]).sum::<f64>() / n,
    ];
    let var = d
        .iter()
        .map(|v| (v[0] - m[0]).powi(2) + (v[1] - m[1]).powi(2))
        .sum::<f64>()
        / (2.0 * n - 2.0);
    let inside = d
        .iter()
        .filter(|v| (v[0] - m[0]).hypot(v[1] - m[1]) <= r_m)
        .count() as f64
        / n;
    (m, var.sqrt(), inside)
}

#[test]
fn motion_noise_grows_like_the_simulator_disc() {
    // 20,000 particles, both axes pooled: the sample σ has a relative standard error of
    // 1/√(2·40,000) = 0.35 %, so 2 % is 5.7 standard errors; the mean's standard error is
    // σ/√20,000 = 0.7 % of σ, checked to 5 %; the share inside the disc (98.89 % for a 2-D
    // Gaussian within 3σ) has a binomial standard error of 0.074 %, checked to 0.4 %.
    let m = MotionModel::default();
    for (leg, radius) in [
        (Odometry::straight([60.0, 80.0], 0.0), 5.0), // 100 m with VO: 5 %
        (Odometry::straight([0.0, -100.0], 1.0), 50.0), // 100 m without: 50 %
        (
            Odometry {
                displacement_m: [-30.0, 10.0],
                distance_vo_m: 60.0,
                distance_novo_m: 4.0,
            },
            5.0, // 0.05·60 + 0.5·4
        ),
    ] {
        assert!((m.disc_growth_m(&leg) - radius).abs() < 1e-12);
        let sigma = radius / 3.0;
        assert!((m.sigma_m(&leg) - sigma).abs() < 1e-12);
        let mut pf = at_point(20_000, 11);
        pf.predict(&leg).unwrap();
        let (mean, s, inside) = spread(&pf, [100.0, 200.0], radius);
        assert!((s / sigma - 1.0).abs() < 0.02, "σ {s} vs {sigma}");
        for k in 0..2 {
            assert!(
                (mean[k] - leg.displacement_m[k]).abs() < 0.05 * sigma,
                "{mean:?}"
            );
        }
        assert!((inside - 0.988_89).abs() < 0.004, "{inside}");
        // Odometry alone: the reported disc is the simulator's radius.
        let post = pf.posterior();
        assert!((post.disc_radius_m / radius - 1.0).abs() < 0.03, "{post:?}");
    }
    // A zero-length leg moves nothing.
    let mut pf = at_point(10, 1);
    pf.predict(&Odometry::straight([0.0, 0.0], 0.3)).unwrap();
    assert!(pf.positions_m().iter().all(|p| *p == [100.0, 200.0]));
}

#[test]
fn weights_follow_the_temperature_and_skip_without_information() {
    let pos = vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0]];
    let p = ParticleSettings {
        resample_threshold: 0.0,
        ..params(4)
    };
    let t = p.temperature;
    let mut pf = ParticleFilter::from_particles(pos, vec![1.0; 4], p, 3).unwrap();
    let r = pf
        .update_with_scores(&[Some(0.3), Some(0.3 + t), None, Some(0.3 + 2.0 * t)])
        .unwrap();
    assert_eq!(r.skipped, None);
    assert_eq!(
        (r.scored_fraction, r.best_score, r.resampled),
        (0.75, Some(0.3), false)
    );
    let z = 1.0 + (-1.0f64).exp() + (-2.0f64).exp();
    let expected = [1.0 / z, (-1.0f64).exp() / z, 0.0, (-2.0f64).exp() / z];
    for (w, e) in pf.weights().iter().zip(expected) {
        assert!((w - e).abs() < 1e-12, "{:?}", pf.weights());
    }
    assert!((r.effective_sample_size - effective_sample_size(&expected)).abs() < 1e-12);
    // A second update multiplies: the zero-weight particle stays at zero whatever it scores.
    let before = pf.weights().to_vec();
    pf.update_with_scores(&[Some(0.5); 4]).unwrap();
    for (a, b) in pf.weights().iter().zip(&before) {
        assert!((a - b).abs() < 1e-12);
    }
    // Nothing scored, or nothing finite: skipped, weights untouched.
    let before = pf.weights().to_vec();
    let r = pf.update_with_scores(&[None; 4]).unwrap();
    assert_eq!(r.skipped, Some(SkipReason::NoParticleOnMap));
    let r = pf
        .update_with_scores(&[Some(f64::NAN), None, Some(f64::INFINITY), None])
        .unwrap();
    assert_eq!(r.skipped, Some(SkipReason::DegenerateWeights));
    assert_eq!(pf.weights(), before.as_slice());
    // Huge score differences underflow every factor but the best one, which stays 1.
    pf.update_with_scores(&[Some(1e6), Some(0.0), None, Some(2e6)])
        .unwrap();
    assert_eq!(pf.weights(), &[0.0, 1.0, 0.0, 0.0]);
    assert!(matches!(
        pf.update_with_scores(&[Some(0.1)]),
        Err(ParticleError::ScoreCountMismatch {
            particles: 4,
            scores: 1
        })
    ));
}

#[test]
fn resamples_below_half_the_particles_and_keeps_the_count() {
    let n = 1000;
    let prior = Prior::Rectangle {
        min_m: [0.0, 0.0],
        max_m: [100.0, 10.0],
    };
    let mut pf = ParticleFilter::new(&prior, params(n), 5).unwrap();
    // A mild preference (ESS stays above N/2): no resampling.
    let mild: Vec<Option<f64>> = pf
        .positions_m()
        .iter()
        .map(|p| Some(1e-4 * p[0] / 100.0))
        .collect();
    let r = pf.update_with_scores(&mild).unwrap();
    assert!(!r.resampled && r.effective_sample_size > 500.0, "{r:?}");
    // A sharp one around x = 30: resampled to N equal weights, all near 30.
    let sharp: Vec<Option<f64>> = pf
        .positions_m()
        .iter()
        .map(|p| Some(0.01 * (p[0] - 30.0).abs()))
        .collect();
    let r = pf.update_with_scores(&sharp).unwrap();
    assert!(r.resampled && r.effective_sample_size < 500.0, "{r:?}");
    assert_eq!(pf.len(), n);
    assert!(pf.weights().iter().all(|&w| w == 1.0 / n as f64));
    let post = pf.posterior();
    assert!((post.mean_m[0] - 30.0).abs() < 0.5, "{post:?}");
    assert!((post.effective_sample_size - n as f64).abs() < 1e-6);
}

#[test]
fn kld_resampling_shrinks_a_concentrated_belief() {
    let p = ParticleSettings {
        particle_count: 4000,
        resampling: Resampling::Kld(KldSettings::default()),
        ..ParticleSettings::default()
    };
    let prior = Prior::Disc {
        center_m: [50.0, 50.0],
        radius_m: 30.0,
    };
    let mut pf = ParticleFilter::new(&prior, p, 9).unwrap();
    let peaked: Vec<Option<f64>> = pf
        .positions_m()
        .iter()
        .map(|q| Some(0.1 * (q[0] - 40.0).hypot(q[1] - 55.0)))
        .collect();
    let r = pf.update_with_scores(&peaked).unwrap();
    assert!(r.resampled);
    assert!((200..1000).contains(&pf.len()), "{}", pf.len());
    let post = pf.posterior();
    assert!((post.mean_m[0] - 40.0).abs() < 1.0 && (post.mean_m[1] - 55.0).abs() < 1.0);
}

#[test]
fn deterministic_under_a_seed() {
    let run = |seed: u64| {
        let prior = Prior::from_uncertainty_disc([10.0, 20.0], 15.0);
        let mut pf = ParticleFilter::new(&prior, params(500), seed).unwrap();
        for step in 0..4 {
            pf.predict(&Odometry::straight([3.0, -1.0], 0.1)).unwrap();
            let target = [13.0 + 3.0 * step as f64, 19.0 - step as f64];
            let s: Vec<Option<f64>> = pf
                .positions_m()
                .iter()
                .map(|p| Some(0.002 * (p[0] - target[0]).hypot(p[1] - target[1])))
                .collect();
            pf.update_with_scores(&s).unwrap();
        }
        pf
    };
    let (a, b, c) = (run(42), run(42), run(43));
    assert_eq!(a.positions_m(), b.positions_m());
    assert_eq!(a.weights(), b.weights());
    assert_eq!(a.posterior(), b.posterior());
    assert_ne!(a.positions_m(), c.positions_m());
}

#[test]
fn bad_inputs_are_errors() {
    let bad = |p: ParticleSettings| {
        ParticleFilter::new(&Prior::from_uncertainty_disc([0.0; 2], 1.0), p, 1)
    };
    assert!(matches!(
        bad(params(0)),
        Err(ParticleError::InvalidParameter {
            field: "params.particle_count",
            ..
        })
    ));
    for (p, field) in [
        (
            ParticleSettings {
                temperature: 0.0,
                ..params(5)
            },
            "params.temperature",
        ),
        (
            ParticleSettings {
                resample_threshold: 1.5,
                ..params(5)
            },
            "params.resample_threshold",
        ),
        (
            ParticleSettings {
                motion: MotionModel {
                    k_vo: -0.1,
                    ..MotionModel::default()
                },
                ..params(5)
            },
            "params.motion.k_vo",
        ),
        (
            ParticleSettings {
                resampling: Resampling::Kld(KldSettings {
                    min_particles: 6,
                    ..KldSettings::default()
                }),
                ..params(5)
            },
            "params.resampling.min_particles",
        ),
    ] {
        match bad(p) {
            Err(ParticleError::InvalidParameter { field: f, .. }) => assert_eq!(f, field),
            other => panic!("{field}: {other:?}"),
        }
    }
    let prior = Prior::Rectangle {
        min_m: [0.0, 0.0],
        max_m: [-1.0, 1.0],
    };
    assert!(ParticleFilter::new(&prior, params(5), 1).is_err());
    let mut pf = at_point(5, 1);
    let e = pf
        .predict(&Odometry {
            displacement_m: [f64::NAN, 0.0],
            distance_vo_m: 1.0,
            distance_novo_m: 0.0,
        })
        .unwrap_err();
    assert!(e.to_string().contains("odometry.displacement_m[0]"), "{e}");
    assert!(
        pf.predict(&Odometry {
            displacement_m: [1.0, 0.0],
            distance_vo_m: -1.0,
            distance_novo_m: 0.0
        })
        .is_err()
    );
    assert!(matches!(
        ParticleFilter::from_particles(vec![[0.0; 2]; 3], vec![1.0; 2], params(3), 1),
        Err(ParticleError::LengthMismatch {
            positions: 3,
            weights: 2
        })
    ));
    assert!(ParticleFilter::from_particles(vec![[0.0; 2]; 2], vec![0.0; 2], params(2), 1).is_err());
    assert!(ParticleFilter::from_particles(vec![], vec![], params(2), 1).is_err());
    assert!(pf.modes(0.0, 0.1).is_err());
}
