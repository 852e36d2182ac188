//! Analysis of the relative orbit $\mathbf r = \mathbf R_B - \mathbf R_A$: apsides, periods,
//! precession, minimum separation.
//!
//! - **Apsides** are the zeros of $\tfrac12\\,\mathrm d r^2/\mathrm dt = \mathbf r\cdot\dot{\mathbf r}$:
//!   an apocentre where it changes from positive to negative, a pericentre where it changes from
//!   negative to positive. Each is located between two samples by bisection on the quintic
//!   Hermite interpolant of [`crate::interpolate`] (error $O(h^6)$ in position), not at step
//!   resolution.
//! - **Azimuth** $\psi$: the angle of $\mathbf r$ in the orbital plane, measured about the unit
//!   vector of the initial relative angular momentum $\hat{\mathbf n} \propto \mathbf r \times \dot{\mathbf r}$
//!   (so it increases in the direction of motion), unwrapped by summing the angle between
//!   consecutive samples, $\Delta\psi = \operatorname{atan2}(\hat{\mathbf n}\cdot(\mathbf r\_{k-1}\times\mathbf r_k),\ \mathbf r\_{k-1}\cdot\mathbf r_k)$
//!   (valid while a step sweeps less than π).
//! - **Radial period** $T_r$: mean time between consecutive apocentres.
//! - **Precession angle** per radial period $\psi_p = \overline{\psi\_{k+1} - \psi_k} - 360°$ over
//!   consecutive apocentres, in degrees: positive when the apsides advance in the direction of
//!   motion.
//! - **Azimuthal period** $T\_\psi = 360°\\, T_r / (360° + \psi_p)$: the time to sweep 360° at the
//!   mean angular rate over whole radial periods.
//! - **Precession rate** $\Omega_p = 60\\,\psi_p/T_r$ in arcminutes per time unit.
//! - **Minimum separation**: the smallest of the interpolated pericentre distances and the sampled
//!   separations.
//!
//! An apsis is found when $\mathbf r\cdot\dot{\mathbf r}$ changes sign between consecutive samples,
//! so a step must not span two apsides (any step that resolves the orbit satisfies this).
//!
//! When fewer than two apocentres are seen, the periods and the precession fall back to
//! consecutive pericentres; with fewer than two of either they are `None`.

use crate::interpolate::relative_between;
use crate::state::Sample;
use surfgrav_potentials::{Real, Vec3};

/// An apocentre or pericentre of the relative orbit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Apsis {
    /// Time.
    pub time: Real,
    /// Separation $|\mathbf r|$.
    pub separation: Real,
    /// Unwrapped azimuth ψ (radians, about the initial angular momentum direction).
    pub azimuth: Real,
    /// Relative position $\mathbf r$.
    pub relative_position: Vec3,
}

/// The result of an orbit analysis.
#[derive(Debug, Clone, PartialEq)]
pub struct OrbitReport {
    /// Apocentres in time order.
    pub apocentres: Vec<Apsis>,
    /// Pericentres in time order.
    pub pericentres: Vec<Apsis>,
    /// Smallest separation (None before any sample).
    pub minimum_separation: Option<Real>,
    /// Time of the smallest separation.
    pub minimum_separation_time: Option<Real>,
    /// $T_r$.
    pub radial_period: Option<Real>,
    /// $T\_\psi$.
    pub azimuthal_period: Option<Real>,
    /// $\psi_p$ in degrees.
    pub precession_angle_deg: Option<Real>,
    /// $\Omega_p$ in arcminutes per time unit.
    pub precession_rate_arcmin: Option<Real>,
}

/// Streaming analyser of the relative orbit: feed it every sample of a run, in order.
#[derive(Debug, Clone, Default)]
pub struct OrbitAnalyser {
    previous: Option<Sample>,
    normal: Vec3,
    azimuth: Real,
    apocentres: Vec<Apsis>,
    pericentres: Vec<Apsis>,
    minimum: Option<(Real, Real)>,
}

/// Bisection steps on a step interval: 2⁻⁶⁰ of a step is below round-off in time.
const BISECTIONS: usize = 60;

impl OrbitAnalyser {
    /// An empty analyser.
    pub fn new() -> Self {
        Self::default()
    }

    fn note_minimum(&mut self, time: Real, separation: Real) {
        if !matches!(self.minimum, Some((_, d)) if d <= separation) {
            self.minimum = Some((time, separation));
        }
    }

    fn angle_from(&self, from: &Vec3, to: &Vec3) -> Real {
        self.normal.dot(&from.cross(to)).atan2(from.dot(to))
    }

    /// Takes the next sample.
    pub fn observe(&mut self, sample: &Sample) {
        let r = sample.state.relative_position();
        self.note_minimum(sample.time, r.norm());
        let Some(previous) = self.previous else {
            let n = r.cross(&sample.state.relative_velocity());
            self.normal = if n.norm() > 0.0 {
                n.normalize()
            } else {
                Vec3::z()
            };
            self.azimuth = 0.0;
            self.previous = Some(*sample);
            return;
        };
        let r0 = previous.state.relative_position();
        let g0 = r0.dot(&previous.state.relative_velocity());
        let g1 = r.dot(&sample.state.relative_velocity());
        let apocentre = g0 >= 0.0 && g1 < 0.0;
        let pericentre = g0 <= 0.0 && g1 > 0.0;
        if apocentre || pericentre {
            let time = if g0 == 0.0 {
                previous.time
            } else {
                let (mut lo, mut hi) = (previous.time, sample.time);
                for _ in 0..BISECTIONS {
                    let mid = 0.5 * (lo + hi);
                    let (rm, vm) = relative_between(&previous, sample, mid);
                    if (rm.dot(&vm) > 0.0) == (g0 > 0.0) {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                0.5 * (lo + hi)
            };
            let (position, _) = relative_between(&previous, sample, time);
            let apsis = Apsis {
                time,
                separation: position.norm(),
                azimuth: self.azimuth + self.angle_from(&r0, &position),
                relative_position: position,
            };
            if apocentre {
                self.apocentres.push(apsis);
            } else {
                self.note_minimum(apsis.time, apsis.separation);
                self.pericentres.push(apsis);
            }
        }
        self.azimuth += self.angle_from(&r0, &r);
        self.previous = Some(*sample);
    }

    /// The analysis of the samples seen so far.
    pub fn report(&self) -> OrbitReport {
        let apsides = if self.apocentres.len() >= 2 {
            &self.apocentres
        } else {
            &self.pericentres
        };
        let (mut radial_period, mut azimuthal_period, mut angle, mut rate) =
            (None, None, None, None);
        if apsides.len() >= 2 {
            let cycles = (apsides.len() - 1) as Real;
            let first = apsides[0];
            let last = apsides[apsides.len() - 1];
            let t_r = (last.time - first.time) / cycles;
            let sweep = (last.azimuth - first.azimuth) / cycles;
            let psi_p = (sweep - 2.0 * std::f64::consts::PI).to_degrees();
            radial_period = Some(t_r);
            angle = Some(psi_p);
            rate = Some(60.0 * psi_p / t_r);
            azimuthal_period = Some(t_r * 2.0 * std::f64::consts::PI / sweep);
        }
        OrbitReport {
            apocentres: self.apocentres.clone(),
            pericentres: self.pericentres.clone(),
            minimum_separation: self.minimum.map(|m| m.1),
            minimum_separation_time: self.minimum.map(|m| m.0),
            radial_period,
            azimuthal_period,
            precession_angle_deg: angle,
            precession_rate_arcmin: rate,
        }
    }
}
