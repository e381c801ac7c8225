//! The rover's true motion: a random smooth 2-D drive in the navigation frame (paper 004 §5:
//! "the rover walk along a randomly generated two-dimensional trajectory").
//!
//! Speed and heading are each a constant plus a sum of sinusoids with random amplitudes, periods
//! and phases, offset so that the drive starts at the given velocity; the velocity is
//! `s·(cos ψ, sin ψ)`, so the body-frame acceleration an ideal accelerometer reads is exactly
//! `(ṡ, s·ψ̇)` (forward, left) and the yaw rate is `ψ̇`. Position is the integral of velocity
//! (RK4, 0.1 s sub-steps: position error < 1e-9 m). The terrain is level (zero roll and pitch),
//! and the rotating-frame terms (Coriolis 2ω_M·v ≈ 2e-5 m/s², transport rate) are left out, as in
//! the paper: they are 100× smaller than the accelerometer bias.

use nalgebra::Vector2;
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

/// How the random drive is drawn (plain struct; a static rover is zero velocity and amplitudes).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct TrajectorySettings {
    /// Velocity at t = 0, east and north, m/s (default: (0.1, 0.1), paper 004 §5's X0).
    pub initial_velocity_enu_m_per_s: [f64; 2],
    /// Largest amplitude of each of the speed's sinusoids, m/s (default: 0.03; a sinusoid moves
    /// the speed by at most twice its amplitude, so two keep it between 0.02 and 0.26 m/s).
    pub speed_amplitude_m_per_s: f64,
    /// Largest amplitude of each of the heading's sinusoids, degrees (default: 30).
    pub heading_amplitude_deg: f64,
    /// Shortest and longest sinusoid period, seconds (default: 150, 600).
    pub period_range_s: [f64; 2],
    /// Sinusoids in the speed and in the heading (default: 2 each).
    pub components: usize,
}

impl Default for TrajectorySettings {
    fn default() -> Self {
        Self {
            initial_velocity_enu_m_per_s: [0.1, 0.1],
            speed_amplitude_m_per_s: 0.03,
            heading_amplitude_deg: 30.0,
            period_range_s: [150.0, 600.0],
            components: 2,
        }
    }
}

/// The true kinematic state at a whole second.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct TrueState {
    /// Seconds since the start of the run.
    pub t_s: u32,
    /// Position (east, north), metres.
    pub position_enu_m: Vector2<f64>,
    /// Velocity (east, north), m/s.
    pub velocity_enu_m_per_s: Vector2<f64>,
    /// Heading ψ (from east to body x, counter-clockwise), radians.
    pub heading_rad: f64,
    /// Acceleration in the body frame (forward, left), m/s².
    pub accel_body_m_per_s2: Vector2<f64>,
    /// Yaw rate ψ̇, rad/s.
    pub yaw_rate_rad_per_s: f64,
}

/// `c + Σ aᵢ·(sin(wᵢt + φᵢ) − sin φᵢ)`: equal to `c` at t = 0.
#[derive(Clone, Debug, PartialEq)]
struct SineSum {
    constant: f64,
    /// (amplitude, angular frequency rad/s, phase rad)
    terms: Vec<(f64, f64, f64)>,
}

impl SineSum {
    fn draw(
        constant: f64,
        max_amplitude: f64,
        s: &TrajectorySettings,
        rng: &mut ChaCha8Rng,
    ) -> Self {
        let terms = (0..s.components)
            .map(|_| {
                let amplitude = max_amplitude * rng.random::<f64>();
                let period = s.period_range_s[0]
                    + (s.period_range_s[1] - s.period_range_s[0]) * rng.random::<f64>();
                let phase = std::f64::consts::TAU * rng.random::<f64>();
                (amplitude, std::f64::consts::TAU / period, phase)
            })
            .collect();
        Self { constant, terms }
    }

    fn value(&self, t: f64) -> f64 {
        self.constant
            + self
                .terms
                .iter()
                .map(|&(a, w, p)| a * ((w * t + p).sin() - p.sin()))
                .sum::<f64>()
    }

    fn rate(&self, t: f64) -> f64 {
        self.terms
            .iter()
            .map(|&(a, w, p)| a * w * (w * t + p).cos())
            .sum()
    }
}

