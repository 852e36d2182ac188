//! Spin–orbit diagnostics of a full two-body run: spin rates, obliquities, libration, and the
//! osculating elements of the mutual orbit with their precession rates.
//!
//! Feed [`SpinOrbitAnalyser::observe`] every sample; [`SpinOrbitAnalyser::report`] gives:
//! - per body: the range of the spin rate $|\boldsymbol\omega|$; the range of the obliquity, the
//!   angle between $\boldsymbol\omega$ and the mutual orbit's normal
//!   $\hat{\mathbf h} = \mathbf r\times\dot{\mathbf r}/|\mathbf r\times\dot{\mathbf r}|$
//!   ($\mathbf r = \mathbf R_B - \mathbf R_A$); for an elongated body (distinct smallest
//!   principal moment), the libration angle: the angle, in the orbit plane, from the line of
//!   centres (seen from that body toward the other) to the body's long axis (the principal
//!   axis of least moment) projected into the plane, wrapped to $(-90°, 90°]$ since the axis has
//!   no sense: its range and its period (mean spacing of its downward crossings of its mean);
//!   a body whose long axis turns through the line of centres (a jump of more than 90° between
//!   samples) is reported as circulating, without a libration range;
//! - the osculating elements of the relative orbit for $\mu = G(m_A + m_B)$: semi-major axis a
//!   (negative when unbound), eccentricity e, inclination i, longitude of the ascending node Ω
//!   and argument of pericentre ω, in the frame whose z axis is the initial total angular
//!   momentum $\mathbf J_0$ and whose x axis is the world x axis projected on its plane (or the
//!   world y axis if x is along $\mathbf J_0$): ranges, and the nodal and apsidal precession
//!   rates as least-squares slopes of the unwrapped Ω and ϖ = Ω + ω against time (degrees
//!   per time unit). Angles are degrees.
//!
//! The formulas are the standard two-body ones: $\mathbf h = \mathbf r\times\mathbf v$,
//! $\mathbf e = \mathbf v\times\mathbf h/\mu - \hat{\mathbf r}$, $1/a = 2/r - v^2/\mu$,
//! $\cos i = \hat{\mathbf h}\cdot\hat{\mathbf z}$, node $\mathbf n = \hat{\mathbf z}\times\mathbf h$.
//! For an orbit in the reference plane ($i$ below $10^{-9}$ rad) Ω is taken as 0, so ϖ stays
//! meaningful.

use crate::diagnostics::SeriesAccumulator;
use crate::state::{Sample, TwoBodyState};
use surfgrav_potentials::{InertiaTensor, Real, Vec3};

/// Smallest and largest value seen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// Smallest.
    pub min: Real,
    /// Largest.
    pub max: Real,
}

impl Range {
    fn empty() -> Self {
        Self {
            min: Real::INFINITY,
            max: Real::NEG_INFINITY,
        }
    }
    fn push(&mut self, x: Real) {
        if x.is_finite() {
            self.min = self.min.min(x);
            self.max = self.max.max(x);
        }
    }
    fn value(self) -> Option<Self> {
        (self.min <= self.max).then_some(self)
    }
}

/// A body's spin diagnostics.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodySpinReport {
    /// Range of $|\boldsymbol\omega|$ (radians per time unit).
    pub spin_rate: Option<Range>,
    /// Range of the obliquity (degrees).
    pub obliquity: Option<Range>,
    /// Range of the libration angle (degrees), for an elongated body.
    pub libration: Option<Range>,
    /// Libration period (time units), when the angle crossed its mean downward at least twice.
    pub libration_period: Option<Real>,
    /// The long axis turned through the line of centres (the angle wrapped by 180° between
    /// samples): the body circulates instead of librating, and the libration range and period
    /// are not given.
    pub circulating: bool,
}

