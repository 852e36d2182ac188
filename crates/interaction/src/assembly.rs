//! Result assembly: the values a strategy refines ([`Values`]), their world-frame assembly
//! from the integrals over the integrated body X (force and torque on X, the other body's
//! torque by the balance of angular momentum), their rounding bounds, and the final
//! [`Interaction`] with its error estimate.

use super::error::{InteractionError, Side};
use super::kernel::{LaminaSums, SolidSums};
use super::options::{Interaction, Method, Request};
use super::surface_choice::Placement;
use surfgrav_surfaces::{Real, Vec3};

/// Relative rounding error allowed per node term in the fixed rules' floor: the field's own
/// error (a few ULP, the potentials crate's measured worst case is below 4) and the products.
/// The floor $4\epsilon\sum_k|t_k|$ per sum bounds the rounding of sums whose terms cancel
/// (the force far from the source, where $\sum|t_k|$ exceeds the result a hundredfold).
pub const ROUNDING_PER_TERM: Real = 4.0 * Real::EPSILON;

/// The part of a result that the levels refine.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Values {
    pub(crate) force_on_a: Vec3,
    pub(crate) torque_on_a: Vec3,
    pub(crate) torque_on_b: Vec3,
    pub(crate) potential_energy: Real,
    /// The discrepancy of the second torque form (world frame, on the integrated body).
    pub(crate) torque_form_gap: Real,
    /// Relative rounding error bound of this evaluation (see [`ROUNDING_PER_TERM`]).
    pub(crate) rounding: Real,
    /// What was asked for: the node loop computed and the estimate certifies only that
    /// (with [`Request::Force`], torques and energy are placeholders).
    pub(crate) request: Request,
}

impl Values {
    /// $|\delta\mathbf F|/|\mathbf F|$ against `other`.
    pub(crate) fn force_change(&self, other: &Values) -> Real {
        (self.force_on_a - other.force_on_a).norm() / self.force_on_a.norm().max(Real::MIN_POSITIVE)
    }

    pub(crate) fn relative_change(&self, other: &Values) -> Real {
        let v = self.potential_energy.abs().max(Real::MIN_POSITIVE);
        let df = (self.force_on_a - other.force_on_a).norm()
            / self.force_on_a.norm().max(Real::MIN_POSITIVE);
        if self.request == Request::Force {
            return df;
        }
        let dma = (self.torque_on_a - other.torque_on_a).norm() / self.torque_on_a.norm().max(v);
        let dmb = (self.torque_on_b - other.torque_on_b).norm() / self.torque_on_b.norm().max(v);
        if self.request == Request::Wrench {
            return df.max(dma).max(dmb);
        }
        let dv = (self.potential_energy - other.potential_energy).abs() / v;
        df.max(dv).max(dma).max(dmb)
    }

    pub(crate) fn form_discrepancy(&self, torque_scale: Real) -> Real {
        if self.request == Request::Force {
            return 0.0;
        }
        self.torque_form_gap
            / torque_scale
                .max(self.potential_energy.abs())
                .max(Real::MIN_POSITIVE)
    }

    pub(crate) fn finish(
        &self,
        method: Method,
        integrated_over: Option<Side>,
        evaluations: usize,
        error_estimate: Real,
        level: Option<u16>,
    ) -> Result<Interaction, InteractionError> {
        let result = Interaction {
            force_on_a: self.force_on_a,
            force_on_b: -self.force_on_a,
            torque_on_a: self.torque_on_a,
            torque_on_b: self.torque_on_b,
            potential_energy: self.potential_energy,
            method,
            integrated_over,
            evaluations,
            error_estimate,
            level,
        };
        finite(result)
    }
}

pub(crate) fn not_met(tolerance: Real, best: Interaction) -> InteractionError {
    InteractionError::ToleranceNotMet {
        tolerance,
        error_estimate: best.error_estimate,
        evaluations: best.evaluations,
        best: Box::new(best),
    }
}

