//! The accuracy requirements of this crate's tests, in one place (issue 4's numbers).
//!
//! Test-specific bounds that describe a measured property of one method at one step size (for
//! instance the RK4 error on the paper-point orbit) stay beside their test with a comment.

/// Kepler orbit, e = 0.5, 10 orbits with the adaptive integrator at tight tolerance: largest
/// position error of the relative orbit against the analytic solution (issue 4).
pub const KEPLER_ADAPTIVE_POSITION: f64 = 1e-10;

/// Largest allowed difference between a measured order of convergence (from the errors at two
/// step sizes h and h/2 after one Kepler orbit) and the method's nominal order. The measurement
/// differs from the nominal order by the next term of the error expansion, O(h), which at the
/// chosen step counts is below 0.15 for every method.
pub const ORDER_OF_CONVERGENCE: f64 = 0.2;

/// Time reversibility of a symmetric composition: |state after N steps forward, velocity reversal,
/// N steps, reversal − initial state| (positions plus velocities, unit-size orbit). Round-off
/// only: a few hundred ULP after 200–4000 force evaluations.
pub const REVERSIBILITY: f64 = 1e-12;

/// Symplectic methods: the largest relative energy error in the last tenth of a long run may
/// exceed the largest in the first tenth by at most this factor (no secular drift).
pub const ENERGY_DRIFT_FACTOR: f64 = 1.1;

/// A model's torques count as vanishing when the larger of |τ_A|, |τ_B| is at most this fraction
/// of |F_A| × separation (the torque a force of the same size would exert at the separation's
/// lever arm). Torques that vanish by symmetry come out of a surface-integral engine at the
/// quadrature tolerance (≈ 1e-12 relative), well below this.
pub const TORQUE_FREE_RELATIVE: f64 = 1e-10;
