//! The adaptive cubature ([`surfgrav_quadrature::AdaptiveCubature`], Gauss–Kronrod G7–K15
//! per direction) over X's parameter rectangle (see the [module docs](super::super), method
//! 4): on request, and as the fallback when the ladder runs out of levels. The 10 integrand
//! components (force, both torques, energy) in one pass, over the polar-angle form of an
//! ellipsoid.

use super::{Problem, Strategy};
use crate::assembly::{
    assemble, not_met, relative_from_absolute, symmetrise_lamina, symmetrise_solid, Values,
};
use crate::body::{with_field, Body, BodyShape};
use crate::error::InteractionError;
use crate::kernel::{
    add_lamina_area_node, add_lamina_rim_node, solid_node, FrameMap, LaminaBlock, LaminaMagnitudes,
    LaminaSums, SolidSums,
};
use crate::options::{Interaction, Method};
use crate::surface_choice::Placement;
use surfgrav_potentials::Potential;
use surfgrav_quadrature::{
    AdaptiveCubature, AdaptiveOptions, Rectangle, MINIMUM_EVALUATION_BUDGET,
};
use surfgrav_surfaces::{Real, Surface, Vec3};

/// The adaptive rule, with the integrator's workspace created on first use and kept.
#[derive(Debug, Clone, Default)]
pub(crate) struct Adaptive {
    integrator: Option<AdaptiveCubature<10>>,
}

impl Strategy for Adaptive {
    /// The adaptive cubature, asked for a quarter of the tolerance on the largest component
    /// (the energy's scale); if the estimate in the engine's norms still exceeds the tolerance
    /// (a force that cancels far away), asked again for less, at most twice, as long as the
    /// estimate keeps falling (it stops at the integrator's rounding floor).
    fn refine(&mut self, problem: &Problem<'_>) -> Result<Interaction, InteractionError> {
        let Problem {
            x,
            y,
            placement: p,
            options,
            budget,
            ..
        } = *problem;
        let tolerance = options.relative_tolerance;
        let mut request = 0.25 * tolerance;
        let mut total = 0usize;
        let mut best: Option<Interaction> = None;
        for _ in 0..3 {
            let remaining = budget.saturating_sub(total);
            if remaining < MINIMUM_EVALUATION_BUDGET {
                break;
            }
            let options = AdaptiveOptions {
                relative_tolerance: request,
                absolute_tolerance: 0.0,
                max_evaluations: remaining,
            };
            let integrator = match &mut self.integrator {
                Some(integrator) => {
                    integrator.set_options(options)?;
                    integrator
                }
                none => none.insert(AdaptiveCubature::new(options)?),
            };
            let (values, estimate, evaluations, converged) = adaptive_values(integrator, x, y, p)?;
            total += evaluations;
            let result = values.finish(Method::Adaptive, Some(p.side), total, estimate, None)?;
            if estimate <= tolerance {
                return Ok(result);
            }
            let improved = best
                .as_ref()
                .is_none_or(|b| estimate < 0.9 * b.error_estimate);
            if improved {
                best = Some(result);
            }
            if !converged || !improved {
                break;
            }
            request = (request * 0.5 * tolerance / estimate).max(request * 1e-3);
        }
        match best {
            Some(mut best) => {
                best.evaluations = total;
                Err(not_met(tolerance, best))
            }
            None => Err(InteractionError::BudgetTooSmall {
                max_evaluations: budget,
                minimum: MINIMUM_EVALUATION_BUDGET,
            }),
        }
    }
}

