//! Conservation diagnostics: total energy, angular momentum and the statistics of their per-step
//! changes (the founding paper's Table 2).
//!
//! - Energy $E = T + V$ with $T = \sum_k \tfrac12 m_k |\dot{\mathbf R}\_k|^2 + \tfrac12\boldsymbol\omega_k\cdot\mathsf I_k\boldsymbol\omega_k$
//!   (translation and spin; a body without an inertia tensor has no spin energy) and $V$ the
//!   model's mutual potential energy.
//! - Total angular momentum about the origin
//!   $\mathbf J = \sum_k m_k \mathbf R_k \times \dot{\mathbf R}\_k + \mathsf Q_k\mathsf I_k\mathsf Q_k^{-1}\boldsymbol\omega_k$.
//! - Per-step changes $\Delta E_k = E_k - E\_{k-1}$ and $\Delta J_k = |\mathbf J_k| - |\mathbf J\_{k-1}|$
//!   between consecutive samples; their mean, sample standard deviation $\sigma$ (divisor $N-1$),
//!   standard error $\sigma/\sqrt N$ and the slope of the least-squares line of the change against
//!   the time at the end of the step.
//! - Largest relative drift $\max_k |E_k - E_0|/|E_0|$ (and the same for $|\mathbf J|$).
//!
//! The moments are accumulated in one pass with Welford's updates (mean, second moment,
//! co-moment with time), which do not cancel catastrophically; the sum of the changes is kept with
//! Neumaier's compensated summation, so it telescopes to $E_N - E_0$ to round-off.

use crate::model::{InteractionError, InteractionModel};
use crate::state::{Sample, TwoBodyState};
use surfgrav_potentials::{Real, Vec3};

/// Neumaier's compensated sum: the workspace's one (`surfgrav_quadrature::CompensatedSum`).
pub use surfgrav_surfaces::CompensatedSum;

/// Translational kinetic energy $T$.
pub fn kinetic_energy(model: &dyn InteractionModel, state: &TwoBodyState) -> Real {
    let spin = |inertia: Option<surfgrav_potentials::InertiaTensor>, body: &crate::BodyState| {
        inertia.map_or(0.0, |i| {
            let w = body
                .orientation
                .inverse_transform_vector(&body.angular_velocity);
            0.5 * w.dot(&i.angular_momentum(&w))
        })
    };
    0.5 * model.mass_a() * state.body_a.velocity.norm_squared()
        + 0.5 * model.mass_b() * state.body_b.velocity.norm_squared()
        + spin(model.inertia_a(), &state.body_a)
        + spin(model.inertia_b(), &state.body_b)
}

/// Total energy $E = T + V$.
pub fn total_energy(
    model: &dyn InteractionModel,
    state: &TwoBodyState,
) -> Result<Real, InteractionError> {
    let potential = model.potential_energy(&state.body_a.pose(), &state.body_b.pose())?;
    Ok(kinetic_energy(model, state) + potential)
}

/// Spin angular momentum of one body about its centroid, world frame:
/// $\mathsf Q\\,\mathsf I\\,\mathsf Q^{-1}\boldsymbol\omega$ (zero without an inertia tensor).
pub fn spin_angular_momentum(
    inertia: Option<surfgrav_potentials::InertiaTensor>,
    body: &crate::BodyState,
) -> Vec3 {
    inertia.map_or_else(Vec3::zeros, |i| {
        body.orientation
            * i.angular_momentum(
                &body
                    .orientation
                    .inverse_transform_vector(&body.angular_velocity),
            )
    })
}

/// Total angular momentum about the origin, orbital and spin:
/// $\mathbf J = \sum_k m_k\mathbf R_k\times\dot{\mathbf R}\_k + \mathsf Q_k\mathsf I_k\boldsymbol\omega_k$
/// (the spins count for bodies whose model gives an inertia tensor).
pub fn angular_momentum(model: &dyn InteractionModel, state: &TwoBodyState) -> Vec3 {
    state.body_a.position.cross(&state.body_a.velocity) * model.mass_a()
        + state.body_b.position.cross(&state.body_b.velocity) * model.mass_b()
        + spin_angular_momentum(model.inertia_a(), &state.body_a)
        + spin_angular_momentum(model.inertia_b(), &state.body_b)
}

/// Streaming statistics of a series $x_k$ observed at times $t_k$.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SeriesAccumulator {
    count: usize,
    mean_x: Real,
    mean_t: Real,
    second_moment_x: Real,
    second_moment_t: Real,
    co_moment: Real,
    sum: CompensatedSum,
}

/// Summary statistics of a series of per-step changes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeriesStatistics {
    /// Number of values $N$.
    pub count: usize,
    /// Mean.
    pub mean: Real,
    /// Sample standard deviation $\sigma$ (divisor $N - 1$; 0 when $N < 2$).
    pub standard_deviation: Real,
    /// Standard error $\sigma/\sqrt N$.
    pub standard_error: Real,
    /// Slope of the least-squares line against time (0 when undefined).
    pub slope: Real,
    /// Compensated sum of the values.
    pub sum: Real,
}