/// World-frame values from integrals over X in its integration frame: force and torque on X.
pub(crate) fn assemble(
    p: &Placement,
    force_x: &Vec3,
    torque_x: &Vec3,
    torque_x_second: &Vec3,
    energy: Real,
) -> Values {
    let f_x = p.rotation * force_x;
    let m_x = p.rotation * torque_x;
    let m_x2 = p.rotation * torque_x_second;
    let f_y = -f_x;
    let m_y = -m_x - (p.position_x - p.position_y).cross(&f_x);
    let (force_on_a, torque_on_a, torque_on_b) = match p.side {
        Side::A => (f_x, m_x, m_y),
        Side::B => (f_y, m_y, m_x),
    };
    Values {
        force_on_a,
        torque_on_a,
        torque_on_b,
        potential_energy: energy,
        torque_form_gap: (m_x - m_x2).norm(),
        rounding: 0.0,
        request: Request::Everything,
    }
}

/// World-frame values, with their rounding bound, from the raw sums over X's (possibly
/// reduced) node set: the mirror images are added first.
pub(crate) fn solid_values(mut s: SolidSums, density: Real, p: &Placement) -> Values {
    if p.half_azimuth {
        s = symmetrise_solid(&s, 1);
    }
    if p.half_transverse {
        s = symmetrise_solid(&s, 2);
    }
    let mut r = s.integrals(density, 0);
    // The potential form's rounding: that of its terms, and the absolute rounding of Φ itself,
    // which Φ − Φ₀ keeps (Σ|Φ||W|: it dominates where the terms cancel to a force small next
    // to ρ|Φ| times the area, far away or for a flat body, whose faces' terms nearly cancel).
    let potential_floor = s.potential_flux_magnitude + s.potential_magnitude;
    // The acceleration form (see FAR_FIELD_RATIO), where summed and its floor is lower.
    let acceleration_floor = s.acceleration_flux_magnitude;
    let acceleration_form = acceleration_floor > 0.0 && acceleration_floor < potential_floor;
    let force_size = if acceleration_form {
        r.force = density * s.acceleration_flux;
        acceleration_floor
    } else {
        potential_floor
    };
    let mut values = assemble(
        p,
        &r.force,
        &r.torque,
        &r.torque_gradient_form,
        r.potential_energy,
    );
    if s.potential_moment_magnitude == 0.0 && s.energy_flux_magnitude == 0.0 {
        // Force only: the force's own rounding.
        values.rounding = ROUNDING_PER_TERM * density * force_size
            / values.force_on_a.norm().max(Real::MIN_POSITIVE);
        return values;
    }
    values.rounding = relative_from_absolute(
        &values,
        ROUNDING_PER_TERM * density * force_size,
        ROUNDING_PER_TERM * density * s.potential_moment_magnitude,
        ROUNDING_PER_TERM * density * s.energy_flux_magnitude / 3.0,
        (p.position_y - p.position_x).norm(),
    );
    values
}

/// The result if every force, torque and energy is finite, else the typed error.
pub(crate) fn finite(result: Interaction) -> Result<Interaction, InteractionError> {
    let finite = result
        .force_on_a
        .iter()
        .chain(result.torque_on_a.iter())
        .chain(result.torque_on_b.iter())
        .all(|x| x.is_finite())
        && result.potential_energy.is_finite();
    if finite {
        Ok(result)
    } else {
        Err(InteractionError::NonFiniteResult {
            what: "force, torque or energy",
        })
    }
}

pub(crate) fn symmetrise_solid(s: &SolidSums, axis: usize) -> SolidSums {
    s.symmetrised(axis)
}

pub(crate) fn symmetrise_lamina(s: &LaminaSums, axis: usize) -> LaminaSums {
    s.plus(&s.mirrored(axis))
}

pub(crate) fn relative_from_absolute(
    values: &Values,
    force_error: Real,
    torque_error: Real,
    energy_error: Real,
    distance: Real,
) -> Real {
    let v = values.potential_energy.abs().max(Real::MIN_POSITIVE);
    let df = force_error / values.force_on_a.norm().max(Real::MIN_POSITIVE);
    let dv = energy_error / v;
    // The torque on the other body inherits the force's error times the lever arm.
    let dma = (torque_error + distance * force_error) / values.torque_on_a.norm().max(v);
    let dmb = (torque_error + distance * force_error) / values.torque_on_b.norm().max(v);
    df.max(dv).max(dma).max(dmb)
}