/// The adaptive cubature over X's parameter rectangle (reduced by the mirror symmetries);
/// returns the values, the relative error estimate, the evaluations and whether the
/// integrator reported convergence.
fn adaptive_values(
    integrator: &mut AdaptiveCubature<10>,
    x: &Body,
    y: &Body,
    p: &Placement,
) -> Result<(Values, Real, usize, bool), InteractionError> {
    let distance = (p.position_y - p.position_x).norm().max(Real::MIN_POSITIVE);
    let density = x.density;
    match x.shape() {
        BodyShape::Solid(e) => {
            // Always the polar-angle form: the azimuth–height form's √(c² − z²) end point at
            // the poles is removed only by a full azimuthal trapezoid sum, which an adaptive
            // rule on the rectangle does not do (measured: 40 times more evaluations at 10⁻⁶,
            // no convergence at 10⁻¹²).
            let theta_hi = if p.half_transverse {
                std::f64::consts::FRAC_PI_2
            } else {
                std::f64::consts::PI
            };
            let phi_hi = if p.half_azimuth {
                std::f64::consts::PI
            } else {
                std::f64::consts::TAU
            };
            let domain_surface = e.polar_azimuth();
            let rect = Rectangle::new(0.0, theta_hi, 0.0, phi_hi)?;
            solid_adaptive(
                integrator,
                &domain_surface,
                rect,
                x,
                y,
                p,
                distance,
                density,
            )
        }
        BodyShape::Surface(s) => {
            let domain = s.parameter_domain();
            let rect = Rectangle::new(
                domain.u.start(),
                domain.u.end(),
                domain.v.start(),
                domain.v.end(),
            )?;
            solid_adaptive(integrator, s.as_ref(), rect, x, y, p, distance, density)
        }
        BodyShape::Disk(l) => lamina_adaptive(integrator, l.radius(), y, p, distance, density),
        BodyShape::Point | BodyShape::FieldOnly | BodyShape::Mesh(_) => {
            Err(InteractionError::NoSurface {
                reason: "the body chosen to integrate over has no surface",
            })
        }
    }
}

#[allow(clippy::too_many_arguments)]
fn solid_adaptive(
    integrator: &mut AdaptiveCubature<10>,
    surface: &dyn Surface,
    rect: Rectangle,
    _x: &Body,
    y: &Body,
    p: &Placement,
    distance: Real,
    density: Real,
) -> Result<(Values, Real, usize, bool), InteractionError> {
    // As in the fixed rules, Φ at the centroid comes out of the force and torque integrands
    // (∮ dS = 0, ∮ x × dS = 0), which lowers the integrator's rounding floor.
    let estimate = with_field!(&y.field, |f| {
        let reference = f.potential(&p.map.apply(&Vec3::zeros()));
        integrator.integrate(rect, |u, v, out: &mut [Real; 10]| {
            let (r, w) = surface.point_and_area_vector(u, v);
            let field = f.field(&p.map.apply(&r));
            // The kernel's one integrand; the force part scaled by the distance so that the
            // integrator's error norm weighs it like the torques.
            let node = solid_node(&field, &p.map, r, &w, reference);
            let flux = node.flux * distance;
            out[0] = flux.x;
            out[1] = flux.y;
            out[2] = flux.z;
            out[3] = node.moment.x;
            out[4] = node.moment.y;
            out[5] = node.moment.z;
            out[6] = node.gradient_moment.x;
            out[7] = node.gradient_moment.y;
            out[8] = node.gradient_moment.z;
            out[9] = node.energy;
        })
    })?;
    let v = &estimate.value;
    let e = &estimate.error_estimate;
    let mut sums = SolidSums {
        potential_flux: Vec3::new(v[0], v[1], v[2]) / distance,
        potential_moment: Vec3::new(v[3], v[4], v[5]),
        gradient_moment: Vec3::new(v[6], v[7], v[8]),
        energy_flux: v[9],
        ..SolidSums::default()
    };
    let mut multiplicity = 1.0;
    if p.half_azimuth {
        sums = symmetrise_solid(&sums, 1);
        multiplicity *= 2.0;
    }
    if p.half_transverse {
        sums = symmetrise_solid(&sums, 2);
        multiplicity *= 2.0;
    }
    let r = sums.integrals(density, estimate.evaluations);
    let values = assemble(
        p,
        &r.force,
        &r.torque,
        &r.torque_gradient_form,
        r.potential_energy,
    );
    // Absolute errors of the physical quantities (the symmetrisation adds the halves' errors).
    let force_error = multiplicity * density * Vec3::new(e[0], e[1], e[2]).norm() / distance;
    let torque_error = multiplicity * density * Vec3::new(e[3], e[4], e[5]).norm();
    let energy_error = multiplicity * density * e[9] / 3.0;
    let relative =
        relative_from_absolute(&values, force_error, torque_error, energy_error, distance);
    let relative = relative.max(values.form_discrepancy(values.torque_on_a.norm()));
    Ok((values, relative, estimate.evaluations, estimate.converged()))
}