/// The mutual orbit's osculating elements.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrbitElementsReport {
    /// Semi-major axis range.
    pub semi_major_axis: Option<Range>,
    /// Eccentricity range.
    pub eccentricity: Option<Range>,
    /// Inclination range (degrees) to the plane normal to $\mathbf J_0$.
    pub inclination: Option<Range>,
    /// Longitude of the ascending node range (degrees, unwrapped).
    pub node: Option<Range>,
    /// Argument of pericentre range (degrees, unwrapped).
    pub pericentre: Option<Range>,
    /// dΩ/dt (degrees per time unit).
    pub nodal_precession_rate: Option<Real>,
    /// dϖ/dt, ϖ = Ω + ω (degrees per time unit).
    pub apsidal_precession_rate: Option<Real>,
}

/// Everything [`SpinOrbitAnalyser`] found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpinOrbitReport {
    /// Body A, body B.
    pub bodies: [BodySpinReport; 2],
    /// The mutual orbit.
    pub orbit: OrbitElementsReport,
}

/// Osculating elements of a relative state (angles in radians, wrapped).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Elements {
    /// Semi-major axis (negative for a hyperbola, infinite for a parabola).
    pub semi_major_axis: Real,
    /// Eccentricity.
    pub eccentricity: Real,
    /// Inclination to the reference plane.
    pub inclination: Real,
    /// Longitude of the ascending node in (−π, π].
    pub node: Real,
    /// Argument of pericentre in (−π, π].
    pub pericentre: Real,
}

/// Relative position and velocity of an orbit with `elements` (an ellipse: a > 0, e < 1) at
/// true anomaly `true_anomaly` (radians), for gravitational parameter `mu`, in the frame
/// `frame` (x, y, z): the inverse of [`osculating_elements`].
pub fn state_from_elements(
    elements: &Elements,
    true_anomaly: Real,
    mu: Real,
    frame: &[Vec3; 3],
) -> (Vec3, Vec3) {
    let (a, e) = (elements.semi_major_axis, elements.eccentricity);
    let p = a * (1.0 - e * e);
    let (s, c) = true_anomaly.sin_cos();
    let radius = p / (1.0 + e * c);
    let perifocal_r = Vec3::new(radius * c, radius * s, 0.0);
    let perifocal_v = Vec3::new(-s, e + c, 0.0) * (mu / p).sqrt();
    let rotation = nalgebra::Rotation3::from_axis_angle(&Vec3::z_axis(), elements.node)
        * nalgebra::Rotation3::from_axis_angle(&Vec3::x_axis(), elements.inclination)
        * nalgebra::Rotation3::from_axis_angle(&Vec3::z_axis(), elements.pericentre);
    let [ex, ey, ez] = frame;
    let world = |u: Vec3| ex * u.x + ey * u.y + ez * u.z;
    (world(rotation * perifocal_r), world(rotation * perifocal_v))
}

/// Mean anomaly → true anomaly of an ellipse of eccentricity `e` < 1 (Newton on Kepler's
/// equation to round-off).
pub fn true_anomaly(mean_anomaly: Real, e: Real) -> Real {
    let mut big_e = if e > 0.8 {
        std::f64::consts::PI
    } else {
        mean_anomaly
    };
    for _ in 0..60 {
        let step = (big_e - e * big_e.sin() - mean_anomaly) / (1.0 - e * big_e.cos());
        big_e -= step;
        if step.abs() < 1e-16 {
            break;
        }
    }
    2.0 * ((1.0 + e).sqrt() * (0.5 * big_e).sin()).atan2((1.0 - e).sqrt() * (0.5 * big_e).cos())
}

/// An orthonormal frame: z along `normal`, x the world x axis (or y) projected on its plane.
fn reference_frame(normal: &Vec3) -> Option<[Vec3; 3]> {
    let z = normal.try_normalize(0.0)?;
    let seed = if z.x.abs() < 0.9 {
        Vec3::x()
    } else {
        Vec3::y()
    };
    let x = (seed - z * z.dot(&seed)).normalize();
    Some([x, z.cross(&x), z])
}

