//! One call that integrates a scene and gathers every diagnostic: what a command-line tool or a
//! report needs.

use crate::diagnostics::{ConservationMonitor, ConservationStatistics};
use crate::integrate::{DynamicsError, Integrator, RunSummary};
use crate::model::InteractionModel;
use crate::orbit::{OrbitAnalyser, OrbitReport};
use crate::state::{Sample, TwoBodyState};
use surfgrav_potentials::Real;

/// Everything a run produced.
#[derive(Debug, Clone, PartialEq)]
pub struct RunReport {
    /// Steps, evaluations, last sample, termination.
    pub summary: RunSummary,
    /// Energy statistics (E = T + V, per-step changes).
    pub energy: ConservationStatistics,
    /// Statistics of |J|.
    pub angular_momentum: ConservationStatistics,
    /// Apsides, periods, precession, minimum separation.
    pub orbit: OrbitReport,
}

/// Integrates `initial` from `t_start` to `t_end` with `integrator`, feeding every sample to the
/// conservation monitor, the orbit analyser and `observer` (for output), in that order.
///
/// A model error while evaluating the energy of a sample is reported as
/// [`DynamicsError::Interaction`] at that sample's time.
pub fn run_with_diagnostics(
    integrator: &mut dyn Integrator,
    model: &dyn InteractionModel,
    initial: &TwoBodyState,
    t_start: Real,
    t_end: Real,
    observer: &mut dyn FnMut(&Sample),
) -> Result<RunReport, DynamicsError> {
    let mut monitor = ConservationMonitor::new(model);
    let mut orbit = OrbitAnalyser::new();
    let summary = integrator.integrate(model, initial, t_start, t_end, &mut |sample| {
        monitor.observe(sample);
        orbit.observe(sample);
        observer(sample);
    })?;
    let to_error = |(time, source)| DynamicsError::Interaction { time, source };
    Ok(RunReport {
        summary,
        energy: monitor.energy().map_err(to_error)?,
        angular_momentum: monitor.angular_momentum().map_err(to_error)?,
        orbit: orbit.report(),
    })
}