/// The lamina's integrand at $(\varphi, s)$ for the adaptive cubature, from the shared node
/// terms ([`add_lamina_area_node`] with the area weight $s$ of the polar coordinates,
/// [`add_lamina_rim_node`] with the rim normal $(\cos\varphi, \sin\varphi, 0)$ spread evenly over
/// $s \in [0, R]$): the energy, the normal force and the rim flux scaled by `distance` (so that
/// every component has the energy's scale), the torque (normal form), the area form's axial
/// torque.
#[allow(clippy::too_many_arguments)]
#[inline]
pub(crate) fn lamina_integrand<P: Potential + ?Sized>(
    f: &P,
    map: &FrameMap,
    radius: Real,
    reference: Real,
    distance: Real,
    phi: Real,
    s: Real,
    out: &mut [Real; 10],
) {
    let (sin, cos) = phi.sin_cos();
    let outward = Vec3::new(cos, sin, 0.0);
    let r = outward * s;
    let mut node = LaminaBlock::default();
    let mut sizes = LaminaMagnitudes::default();
    let field = f.field(&map.apply(&r));
    add_lamina_area_node(&mut node, &mut sizes, &field, map, &r, &Vec3::z(), s);
    let rim = f.potential(&map.apply(&(outward * radius)));
    add_lamina_rim_node(&mut node, &mut sizes, rim, reference, &outward);
    out[0] = node.potential;
    out[1] = node.normal_acceleration * distance;
    out[2] = node.normal_moment.x;
    out[3] = node.normal_moment.y;
    out[4] = node.rim_potential_flux.x * distance;
    out[5] = node.rim_potential_flux.y * distance;
    out[6] = node.moment.z;
}