/// Elements of relative position `r` and velocity `v` for gravitational parameter `mu`, in
/// the frame `frame` (x, y, z).
pub fn osculating_elements(r: &Vec3, v: &Vec3, mu: Real, frame: &[Vec3; 3]) -> Elements {
    let [ex, ey, ez] = frame;
    let to = |u: &Vec3| Vec3::new(u.dot(ex), u.dot(ey), u.dot(ez));
    let (r, v) = (to(r), to(v));
    let h = r.cross(&v);
    let radius = r.norm();
    let e_vec = v.cross(&h) / mu - r / radius;
    let inverse_a = 2.0 / radius - v.norm_squared() / mu;
    let inclination = (h.x.hypot(h.y)).atan2(h.z);
    let node_vec = Vec3::new(-h.y, h.x, 0.0);
    let (node, reference) = if inclination.abs() < 1e-9 {
        (0.0, Vec3::x())
    } else {
        (node_vec.y.atan2(node_vec.x), node_vec.normalize())
    };
    // ω: angle from the node to e, measured in the orbit plane about h.
    let hn = h.normalize();
    let pericentre = hn
        .dot(&reference.cross(&e_vec))
        .atan2(reference.dot(&e_vec));
    Elements {
        semi_major_axis: 1.0 / inverse_a,
        eccentricity: e_vec.norm(),
        inclination,
        node,
        pericentre,
    }
}

/// Unwraps a sequence of angles (radians) into a continuous one.
#[derive(Debug, Clone, Copy, Default)]
struct Unwrapper {
    last: Option<Real>,
    offset: Real,
}

impl Unwrapper {
    fn push(&mut self, angle: Real) -> Real {
        use std::f64::consts::{PI, TAU};
        if let Some(last) = self.last {
            let jump = angle + self.offset - last;
            if jump > PI {
                self.offset -= TAU * ((jump + PI) / TAU).floor();
            } else if jump < -PI {
                self.offset += TAU * ((PI - jump) / TAU).floor();
            }
        }
        let value = angle + self.offset;
        self.last = Some(value);
        value
    }
}

/// The long axis of an elongated body, body frame: the principal axis of least moment when that
/// moment is distinct (by more than rounding); `None` for a body symmetric about it or without
/// an inertia tensor.
pub fn long_axis(inertia: Option<InertiaTensor>) -> Option<Vec3> {
    let i = inertia?;
    let m = i.principal_moments();
    let k = (0..3).min_by(|&a, &b| m[a].total_cmp(&m[b]))?;
    let others = (0..3)
        .filter(|&j| j != k)
        .map(|j| m[j])
        .fold(Real::INFINITY, Real::min);
    (others - m[k] > 1e-12 * m.max()).then(|| {
        let mut e = Vec3::zeros();
        e[k] = 1.0;
        i.principal_axes() * e
    })
}

/// Obliquity of body `k` (0 = A, 1 = B) in degrees: the angle between its angular velocity and
/// the mutual orbit's normal; `None` without spin or orbital angular momentum.
pub fn obliquity_deg(state: &TwoBodyState, k: usize) -> Option<Real> {
    let n = state
        .relative_position()
        .cross(&state.relative_velocity())
        .try_normalize(0.0)?;
    let body = if k == 0 { &state.body_a } else { &state.body_b };
    let w = body.angular_velocity.try_normalize(0.0)?;
    Some(w.dot(&n).clamp(-1.0, 1.0).acos().to_degrees())
}

/// Libration angle of body `k` in degrees (module docs) for its body-frame long axis `axis`.
pub fn libration_deg(state: &TwoBodyState, k: usize, axis: &Vec3) -> Option<Real> {
    let r = state.relative_position();
    let n = r.cross(&state.relative_velocity()).try_normalize(0.0)?;
    let (body, toward) = if k == 0 {
        (&state.body_a, r)
    } else {
        (&state.body_b, -r)
    };
    let long = body.orientation * axis;
    let in_plane = long - n * long.dot(&n);
    let mut angle = n.dot(&toward.cross(&in_plane)).atan2(toward.dot(&in_plane));
    // The axis has no sense: wrap into (−π/2, π/2].
    if angle > std::f64::consts::FRAC_PI_2 {
        angle -= std::f64::consts::PI;
    } else if angle <= -std::f64::consts::FRAC_PI_2 {
        angle += std::f64::consts::PI;
    }
    Some(angle.to_degrees())
}