/// The true drive, sampled at every whole second `0..=duration_s`.
#[derive(Clone, Debug, PartialEq)]
pub struct TruthTrajectory {
    speed: SineSum,
    heading: SineSum,
    states: Vec<TrueState>,
}

impl TruthTrajectory {
    /// Draws a drive from `rng` and integrates it over `duration_s` seconds from the origin.
    pub fn generate(settings: &TrajectorySettings, duration_s: u32, rng: &mut ChaCha8Rng) -> Self {
        let [ve, vn] = settings.initial_velocity_enu_m_per_s;
        let speed = SineSum::draw(
            ve.hypot(vn),
            settings.speed_amplitude_m_per_s,
            settings,
            rng,
        );
        let heading = SineSum::draw(
            vn.atan2(ve),
            settings.heading_amplitude_deg.to_radians(),
            settings,
            rng,
        );
        let mut truth = Self {
            speed,
            heading,
            states: Vec::with_capacity(duration_s as usize + 1),
        };
        const SUBSTEPS: u32 = 10;
        let h = 1.0 / f64::from(SUBSTEPS);
        let mut p = Vector2::zeros();
        for t_s in 0..=duration_s {
            truth.states.push(truth.state_at(t_s, p));
            for j in 0..SUBSTEPS {
                let t = f64::from(t_s) + f64::from(j) * h;
                // Velocity depends on time only, so RK4 is Simpson's rule here.
                p += h / 6.0
                    * (truth.velocity(t)
                        + 4.0 * truth.velocity(t + 0.5 * h)
                        + truth.velocity(t + h));
            }
        }
        truth
    }

    /// The states at `0..=duration_s` seconds.
    pub fn states(&self) -> &[TrueState] {
        &self.states
    }

    fn velocity(&self, t: f64) -> Vector2<f64> {
        let (s, psi) = (self.speed.value(t), self.heading.value(t));
        Vector2::new(s * psi.cos(), s * psi.sin())
    }

    fn state_at(&self, t_s: u32, position_enu_m: Vector2<f64>) -> TrueState {
        let t = f64::from(t_s);
        let s = self.speed.value(t);
        let yaw_rate = self.heading.rate(t);
        TrueState {
            t_s,
            position_enu_m,
            velocity_enu_m_per_s: self.velocity(t),
            heading_rad: self.heading.value(t),
            accel_body_m_per_s2: Vector2::new(self.speed.rate(t), s * yaw_rate),
            yaw_rate_rad_per_s: yaw_rate,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn the_body_acceleration_is_the_derivative_of_the_velocity() {
        let mut rng = ChaCha8Rng::seed_from_u64(4);
        let truth = TruthTrajectory::generate(&TrajectorySettings::default(), 1000, &mut rng);
        for s in truth.states().iter().step_by(97) {
            let t = f64::from(s.t_s);
            let h = 1e-3;
            let dv = (truth.velocity(t + h) - truth.velocity(t - h)) / (2.0 * h);
            let (sin, cos) = s.heading_rad.sin_cos();
            let a = s.accel_body_m_per_s2;
            let a_enu = Vector2::new(cos * a.x - sin * a.y, sin * a.x + cos * a.y);
            assert!((dv - a_enu).norm() < 1e-9, "t = {t}: {dv} vs {a_enu}");
        }
        let first = truth.states()[0];
        assert!((first.velocity_enu_m_per_s - Vector2::new(0.1, 0.1)).norm() < 1e-16);
        assert_eq!(first.position_enu_m, Vector2::zeros());
    }

    #[test]
    fn zero_velocity_and_amplitudes_give_a_static_rover() {
        let settings = TrajectorySettings {
            initial_velocity_enu_m_per_s: [0.0, 0.0],
            speed_amplitude_m_per_s: 0.0,
            heading_amplitude_deg: 0.0,
            ..TrajectorySettings::default()
        };
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let truth = TruthTrajectory::generate(&settings, 100, &mut rng);
        assert!(
            truth
                .states()
                .iter()
                .all(|s| s.position_enu_m == Vector2::zeros()
                    && s.accel_body_m_per_s2 == Vector2::zeros())
        );
    }
}