impl SeriesAccumulator {
    /// Adds the value `x` observed at time `t`.
    pub fn push(&mut self, t: Real, x: Real) {
        self.count += 1;
        let n = self.count as Real;
        let dx = x - self.mean_x;
        let dt = t - self.mean_t;
        self.mean_x += dx / n;
        self.mean_t += dt / n;
        self.second_moment_x += dx * (x - self.mean_x);
        self.second_moment_t += dt * (t - self.mean_t);
        self.co_moment += dt * (x - self.mean_x);
        self.sum.add(x);
    }

    /// The statistics so far.
    pub fn statistics(&self) -> SeriesStatistics {
        let n = self.count as Real;
        let standard_deviation = if self.count > 1 {
            (self.second_moment_x / (n - 1.0)).sqrt()
        } else {
            0.0
        };
        SeriesStatistics {
            count: self.count,
            mean: self.mean_x,
            standard_deviation,
            standard_error: if self.count > 0 {
                standard_deviation / n.sqrt()
            } else {
                0.0
            },
            slope: if self.second_moment_t > 0.0 {
                self.co_moment / self.second_moment_t
            } else {
                0.0
            },
            sum: self.sum.value(),
        }
    }
}

/// The conservation report of one quantity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConservationStatistics {
    /// Value at the first sample.
    pub initial: Real,
    /// Value at the last sample.
    pub last: Real,
    /// Statistics of the per-step changes.
    pub step_changes: SeriesStatistics,
    /// $\max_k |x_k - x_0| / |x_0|$ (absolute when $x_0 = 0$).
    pub max_relative_drift: Real,
}

/// Energy and angular momentum over a run, fed sample by sample.
///
/// Evaluates the energy once per sample (never at integrator stages).
pub struct ConservationMonitor<'m> {
    model: &'m dyn InteractionModel,
    previous: Option<(Real, Real)>,
    initial: (Real, Real),
    initial_vector: Vec3,
    energy: SeriesAccumulator,
    angular_momentum: SeriesAccumulator,
    max_energy_drift: Real,
    max_angular_momentum_drift: Real,
    error: Option<(Real, InteractionError)>,
}

impl<'m> ConservationMonitor<'m> {
    /// A monitor for runs of `model`.
    pub fn new(model: &'m dyn InteractionModel) -> Self {
        Self {
            model,
            previous: None,
            initial: (0.0, 0.0),
            initial_vector: Vec3::zeros(),
            energy: SeriesAccumulator::default(),
            angular_momentum: SeriesAccumulator::default(),
            max_energy_drift: 0.0,
            max_angular_momentum_drift: 0.0,
            error: None,
        }
    }

    /// Takes the next sample. After a model error the monitor ignores further samples and
    /// [`ConservationMonitor::energy`] reports the error.
    pub fn observe(&mut self, sample: &Sample) {
        if self.error.is_some() {
            return;
        }
        let energy = match total_energy(self.model, &sample.state) {
            Ok(e) => e,
            Err(err) => {
                self.error = Some((sample.time, err));
                return;
            }
        };
        let j = angular_momentum(self.model, &sample.state);
        let j_norm = j.norm();
        let relative = |x: Real, x0: Real| {
            if x0 != 0.0 {
                ((x - x0) / x0).abs()
            } else {
                (x - x0).abs()
            }
        };
        match self.previous {
            None => {
                self.initial = (energy, j_norm);
                self.initial_vector = j;
            }
            Some((e_prev, j_prev)) => {
                self.energy.push(sample.time, energy - e_prev);
                self.angular_momentum.push(sample.time, j_norm - j_prev);
                self.max_energy_drift = self.max_energy_drift.max(relative(energy, self.initial.0));
                self.max_angular_momentum_drift = self
                    .max_angular_momentum_drift
                    .max(relative(j_norm, self.initial.1));
            }
        }
        self.previous = Some((energy, j_norm));
    }

    /// Angular momentum vector at the first sample.
    pub fn initial_angular_momentum(&self) -> Vec3 {
        self.initial_vector
    }

    /// Energy statistics, or the model error (with its time) that stopped the monitor.
    pub fn energy(&self) -> Result<ConservationStatistics, (Real, InteractionError)> {
        self.report(&self.energy, self.initial.0, 0, self.max_energy_drift)
    }

    /// Statistics of $|\mathbf J|$.
    pub fn angular_momentum(&self) -> Result<ConservationStatistics, (Real, InteractionError)> {
        self.report(
            &self.angular_momentum,
            self.initial.1,
            1,
            self.max_angular_momentum_drift,
        )
    }

    fn report(
        &self,
        series: &SeriesAccumulator,
        initial: Real,
        which: usize,
        drift: Real,
    ) -> Result<ConservationStatistics, (Real, InteractionError)> {
        if let Some(err) = &self.error {
            return Err(err.clone());
        }
        let last = self
            .previous
            .map(|p| if which == 0 { p.0 } else { p.1 })
            .unwrap_or(initial);
        Ok(ConservationStatistics {
            initial,
            last,
            step_changes: series.statistics(),
            max_relative_drift: drift,
        })
    }
}