/// Collects the spin–orbit diagnostics of a run (module docs).
#[derive(Debug, Clone)]
pub struct SpinOrbitAnalyser {
    mu: Real,
    frame: Option<[Vec3; 3]>,
    long_axes: [Option<Vec3>; 2],
    spin_rate: [Range; 2],
    obliquity: [Range; 2],
    libration: [Vec<(Real, Real)>; 2],
    elements: [Range; 5],
    node: Unwrapper,
    pericentre: Unwrapper,
    node_fit: SeriesAccumulator,
    apsis_fit: SeriesAccumulator,
}

impl SpinOrbitAnalyser {
    /// An analyser for bodies of inertia tensors `inertia` (A, B; `None` for a body that does
    /// not rotate), gravitational parameter `mu` = G(m_A + m_B) of the relative orbit, and the
    /// initial total angular momentum `j0` defining the reference plane.
    pub fn new(inertia: [Option<InertiaTensor>; 2], mu: Real, j0: Vec3) -> Self {
        Self {
            mu,
            frame: reference_frame(&j0),
            long_axes: [long_axis(inertia[0]), long_axis(inertia[1])],
            spin_rate: [Range::empty(); 2],
            obliquity: [Range::empty(); 2],
            libration: [Vec::new(), Vec::new()],
            elements: [Range::empty(); 5],
            node: Unwrapper::default(),
            pericentre: Unwrapper::default(),
            node_fit: SeriesAccumulator::default(),
            apsis_fit: SeriesAccumulator::default(),
        }
    }

    /// Takes the next sample.
    pub fn observe(&mut self, sample: &Sample) {
        self.observe_state(sample.time, &sample.state);
    }

    /// Takes the state at `time`.
    pub fn observe_state(&mut self, time: Real, state: &TwoBodyState) {
        let r = state.relative_position();
        let v = state.relative_velocity();
        for k in 0..2 {
            let body = if k == 0 { &state.body_a } else { &state.body_b };
            self.spin_rate[k].push(body.angular_velocity.norm());
            if let Some(o) = obliquity_deg(state, k) {
                self.obliquity[k].push(o);
            }
            if let Some(angle) = self.long_axes[k].and_then(|a| libration_deg(state, k, &a)) {
                self.libration[k].push((time, angle));
            }
        }
        if let Some(frame) = &self.frame {
            let e = osculating_elements(&r, &v, self.mu, frame);
            let node = self.node.push(e.node).to_degrees();
            let pericentre = self.pericentre.push(e.pericentre).to_degrees();
            for (range, x) in self.elements.iter_mut().zip([
                e.semi_major_axis,
                e.eccentricity,
                e.inclination.to_degrees(),
                node,
                pericentre,
            ]) {
                range.push(x);
            }
            self.node_fit.push(time, node);
            self.apsis_fit.push(time, node + pericentre);
        }
    }

