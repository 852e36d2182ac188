//! Shared test fixtures: the analytic Kepler orbit and the paper-2s scene.
#![allow(dead_code)]

use surfgrav_dynamics::{BodyState, PointMasses, Sample, SceneModel, SceneSettings, TwoBodyState};
use surfgrav_interaction::Body;
use surfgrav_potentials::{Real, Spheroid, Vec3};

/// A Kepler problem: two point masses of 0.5 each, G = 1 (μ = 1), semi-major axis 1,
/// eccentricity `e`, starting at pericentre on +x moving toward +y, centre of mass at rest at the
/// origin. Period 2π.
pub struct Kepler {
    pub eccentricity: Real,
    pub model: PointMasses,
}

impl Kepler {
    pub fn new(eccentricity: Real) -> Self {
        Self {
            eccentricity,
            model: PointMasses::new(0.5, 0.5, 1.0).unwrap(),
        }
    }

    pub fn period(&self) -> Real {
        2.0 * std::f64::consts::PI
    }

    /// Relative position and velocity at time t, by Newton's method on Kepler's equation
    /// E − e sin E = t (mean motion 1).
    pub fn relative(&self, t: Real) -> (Vec3, Vec3) {
        let e = self.eccentricity;
        let m = t.rem_euclid(self.period());
        let mut big_e = if e > 0.8 { std::f64::consts::PI } else { m };
        for _ in 0..50 {
            let delta = (big_e - e * big_e.sin() - m) / (1.0 - e * big_e.cos());
            big_e -= delta;
            if delta.abs() < 1e-16 {
                break;
            }
        }
        let b = (1.0 - e * e).sqrt();
        let (s, c) = big_e.sin_cos();
        let edot = 1.0 / (1.0 - e * c);
        (
            Vec3::new(c - e, b * s, 0.0),
            Vec3::new(-s * edot, b * c * edot, 0.0),
        )
    }

    pub fn initial_state(&self) -> TwoBodyState {
        let (r, v) = self.relative(0.0);
        TwoBodyState::new(
            BodyState::new(-0.5 * r, -0.5 * v),
            BodyState::new(0.5 * r, 0.5 * v),
        )
    }

    /// Error of a sample's relative position against the analytic orbit.
    pub fn position_error(&self, sample: &Sample) -> Real {
        (sample.state.relative_position() - self.relative(sample.time).0).norm()
    }
}

/// The paper-point scene: m = 1, G = 1, R = (∓3.5, 0, 0), V = (0, ±0.2, 0).
pub fn paper_point() -> (PointMasses, TwoBodyState) {
    (
        PointMasses::new(1.0, 1.0, 1.0).unwrap(),
        TwoBodyState::new(
            BodyState::new(Vec3::new(-3.5, 0.0, 0.0), Vec3::new(0.0, 0.2, 0.0)),
            BodyState::new(Vec3::new(3.5, 0.0, 0.0), Vec3::new(0.0, -0.2, 0.0)),
        ),
    )
}

/// The founding paper's oblate spheroid: a = 1, c = 0.25, m = 1.
pub fn paper_spheroid() -> Body {
    Body::spheroid(Spheroid::new(1.0, 0.25, 1.0).unwrap()).unwrap()
}

/// paper-2s: oblate spheroids a = 1, c = 0.25, m = 1, G = 1, R = (∓3.5, 0, 0), V = (0, ±0.2, 0).
pub fn paper_2s_initial() -> TwoBodyState {
    TwoBodyState::new(
        BodyState::new(Vec3::new(-3.5, 0.0, 0.0), Vec3::new(0.0, 0.2, 0.0)),
        BodyState::new(Vec3::new(3.5, 0.0, 0.0), Vec3::new(0.0, -0.2, 0.0)),
    )
}

/// The paper-2s scene model, tabulated or direct.
pub fn paper_2s(interpolate: bool) -> SceneModel {
    let settings = SceneSettings {
        interpolate,
        ..SceneSettings::default()
    };
    SceneModel::build(
        paper_spheroid(),
        paper_spheroid(),
        &paper_2s_initial(),
        &settings,
    )
    .unwrap()
}