fn lamina_adaptive(
    integrator: &mut AdaptiveCubature<10>,
    radius: Real,
    y: &Body,
    p: &Placement,
    distance: Real,
    density: Real,
) -> Result<(Values, Real, usize, bool), InteractionError> {
    let phi_hi = if p.half_azimuth {
        std::f64::consts::PI
    } else {
        std::f64::consts::TAU
    };
    let rect = Rectangle::new(0.0, phi_hi, 0.0, radius)?;
    // Area integrand in polar coordinates (s ds dφ) plus the rim line integral spread evenly
    // over s ∈ [0, R] (so one 2-D integral carries both).
    let estimate = with_field!(&y.field, |f| {
        // ∮ ν̂ dl = 0: Φ at the centre comes out of the rim integrand.
        let reference = f.potential(&p.map.apply(&Vec3::zeros()));
        integrator.integrate(rect, |phi: Real, s: Real, out: &mut [Real; 10]| {
            lamina_integrand(f, &p.map, radius, reference, distance, phi, s, out);
        })
    })?;
    let v = &estimate.value;
    let e = &estimate.error_estimate;
    let mut sums = LaminaSums {
        area_potential: v[0],
        area_normal_acceleration: v[1] / distance,
        area_normal_moment: Vec3::new(v[2], v[3], 0.0),
        area_acceleration: Vec3::zeros(),
        area_moment: Vec3::new(v[2], v[3], v[6]),
        rim_potential_flux: Vec3::new(v[4], v[5], 0.0) / distance,
        ..LaminaSums::default()
    };
    let mut multiplicity = 1.0;
    if p.half_azimuth {
        sums = symmetrise_lamina(&sums, 1);
        multiplicity *= 2.0;
    }
    let evaluations = 2 * estimate.evaluations;
    let r = sums.integrals(density, &Vec3::z(), evaluations);
    let values = assemble(
        p,
        &r.force,
        &r.torque,
        &r.torque_area_form,
        r.potential_energy,
    );
    let force_error = multiplicity * density * (e[1].hypot(e[4]).hypot(e[5])) / distance;
    let torque_error = multiplicity * density * e[2].hypot(e[3]).hypot(e[6]);
    let energy_error = multiplicity * density * e[0];
    let relative =
        relative_from_absolute(&values, force_error, torque_error, energy_error, distance);
    Ok((values, relative, evaluations, estimate.converged()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::lamina_sums;
    use surfgrav_potentials::{Ellipsoid, Pose, UniformDisk};
    use surfgrav_surfaces::{Lamina, LaminaNodes};

    /// One lamina integrand: the adaptive cubature's integrand ([`lamina_integrand`]) and the
    /// table loop ([`lamina_sums`], which evaluates its blocks through the batched
    /// `fields_into` / `potentials_into`) give the same bits on the same node, for a triaxial
    /// ellipsoid and a disk as the source, 64 nodes each (both go through
    /// [`add_lamina_area_node`] and [`add_lamina_rim_node`]; a unit disk, so that the table's
    /// area weight $1\cdot1\cdot s$ and rim normal $(\cos\varphi, \sin\varphi, 0)\cdot(1\cdot1)$ are
    /// exactly the integrand's).
    #[test]
    fn the_adaptive_and_table_lamina_integrands_agree_bit_for_bit() {
        let lamina = Lamina::new(1.0).unwrap();
        let pose = Pose::new(Vec3::new(0.3, -0.4, 1.2), Vec3::new(0.4, 0.2, -0.7));
        let map = FrameMap::between(&Pose::identity(), &pose).unwrap();
        let ellipsoid = Ellipsoid::new(1.0, 0.7, 0.4, 1.0).unwrap();
        let disk = UniformDisk::new(0.8, 1.0).unwrap();
        let sources: [&dyn Potential; 2] = [&ellipsoid, &disk];
        let distance = 1.3;
        for source in sources {
            let reference = source.potential(&map.apply(&Vec3::zeros()));
            let mut nodes = LaminaNodes::default();
            for i in 0..8 {
                for j in 0..8 {
                    let phi = 0.1 + 0.77 * Real::from(i);
                    let s = 0.05 + 0.12 * Real::from(j);
                    let (sin, cos) = phi.sin_cos();
                    lamina.fill_nodes(
                        &[(cos, sin, 1.0)],
                        &[(s, 1.0)],
                        &[(cos, sin, 1.0)],
                        &mut nodes,
                    );
                    let sums = lamina_sums(&nodes, source, &map);
                    let mut out = [0.0; 10];
                    lamina_integrand(source, &map, 1.0, reference, distance, phi, s, &mut out);
                    let table = [
                        sums.area_potential,
                        sums.area_normal_acceleration * distance,
                        sums.area_normal_moment.x,
                        sums.area_normal_moment.y,
                        sums.rim_potential_flux.x * distance,
                        sums.rim_potential_flux.y * distance,
                        sums.area_moment.z,
                    ];
                    for (k, (got, want)) in out.iter().zip(&table).enumerate() {
                        assert_eq!(
                            got.to_bits(),
                            want.to_bits(),
                            "component {k} at phi {phi}, s {s}: {got:e} against {want:e}"
                        );
                    }
                    assert!(out[0] < 0.0 && out[1] != 0.0, "phi {phi}, s {s}: {out:?}");
                }
            }
        }
    }
}