    /// The diagnostics so far.
    pub fn report(&self) -> SpinOrbitReport {
        let body = |k: usize| {
            let series = &self.libration[k];
            // A jump of more than 90° between samples is a wrap of the axis through ±90°.
            let circulating = series.windows(2).any(|w| (w[1].1 - w[0].1).abs() > 90.0);
            if circulating {
                return BodySpinReport {
                    spin_rate: self.spin_rate[k].value(),
                    obliquity: self.obliquity[k].value(),
                    libration: None,
                    libration_period: None,
                    circulating,
                };
            }
            let mut range = Range::empty();
            for &(_, a) in series {
                range.push(a);
            }
            let period = (series.len() > 2)
                .then(|| {
                    let mean = series.iter().map(|p| p.1).sum::<Real>() / series.len() as Real;
                    let crossings: Vec<Real> = series
                        .windows(2)
                        .filter_map(|w| {
                            let (p0, p1) = (w[0].1 - mean, w[1].1 - mean);
                            (p0 > 0.0 && p1 <= 0.0)
                                .then(|| w[0].0 + (w[1].0 - w[0].0) * p0 / (p0 - p1))
                        })
                        .collect();
                    (crossings.len() >= 2).then(|| {
                        (crossings[crossings.len() - 1] - crossings[0])
                            / (crossings.len() - 1) as Real
                    })
                })
                .flatten();
            BodySpinReport {
                spin_rate: self.spin_rate[k].value(),
                obliquity: self.obliquity[k].value(),
                libration: range.value(),
                libration_period: period,
                circulating,
            }
        };
        let slope = |fit: &SeriesAccumulator| {
            let s = fit.statistics().slope;
            s.is_finite().then_some(s)
        };
        let [a, e, i, node, pericentre] = self.elements.map(Range::value);
        SpinOrbitReport {
            bodies: [body(0), body(1)],
            orbit: OrbitElementsReport {
                semi_major_axis: a,
                eccentricity: e,
                inclination: i,
                node,
                pericentre,
                nodal_precession_rate: slope(&self.node_fit),
                apsidal_precession_rate: slope(&self.apsis_fit),
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A Kepler orbit with known elements round-trips through position and velocity; the
    /// state is checked against an independent property (vis-viva, |h| = sqrt(μp)).
    #[test]
    fn elements_round_trip() {
        let (mu, a, e, i, node, w, nu): (Real, Real, Real, Real, Real, Real, Real) =
            (2.0, 3.0, 0.3, 0.4, 1.1, -0.7, 0.9);
        let frame = [Vec3::x(), Vec3::y(), Vec3::z()];
        let given = Elements {
            semi_major_axis: a,
            eccentricity: e,
            inclination: i,
            node,
            pericentre: w,
        };
        let (r, v) = state_from_elements(&given, nu, mu, &frame);
        assert!((v.norm_squared() - mu * (2.0 / r.norm() - 1.0 / a)).abs() < 1e-14);
        assert!((r.cross(&v).norm() - (mu * a * (1.0 - e * e)).sqrt()).abs() < 1e-14);
        let el = osculating_elements(&r, &v, mu, &frame);
        assert!((el.semi_major_axis - a).abs() < 1e-13);
        assert!((el.eccentricity - e).abs() < 1e-14);
        assert!((el.inclination - i).abs() < 1e-14);
        assert!((el.node - node).abs() < 1e-14);
        assert!((el.pericentre - w).abs() < 1e-14);
    }

    #[test]
    fn kepler_equation_is_solved() {
        for &(m, e) in &[(0.3, 0.1), (2.5, 0.7), (5.9, 0.95), (0.0, 0.5)] {
            let nu: Real = true_anomaly(m, e);
            // Back to the mean anomaly through the eccentric anomaly.
            let big_e = 2.0
                * ((1.0 - e).sqrt() * (0.5 * nu).sin()).atan2((1.0 + e).sqrt() * (0.5 * nu).cos());
            let back = (big_e - e * big_e.sin()).rem_euclid(std::f64::consts::TAU);
            assert!((back - m).abs() < 1e-14, "{m} {e}: {back}");
        }
    }

    #[test]
    fn unwrapping_follows_full_turns() {
        let mut u = Unwrapper::default();
        let values: Vec<Real> = (0..40)
            .map(|k| {
                let angle = 0.5 * k as Real;
                u.push((angle.sin()).atan2(angle.cos()))
            })
            .collect();
        for (k, v) in values.iter().enumerate() {
            assert!((v - 0.5 * k as Real).abs() < 1e-12);
        }
    }
}
