//! The interaction engine: method choice, the resolution ladder, the adaptive alternative, and
//! the assembly of world-frame results.

use super::aimed;
use super::body::{Body, BodyShape, SourceField, ALIGNMENT};
use super::error::{InteractionError, Side};
use super::kernel::{lamina_sums, solid_table_sums, FrameMap, LaminaSums, SolidSums};
use super::nested::{self as nested_rule, ellipsoid_line, round_base, solid_sums_from};
// Also the names other modules of the engine import from here.
pub(crate) use super::options::{
    Evaluation, ForceInteraction, Interaction, InteractionOptions, Method, MethodChoice, Request,
    SurfaceChoice,
};
use super::overlap::{contact, Contact};
use super::rules::{
    azimuth_count, next_transverse, table_size, NodeTable, Parametrisation, TableKey,
    TransverseRatio, CLUSTERING, MAX_TRANSVERSE, TRANSVERSE_RATIO,
};
use crate::{Real, Surface, Vec3};
use nalgebra::UnitQuaternion;
use surfgrav_potentials::{CoplanarDiskPair, Pose, Potential, Region, UniformDisk};
use surfgrav_quadrature::{
    geometric_estimate, rate_estimate, AdaptiveCubature, AdaptiveOptions, NestedCubature,
    NestedLevels, Rectangle, MINIMUM_EVALUATION_BUDGET,
};

/// `with_field!(field, |f| expr)`: evaluates `expr` with `f` bound to the concrete potential
/// (one monomorphised copy per built-in kind, `dyn Potential` for user potentials).
macro_rules! with_field {
    ($field:expr, |$f:ident| $body:expr) => {
        match $field {
            SourceField::PointMass($f) => $body,
            SourceField::Sphere($f) => $body,
            SourceField::Spheroid($f) => $body,
            SourceField::Ellipsoid($f) => $body,
            SourceField::Disk($f) => $body,
            SourceField::Custom(custom) => {
                let $f: &dyn Potential = custom.as_ref();
                $body
            }
        }
    };
}

/// Relative rounding error allowed per node term in the fixed rules' floor: the field's own
/// error (a few ULP, the potentials crate's measured worst case is below 4) and the products.
/// The floor $4\epsilon\sum_k|t_k|$ per sum bounds the rounding of sums whose terms cancel
/// (the force far from the source, where $\sum|t_k|$ exceeds the result a hundredfold).
pub const ROUNDING_PER_TERM: Real = 4.0 * Real::EPSILON;

/// Azimuth nodes of the nested rule's start grid over the ladder's predicted count (tuned on
/// the founding paper's pair at separations 2.1 to 30, 10⁻¹²: larger wastes nodes, smaller
/// makes a doubling, twice the nodes, likely).
pub const NESTED_AZIMUTH_SCALE: Real = 1.3;

/// Height nodes of the nested rule's start grid over the ladder's predicted Gauss–Legendre
/// count (Fejér's rule needs more nodes than Gauss–Legendre; tuned as the azimuth scale).
pub const NESTED_HEIGHT_SCALE: Real = 2.4;

/// From this gap ratio $g = (d - R_X - R_Y^{\mathrm{sing}})/R_X$ on (centroid distance $d$,
/// X's bounding radius $R_X$, the radius of Y's singular set), the nested rule starts one
/// level coarser in height and estimates a direction's error geometrically,
/// $\delta_2(\delta_2/\delta_1)^{p}$ with $p$ = [`NESTED_GEOMETRIC_EXPONENT`]
/// ([`surfgrav_quadrature::geometric_estimate`]), instead of $\delta_2^2/\delta_1$. There
/// the integrand is analytic in a strip of half-width about $\operatorname{acosh}(1 + g)$ in
/// the azimuth (and an equally large Bernstein ellipse in height), so the error falls like
/// $\rho^{-n}$ with $\rho \gtrsim 2g$ and each doubling squares it; $\delta_2^2/\delta_1$
/// then over-estimates by $\delta_1/\delta_2$, which made the founding paper's pair at
/// separation 30 certify 10⁻¹² only on 99 nodes (error 10⁻¹⁵) where a 35-node table reaches
/// 10⁻¹⁵. Measured over separations 10 to 10⁸ sizes, c/a 0.01 to 100, four directions and
/// tolerances 10⁻⁶, 10⁻⁹, 10⁻¹² (2016 cases, `nested_far_field_estimates_full_grid` in
/// `tests/interaction_estimates.rs`): no true error above the estimate (with $\delta_2^2/\delta_1$
/// before the change, 72 cases above it at 10⁻⁶ and 10⁻⁹). With this exponent set to 2 (the
/// bare geometric extrapolation) 34 cases missed the tolerance.
pub const NESTED_GEOMETRIC_GAP: Real = 8.0;

/// The exponent $p$ of the nested rule's far-field estimate (see [`NESTED_GEOMETRIC_GAP`]):
/// below the asymptotic 2, a margin for a prefactor that grows with the level.
pub const NESTED_GEOMETRIC_EXPONENT: Real = 1.5;

/// Beyond this many bounding radii of the integrated body X between the centroids, the fixed
/// and nested rules also sum the acceleration form of the force,
/// $\rho\oint\mathbf x\\,(\mathbf a\cdot\mathrm d\mathbf S)$, and use it instead of
/// $-\rho\oint(\Phi - \Phi_0)\\,\mathrm d\mathbf S$ when its rounding floor
/// $\sum|\mathbf x_k||\mathbf a_k\cdot\mathbf W_k|$ is below $\sum|\Phi_k||\mathbf W_k|$, the floor
/// the potential form really has there: $\Phi_k - \Phi_0$ keeps the absolute rounding of
/// $\Phi_k$, about distance/size times its own size, which the potential form's floor
/// $\sum|\Phi_k - \Phi_0||\mathbf W_k|$ does not see. Measured: at $10^8$ sizes the potential
/// form stalls at $10^{-8}$ relative and the acceleration form reaches $10^{-16}$; a flat
/// spheroid (c/a = 0.0013) 89 radii from a needle: $3\times10^{-12}$ against $4\times10^{-13}$.
/// Nearer, only the potential form is summed (the extra terms cost 8 % of the loop), which
/// leaves the founding paper's pair unchanged up to separation 30; a flat body is far sooner
/// (see [`CANCELLATION_RATIO`]).
pub const FAR_FIELD_RATIO: Real = 40.0;

/// Beyond this many cancellation radii (`cancellation_radius`: $3/(1/a + 1/b + 1/c)$ for an
/// ellipsoid X) the acceleration form is summed too: there the potential form's terms exceed
/// the force about $d/R$ times and its rounding floor, $4\epsilon\rho\sum(|\Phi_k - \Phi_0| +
/// |\Phi_k|)|\mathbf W_k|$, reaches about $120 \cdot 4\epsilon \approx 10^{-13}$ relative, a
/// tenth of the default tolerance. This is what matters for a flat body: spheroids of
/// c/a = 0.01 stacked 10 to 30 radii apart along their axes have a force whose potential form
/// scatters by up to $6\cdot10^{-13}$ between tables of 40 to 400 nodes (rounding, the faces'
/// terms cancelling); measured before this rule, 47 of the 2016 far-field cases of
/// `tests/interaction_estimates.rs` had true errors up to $2.6\cdot10^{-13}$ above estimates
/// near $10^{-15}$, none after. A sphere's cancellation radius is its radius, so for round
/// bodies [`FAR_FIELD_RATIO`] decides.
pub const CANCELLATION_RATIO: Real = 120.0;

/// The factor on the aimed rule's predicted cost over a body near a disk (see
/// `InteractionEngine::predicted_cost`): large enough that the disk's lamina rule is chosen.
const AIMED_DISK_PENALTY: Real = 8.0;

/// The relative accuracy reported for the closed forms (the potentials crate's documented
/// accuracy of the acceleration, which dominates).
pub const ANALYTIC_RELATIVE_ERROR: Real = 1e-13;

/// The part of a result that the levels refine.
#[derive(Debug, Clone, Copy)]
struct Values {
    force_on_a: Vec3,
    torque_on_a: Vec3,
    torque_on_b: Vec3,
    potential_energy: Real,
    /// The discrepancy of the second torque form (world frame, on the integrated body).
    torque_form_gap: Real,
    /// Relative rounding error bound of this evaluation (see [`ROUNDING_PER_TERM`]).
    rounding: Real,
    /// What was asked for: the node loop computed and the estimate certifies only that
    /// (with [`Request::Force`], torques and energy are placeholders).
    request: Request,
}

impl Values {
    /// $|\delta\mathbf F|/|\mathbf F|$ against `other`.
    fn force_change(&self, other: &Values) -> Real {
        (self.force_on_a - other.force_on_a).norm() / self.force_on_a.norm().max(Real::MIN_POSITIVE)
    }

    fn relative_change(&self, other: &Values) -> Real {
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

    fn form_discrepancy(&self, torque_scale: Real) -> Real {
        if self.request == Request::Force {
            return 0.0;
        }
        self.torque_form_gap
            / torque_scale
                .max(self.potential_energy.abs())
                .max(Real::MIN_POSITIVE)
    }

    fn finish(
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
}

/// Where the integrated body X and the source body Y are, in X's integration frame.
#[derive(Debug, Clone, Copy)]
struct Placement {
    side: Side,
    /// X's integration frame → world (X's body frame, possibly turned about its axis).
    rotation: UnitQuaternion<Real>,
    position_x: Vec3,
    position_y: Vec3,
    map: FrameMap,
    half_transverse: bool,
    half_azimuth: bool,
    clustering: u8,
    /// Index of the transverse-to-azimuth ratio κ.
    ratio: u8,
    /// Whether the azimuth nodes are clustered.
    clustered: bool,
    /// Sine of Y's elevation above X's equatorial plane.
    sin_elevation: Real,
    /// Gap between X's bounding sphere and Y's singular set, over X's bounding radius.
    gap_ratio: Real,
    /// Whether the integration nodes must be checked against Y's region (shape unknown).
    node_check: bool,
    /// Whether the centroids are more than [`FAR_FIELD_RATIO`] of X's bounding radii apart.
    far: bool,
    /// The aimed rule's pole and clustering, where the fixed rules use it over X
    /// ([`Parametrisation::Aimed`], or [`Parametrisation::Automatic`] without both mirror
    /// symmetries).
    aim: Option<aimed::Aim>,
}

impl Placement {
    /// This placement with the aimed rule's aim where the fixed rules use it over X: an
    /// ellipsoid whose nodes need no check, with [`Parametrisation::Aimed`], or with
    /// [`Parametrisation::Automatic`] unless the pose has both mirror symmetries (then the
    /// azimuth–height table, clustered toward the other body and quartered, is cheaper).
    fn aimed(self, x: &Body, y: &Body, options: InteractionOptions) -> Self {
        let ladder = matches!(
            options.method,
            MethodChoice::Automatic | MethodChoice::FixedRules
        );
        let wanted = ladder
            && match options.parametrisation {
                Parametrisation::Aimed => true,
                Parametrisation::Automatic => !(self.half_azimuth && self.half_transverse),
                Parametrisation::AzimuthHeight | Parametrisation::PolarAzimuth => false,
            };
        let aim = match x.shape() {
            BodyShape::Solid(e) if wanted && !self.node_check => {
                Some(aimed::aim(e, y, &self.map, options.relative_tolerance))
            }
            _ => None,
        };
        Self { aim, ..self }
    }
}

/// Computes interactions of [`Body`] pairs (see the [module docs](super)); holds the options
/// and the adaptive integrator's workspace. Node tables are cached in the bodies.
#[derive(Debug, Clone, Default)]
pub struct InteractionEngine {
    options: InteractionOptions,
    /// The adaptive integrator's workspace, created on first use and kept.
    adaptive: Option<AdaptiveCubature<10>>,
    /// The nested rule's workspace (line sums), kept.
    nested: NestedCubature<{ nested_rule::COMPONENTS }>,
    /// The nested rule's node geometry, kept ([`nested_rule::GeometryCache`]).
    nested_geometry: nested_rule::GeometryCache,
    /// The aimed rule's unit-sphere grids, kept ([`aimed::GridCache`]).
    aimed_grids: aimed::GridCache,
}

fn check_pose(pose: &Pose, body: Side) -> Result<(), InteractionError> {
    if !pose.position.iter().all(|x| x.is_finite()) {
        return Err(InteractionError::NonFinitePose {
            body,
            what: "position",
        });
    }
    if !pose.rotation.coords.iter().all(|x| x.is_finite()) {
        return Err(InteractionError::NonFinitePose {
            body,
            what: "rotation",
        });
    }
    Ok(())
}

/// Radius of the set where a body's exterior potential, continued inward, is singular: its
/// focal set (0 for spheres and points, the disk itself for a disk).
fn singular_radius(body: &Body) -> Real {
    match body.shape() {
        BodyShape::Point => 0.0,
        BodyShape::Solid(e) => {
            let mut s = [e.x_semi_axis(), e.y_semi_axis(), e.z_semi_axis()];
            s.sort_by(Real::total_cmp);
            ((s[2] - s[0]) * (s[2] + s[0])).sqrt()
        }
        BodyShape::Disk(l) => l.radius(),
        BodyShape::Surface(_) | BodyShape::FieldOnly | BodyShape::Mesh(_) => body.bounding_radius(),
    }
}

impl InteractionEngine {
    /// An engine with these options.
    ///
    /// # Errors
    /// [`InteractionError::InvalidTolerance`] unless the tolerance is in (0, 1);
    /// [`InteractionError::BudgetTooSmall`] for a budget below the adaptive rule's minimum.
    pub fn new(options: InteractionOptions) -> Result<Self, InteractionError> {
        let tolerance = options.relative_tolerance;
        if !(tolerance.is_finite() && tolerance > 0.0 && tolerance < 1.0) {
            return Err(InteractionError::InvalidTolerance { tolerance });
        }
        if options.max_evaluations < MINIMUM_EVALUATION_BUDGET {
            return Err(InteractionError::BudgetTooSmall {
                max_evaluations: options.max_evaluations,
                minimum: MINIMUM_EVALUATION_BUDGET,
            });
        }
        Ok(Self {
            options,
            adaptive: None,
            nested: NestedCubature::new(),
            nested_geometry: nested_rule::GeometryCache::default(),
            aimed_grids: aimed::GridCache::default(),
        })
    }

    /// The options.
    pub fn options(&self) -> &InteractionOptions {
        &self.options
    }

    /// The force only, for integrator stages that need nothing else
    /// ([`Self::evaluate`] with [`Request::Force`]): the fixed rules then sum and certify the
    /// force alone (the torque and energy terms of the node loop are skipped, and only the
    /// force must meet the tolerance). Other methods compute everything and return the force.
    ///
    /// # Errors
    /// As [`Self::interact`].
    pub fn force(
        &mut self,
        a: &Body,
        pose_a: &Pose,
        b: &Body,
        pose_b: &Pose,
    ) -> Result<ForceInteraction, InteractionError> {
        let r = self.compute(a, pose_a, b, pose_b, Request::Force)?;
        Ok(ForceInteraction {
            force_on_a: r.force_on_a,
            force_on_b: r.force_on_b,
            method: r.method,
            integrated_over: r.integrated_over,
            evaluations: r.evaluations,
            error_estimate: r.error_estimate,
        })
    }

    /// Force, torque and energy of A (at `pose_a`) and B (at `pose_b`) ([`Self::evaluate`] with
    /// [`Request::Everything`]).
    ///
    /// # Errors
    /// Non-finite poses, overlapping or touching bodies, bodies with different G, no surface to
    /// integrate over, a tolerance not met within the budget (with the best result attached),
    /// or a result that overflows.
    pub fn interact(
        &mut self,
        a: &Body,
        pose_a: &Pose,
        b: &Body,
        pose_b: &Pose,
    ) -> Result<Interaction, InteractionError> {
        self.compute(a, pose_a, b, pose_b, Request::Everything)
    }

    /// What `request` asks for, of A (at `pose_a`) and B (at `pose_b`): the fixed rules sum
    /// and certify only that; the nested and adaptive rules compute and certify everything.
    /// A quantity not asked for is `None` in the result.
    ///
    /// ```
    /// use surfgrav_potentials::{Pose, Spheroid, Vec3};
    /// use surfgrav_surfaces::interaction::{Body, InteractionEngine, Request};
    ///
    /// let body = || Body::spheroid(Spheroid::new(1.0, 0.25, 1.0).unwrap()).unwrap();
    /// let (a, b) = (body(), body());
    /// // B tilted and lifted: a torque on each body.
    /// let pose_b = Pose::new(Vec3::new(2.4, 0.3, 0.5), Vec3::new(0.3, -0.2, 0.4));
    /// let mut engine = InteractionEngine::default();
    /// let wrench = engine.evaluate(&a, &Pose::identity(), &b, &pose_b, Request::Wrench)?;
    /// let full = engine.interact(&a, &Pose::identity(), &b, &pose_b)?;
    /// let torque = wrench.torque_on_a.expect("a wrench has torques");
    /// assert!((torque - full.torque_on_a).norm() <= 1e-11 * full.potential_energy.abs());
    /// assert!(wrench.potential_energy.is_none() && wrench.error_estimate <= 1e-12);
    /// # Ok::<(), surfgrav_surfaces::interaction::InteractionError>(())
    /// ```
    ///
    /// # Errors
    /// As [`Self::interact`].
    pub fn evaluate(
        &mut self,
        a: &Body,
        pose_a: &Pose,
        b: &Body,
        pose_b: &Pose,
        request: Request,
    ) -> Result<Evaluation, InteractionError> {
        let r = self.compute(a, pose_a, b, pose_b, request)?;
        let torques = request != Request::Force;
        Ok(Evaluation {
            request,
            force_on_a: r.force_on_a,
            force_on_b: r.force_on_b,
            torque_on_a: torques.then_some(r.torque_on_a),
            torque_on_b: torques.then_some(r.torque_on_b),
            potential_energy: (request == Request::Everything).then_some(r.potential_energy),
            method: r.method,
            integrated_over: r.integrated_over,
            evaluations: r.evaluations,
            error_estimate: r.error_estimate,
            level: r.level,
        })
    }

    fn compute(
        &mut self,
        a: &Body,
        pose_a: &Pose,
        b: &Body,
        pose_b: &Pose,
        request: Request,
    ) -> Result<Interaction, InteractionError> {
        check_pose(pose_a, Side::A)?;
        check_pose(pose_b, Side::B)?;
        let (ga, gb) = (
            a.potential().gravitational_constant(),
            b.potential().gravitational_constant(),
        );
        if ga != gb {
            return Err(InteractionError::GravitationalConstantMismatch { a: ga, b: gb });
        }
        if a.as_polyhedron().is_some() || b.as_polyhedron().is_some() {
            // Meshes have their own rules, contact test and choice of surface.
            return super::mesh_pair::interact(
                &self.options,
                request == Request::Force,
                a,
                pose_a,
                b,
                pose_b,
            );
        }
        let separation = (pose_b.position - pose_a.position).norm();
        let exact = contact(a, pose_a, b, pose_b);
        match exact {
            Contact::Overlapping => return Err(InteractionError::Overlap { separation }),
            Contact::Touching => return Err(InteractionError::Touching { separation }),
            Contact::Separated | Contact::Unknown => {}
        }
        if self.options.method == MethodChoice::Automatic {
            if a.is_spherically_symmetric() || b.is_spherically_symmetric() {
                if exact == Contact::Unknown {
                    check_point_formula(a, pose_a, b, pose_b, separation)?;
                }
                return analytic_point(a, pose_a, b, pose_b);
            }
            if let Some(result) = analytic_disk_pair(a, pose_a, b, pose_b)? {
                return Ok(result);
            }
        }
        let unknown = exact == Contact::Unknown;
        let (placement, x, pose_x, y, pose_y) =
            self.choose_surface(a, pose_a, b, pose_b, unknown)?;
        if placement.node_check {
            check_centroids(x, pose_x, y, pose_y, separation)?;
        }
        let budget = self.options.max_evaluations;
        match self.options.method {
            MethodChoice::Adaptive => self.adaptive(x, y, &placement, budget),
            MethodChoice::Nested => self.nested(x, y, &placement),
            MethodChoice::FixedLevel(transverse) => {
                self.single_level(x, y, &placement, transverse, request)
            }
            MethodChoice::FixedRules => self.ladder(x, y, &placement, request),
            MethodChoice::Automatic => match self.ladder(x, y, &placement, request) {
                // The fallback: the ladder ran out of levels (not of budget, not into
                // rounding); the adaptive rule gets the rest of the budget and the better
                // result is kept. (Measured, the ladder is cheaper in every case tried, even
                // 0.003 from a disk's rim, so this is a safety net.)
                Err(InteractionError::ToleranceNotMet { best, .. })
                    if best.level == Some(MAX_TRANSVERSE)
                        && budget - best.evaluations >= MINIMUM_EVALUATION_BUDGET =>
                {
                    match self.adaptive(x, y, &placement, budget - best.evaluations) {
                        Ok(mut r) => {
                            r.evaluations += best.evaluations;
                            Ok(r)
                        }
                        Err(InteractionError::ToleranceNotMet { best: other, .. })
                            if other.error_estimate < best.error_estimate =>
                        {
                            let mut other = *other;
                            other.evaluations += best.evaluations;
                            Err(not_met(self.options.relative_tolerance, other))
                        }
                        _ => Err(not_met(self.options.relative_tolerance, *best)),
                    }
                }
                other => other,
            },
        }
    }

    /// The integration surface: the one forced by the options, the only one there is, or the
    /// one with the lower predicted cost ([`Self::predicted_cost`]); ties go to A.
    #[allow(clippy::type_complexity)]
    fn choose_surface<'b>(
        &self,
        a: &'b Body,
        pose_a: &'b Pose,
        b: &'b Body,
        pose_b: &'b Pose,
        unknown: bool,
    ) -> Result<(Placement, &'b Body, &'b Pose, &'b Body, &'b Pose), InteractionError> {
        let over_a = |engine: &Self| -> Result<_, InteractionError> {
            Ok((
                engine.place(Side::A, a, pose_a, b, pose_b, unknown)?,
                a,
                pose_a,
                b,
                pose_b,
            ))
        };
        let over_b = |engine: &Self| -> Result<_, InteractionError> {
            Ok((
                engine.place(Side::B, b, pose_b, a, pose_a, unknown)?,
                b,
                pose_b,
                a,
                pose_a,
            ))
        };
        let forced = match self.options.surface {
            SurfaceChoice::A => Some(Side::A),
            SurfaceChoice::B => Some(Side::B),
            SurfaceChoice::Automatic => None,
        };
        if let Some(side) = forced {
            let body = if side == Side::A { a } else { b };
            if !body.has_surface() {
                return Err(InteractionError::NoSurface {
                    reason: "the body chosen to integrate over has no surface",
                });
            }
            return if side == Side::A {
                over_a(self)
            } else {
                over_b(self)
            };
        }
        match (a.has_surface(), b.has_surface()) {
            (false, false) => Err(InteractionError::NoSurface {
                reason: "neither body has a surface (give one a shape)",
            }),
            (true, false) => over_a(self),
            (false, true) => over_b(self),
            (true, true) => {
                let candidate_a = over_a(self)?;
                let candidate_b = over_b(self)?;
                let cost_a = self.predicted_cost(&candidate_a.0, b);
                let cost_b = self.predicted_cost(&candidate_b.0, a);
                Ok(if cost_b < cost_a * (1.0 - 1e-9) {
                    candidate_b
                } else {
                    candidate_a
                })
            }
        }
    }

    /// Predicted cost of integrating over X in Y's field: the predicted table size
    /// ($\kappa N^2$ from [`Self::start_transverse`]'s model, halved for each mirror symmetry)
    /// times the relative cost of one evaluation of Y's field (measured: a spheroid 1, a
    /// triaxial ellipsoid 3, a disk 3.5, a sphere or point 0.2). The model captures what the
    /// measurements show: integrate over the body that is small and far from the other's
    /// singular set (its focal set), seen at a high elevation, with a cheap field to evaluate.
    fn predicted_cost(&self, placement: &Placement, y: &Body) -> Real {
        let field_cost = match &y.field {
            SourceField::PointMass(_) | SourceField::Sphere(_) => 0.2,
            SourceField::Spheroid(_) | SourceField::Custom(_) => 1.0,
            SourceField::Ellipsoid(_) => 3.0,
            SourceField::Disk(_) => 3.5,
        };
        if let Some(aim) = &placement.aim {
            // Near a disk's rim (a singular curve running past the pole) the aimed rule
            // converges far more slowly than its point model predicts: measured on the
            // random-pose set (`pose_benchmark`, seed 12, gaps 0.05 to 1), the spheroid or
            // ellipsoid beside a disk took 1.3 to 8 times the time of the disk's own lamina
            // rule in five cases of six.
            let rim = if matches!(y.field, SourceField::Disk(_)) && aim.cluster > 0 {
                AIMED_DISK_PENALTY
            } else {
                1.0
            };
            return aimed::grid_key(aim.start, aim).size() as Real * field_cost * rim;
        }
        let t = Real::from(self.start_transverse(placement));
        let kappa = TRANSVERSE_RATIO[usize::from(placement.ratio)];
        let mut nodes = t * t / kappa;
        if placement.half_azimuth {
            nodes *= 0.5;
        }
        if placement.half_transverse {
            nodes *= 0.5;
        }
        nodes * field_cost
    }

    fn place(
        &self,
        side: Side,
        x: &Body,
        pose_x: &Pose,
        y: &Body,
        pose_y: &Pose,
        unknown_shape: bool,
    ) -> Result<Placement, InteractionError> {
        let relative = pose_x
            .rotation
            .inverse_transform_vector(&(pose_y.position - pose_x.position));
        let axisymmetric = x.is_axisymmetric_surface();
        // Turn an axisymmetric surface about its axis so that Y lies in its x–z plane, x > 0.
        let turn = if axisymmetric && (relative.x != 0.0 || relative.y != 0.0) {
            relative.y.atan2(relative.x)
        } else {
            0.0
        };
        let rotation = pose_x.rotation * UnitQuaternion::from_axis_angle(&Vec3::z_axis(), turn);
        let q = rotation.inverse_transform_vector(&(pose_y.position - pose_x.position));
        let integration_pose = Pose {
            position: pose_x.position,
            rotation,
        };
        let map = FrameMap::between(&integration_pose, pose_y)?;
        let distance = q.norm();
        let symmetric_tables = matches!(x.shape(), BodyShape::Solid(_) | BodyShape::Disk(_));
        let use_symmetry = self.options.exploit_symmetry && symmetric_tables;
        let mirror = |axis: usize| {
            let normal = map.rotation.column(axis).into_owned();
            q[axis].abs() <= ALIGNMENT * distance && y.symmetry.mirrors(&normal)
        };
        let half_azimuth = use_symmetry && mirror(1);
        let half_transverse = use_symmetry && matches!(x.shape(), BodyShape::Solid(_)) && mirror(2);
        let gap_ratio =
            ((distance - x.bounding_radius() - singular_radius(y)) / x.bounding_radius()).max(1e-3);
        let sin_elevation = if distance > 0.0 { q.z / distance } else { 1.0 };
        let clustering = if self.options.cluster_azimuth && axisymmetric {
            // Measured best strength for a body in the equatorial plane, faded out with the
            // elevation of the other body above it (see the module docs).
            let cos2 = 1.0 - sin_elevation * sin_elevation;
            let eps = 1.0 - cos2 * 0.5 / (1.0 + gap_ratio);
            nearest_clustering(eps)
        } else {
            0
        };
        let kappa =
            TransverseRatio::for_geometry(x.shape(), self.options.parametrisation, sin_elevation);
        let ratio = TransverseRatio::index(kappa);
        let bounding_overlap = distance <= x.bounding_radius() + y.bounding_radius();
        Ok(Placement {
            side,
            rotation,
            position_x: pose_x.position,
            position_y: pose_y.position,
            map,
            half_transverse,
            half_azimuth,
            clustering,
            ratio,
            clustered: clustering > 0,
            sin_elevation,
            gap_ratio,
            node_check: unknown_shape && bounding_overlap,
            far: distance > FAR_FIELD_RATIO * x.bounding_radius()
                || distance > CANCELLATION_RATIO * cancellation_radius(x),
            aim: None,
        }
        .aimed(x, y, self.options))
    }

    /// The first transverse count of the ladder, predicted from the gap ratio $g$, the
    /// elevation β and the tolerance τ so that it usually meets the tolerance, erring low (one
    /// level too low costs less than one too high). Measured azimuth counts for $10^{-12}$
    /// (founding paper's pair, equatorial plane): $N \approx 21\\,g^{-0.2}$ clustered,
    /// $26\\,g^{-0.36}$ uniform; fewer out of the plane; proportional to $\log(1/\tau)$.
    fn start_transverse(&self, placement: &Placement) -> u16 {
        let digits = -self.options.relative_tolerance.log10();
        let g = placement.gap_ratio;
        let azimuth = if placement.clustered {
            21.0 * g.powf(-0.2)
        } else {
            26.0 * g.powf(-0.36)
        };
        let plane = (1.0 - 0.7 * placement.sin_elevation.abs()).max(0.3);
        let kappa = TRANSVERSE_RATIO[usize::from(placement.ratio)];
        let t = kappa * azimuth * plane * digits / 12.0;
        (t.round() as u16).clamp(2, MAX_TRANSVERSE)
    }

    /// Growth factor of the ladder for the tolerance (module docs of [`super::rules`]).
    fn growth(&self) -> Real {
        let digits = -self.options.relative_tolerance.log10();
        (1.0 + 1.0 / digits.max(1.0)).max(1.08)
    }

    fn table_key(&self, p: &Placement, transverse: u16) -> TableKey {
        TableKey {
            parametrisation: match self.options.parametrisation {
                Parametrisation::Aimed | Parametrisation::Automatic => {
                    Parametrisation::AzimuthHeight
                }
                other => other,
            },
            transverse,
            ratio: p.ratio,
            clustering: p.clustering,
            half_transverse: p.half_transverse,
            half_azimuth: p.half_azimuth,
        }
    }

    fn single_level(
        &mut self,
        x: &Body,
        y: &Body,
        p: &Placement,
        transverse: u16,
        request: Request,
    ) -> Result<Interaction, InteractionError> {
        let transverse = transverse.clamp(1, MAX_TRANSVERSE);
        let table = x.table(self.table_key(p, transverse))?;
        if table.len() > self.options.max_evaluations {
            return Err(InteractionError::BudgetTooSmall {
                max_evaluations: self.options.max_evaluations,
                minimum: table.len(),
            });
        }
        if p.node_check {
            check_nodes(&table, y, &p.map)?;
        }
        let method = match p.side {
            Side::A => Method::SurfaceOverA,
            Side::B => Method::SurfaceOverB,
        };
        evaluate_table(x, y, &table, p, request).finish(
            method,
            Some(p.side),
            table.len(),
            Real::INFINITY,
            Some(transverse),
        )
    }

    fn ladder(
        &mut self,
        x: &Body,
        y: &Body,
        p: &Placement,
        request: Request,
    ) -> Result<Interaction, InteractionError> {
        if let (Some(aim), BodyShape::Solid(e)) = (p.aim, x.shape()) {
            return self.aimed_ladder(e, &aim, x, y, p, request);
        }
        let key = |transverse: u16| self.table_key(p, transverse);
        run_ladder(
            &self.ladder_settings(),
            p,
            self.start_transverse(p),
            |level| table_size(x.shape(), &key(level)),
            |level| {
                let table = x.table(key(level))?;
                if p.node_check {
                    check_nodes(&table, y, &p.map)?;
                }
                Ok((evaluate_table(x, y, &table, p, request), table.len()))
            },
        )
    }

    fn ladder_settings(&self) -> LadderSettings {
        LadderSettings {
            tolerance: self.options.relative_tolerance,
            max_evaluations: self.options.max_evaluations,
            growth: self.growth(),
            jump: false,
            single_step: false,
        }
    }

    /// The ladder of the aimed rule ([`super::aimed`]) over the ellipsoid `e` (X's surface).
    fn aimed_ladder(
        &mut self,
        e: &crate::EllipsoidSurface,
        aim: &aimed::Aim,
        x: &Body,
        y: &Body,
        p: &Placement,
        request: Request,
    ) -> Result<Interaction, InteractionError> {
        // The aimed nodes have no mirror symmetry.
        let p = &Placement {
            half_azimuth: false,
            half_transverse: false,
            ..*p
        };
        let start = aim.start;
        // The product rule (Gauss–Legendre in cos θ over the whole range, no split halves)
        // gains two degrees per node: a step of one node suffices.
        let settings = LadderSettings {
            jump: true,
            single_step: aim.cluster == 0,
            ..self.ladder_settings()
        };
        let grids = &mut self.aimed_grids;
        run_ladder(
            &settings,
            p,
            start,
            |level| aimed::grid_key(level, aim).size(),
            |level| {
                let grid = grids.get(aimed::grid_key(level, aim))?;
                let sums = match (p.far, request == Request::Force) {
                    (true, true) => with_field!(&y.field, |f| aimed::aimed_sums::<_, true, false>(
                        e, &grid, aim, f, &p.map
                    )),
                    (false, true) => with_field!(
                        &y.field,
                        |f| aimed::aimed_sums::<_, false, false>(e, &grid, aim, f, &p.map)
                    ),
                    (true, false) => with_field!(&y.field, |f| aimed::aimed_sums::<_, true, true>(
                        e, &grid, aim, f, &p.map
                    )),
                    (false, false) => with_field!(
                        &y.field,
                        |f| aimed::aimed_sums::<_, false, true>(e, &grid, aim, f, &p.map)
                    ),
                };
                let mut values = solid_values(sums, x.density, p);
                values.request = request;
                Ok((values, grid.len()))
            },
        )
    }

    /// The nested doubling rule over an ellipsoid X (other surfaces, and bodies of unknown
    /// shape whose nodes must be checked, go to the ladder).
    fn nested(
        &mut self,
        x: &Body,
        y: &Body,
        p: &Placement,
    ) -> Result<Interaction, InteractionError> {
        let BodyShape::Solid(e) = x.shape() else {
            return self.ladder(x, y, p, Request::Everything);
        };
        if p.node_check {
            return self.ladder(x, y, p, Request::Everything);
        }
        let tolerance = self.options.relative_tolerance;
        let method = match p.side {
            Side::A => Method::SurfaceOverA,
            Side::B => Method::SurfaceOverB,
        };
        // The start grid's coarser levels are the ladder's predicted sufficient grid.
        let (azimuth_base, height_base) = self.nested_bases(p);
        let set = nested_rule::rule_set(azimuth_base, p.clustering, p.half_azimuth, height_base)?;
        let axes = [e.x_semi_axis(), e.y_semi_axis(), e.z_semi_axis()];
        let mirror = !p.half_transverse;
        let density = x.density;
        let values_of = |v: &[Real; nested_rule::COMPONENTS]| {
            solid_values(solid_sums_from(v, p.far), density, p)
        };
        let start = NestedLevels {
            periodic: 2,
            across: 2,
        };
        let budget = self.options.max_evaluations;
        let far_geometric = Self::far_nested(p);
        let workspace = &mut self.nested;
        let geometry = self.nested_geometry.get(
            azimuth_base,
            p.clustering,
            p.half_azimuth,
            height_base,
            axes,
        );
        let (estimate, values) = with_field!(&y.field, |f| {
            let reference = f.potential(&p.map.apply(&Vec3::zeros()));
            workspace.integrate_converted(
                &set.rule,
                start,
                tolerance,
                budget,
                |k, start, ends: &[usize], outs: &mut [[Real; nested_rule::COMPONENTS]]| {
                    let end = ends.last().copied().unwrap_or(start);
                    let (nodes, fields) = geometry.line(&set, axes, k, start..end);
                    if p.far {
                        ellipsoid_line::<_, true>(
                            nodes, start, ends, mirror, f, &p.map, reference, outs, fields,
                        )
                    } else {
                        ellipsoid_line::<_, false>(
                            nodes, start, ends, mirror, f, &p.map, reference, outs, fields,
                        )
                    }
                },
                values_of,
                |_, _, v: &Values, coarse: &Values| {
                    let change = v
                        .relative_change(coarse)
                        .max(v.form_discrepancy(v.torque_on_a.norm()));
                    // Levels that agree to rounding: refining cannot lower the estimate.
                    if change <= v.rounding {
                        0.0
                    } else {
                        change
                    }
                },
                |coarser, change| {
                    if far_geometric {
                        geometric_estimate(coarser, change, NESTED_GEOMETRIC_EXPONENT)
                    } else {
                        rate_estimate(coarser, change)
                    }
                },
            )
        })?;
        let error = estimate
            .error_estimate
            .max(values.rounding)
            .max(values.form_discrepancy(values.torque_on_a.norm()));
        let result = values.finish(method, Some(p.side), estimate.evaluations, error, None)?;
        if estimate.converged && error <= tolerance {
            Ok(result)
        } else {
            Err(not_met(tolerance, result))
        }
    }

    /// Azimuth and height bases of the nested rule's start grid, level (2, 2): it holds about
    /// [`NESTED_AZIMUTH_SCALE`] times the ladder's predicted azimuth count and
    /// [`NESTED_HEIGHT_SCALE`] times its transverse count, at least 11 heights per half (fewer
    /// make the rate estimate rest on 1- and 3-node levels, which stay pre-asymptotic); far
    /// away ([`NESTED_GEOMETRIC_GAP`]) the height base halved (at least 2), for the geometric
    /// estimate.
    fn nested_bases(&self, p: &Placement) -> (usize, usize) {
        let t = self.start_transverse(p);
        let kappa = TRANSVERSE_RATIO[usize::from(p.ratio)];
        let n = azimuth_count(t, kappa) as Real;
        let azimuth = 2 * round_base(((NESTED_AZIMUTH_SCALE * n / 8.0).ceil() as usize).max(1));
        let height =
            round_base(((NESTED_HEIGHT_SCALE * Real::from(t) + 1.0) / 4.0).round() as usize).max(3);
        if Self::far_nested(p) {
            // One level coarser in height: the geometric estimate certifies from coarser
            // levels. Halving the azimuth base too saves 1.4 % of the evaluations over the
            // 2016 far-field cases of `tests/interaction_estimates.rs` (203,060 against
            // 205,952) but often costs a second iteration: the founding paper's pair at
            // separation 30 takes the same 63 nodes in 11.4 µs instead of 9.1 µs.
            return (azimuth, (height / 2).max(2));
        }
        (azimuth, height)
    }

    /// Whether the nested rule uses the geometric estimate ([`NESTED_GEOMETRIC_GAP`]).
    fn far_nested(p: &Placement) -> bool {
        p.gap_ratio >= NESTED_GEOMETRIC_GAP
    }

    /// The adaptive cubature, asked for a quarter of the tolerance on the largest component
    /// (the energy's scale); if the estimate in the engine's norms still exceeds the tolerance
    /// (a force that cancels far away), asked again for less, at most twice, as long as the
    /// estimate keeps falling (it stops at the integrator's rounding floor).
    fn adaptive(
        &mut self,
        x: &Body,
        y: &Body,
        p: &Placement,
        budget: usize,
    ) -> Result<Interaction, InteractionError> {
        let tolerance = self.options.relative_tolerance;
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
            let integrator = match &mut self.adaptive {
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

/// What a ladder of levels needs from the engine's options.
struct LadderSettings {
    tolerance: Real,
    max_evaluations: usize,
    growth: Real,
    /// From the third level on, jump to the level the observed rate of convergence predicts
    /// (at most 1.5 times the current one) instead of the next of the ladder. The aimed rule
    /// only: on the fixed tables a disk pair at gap 0.05 (`pose_benchmark`, seed 12, four per
    /// pair, case disk-disk #3) then certified 2.6e-13 with a true error of 5.8e-13 (the
    /// split Gauss–Legendre halves stall from one level to the next, so the change after a
    /// jump can understate the jumped level's error); without it, 3.6e-13 and 3.2e-14.
    jump: bool,
    /// Steps of one node where the ladder would step two (see `aimed_ladder`).
    single_step: bool,
}

/// A ladder of levels from `start` (a level named by its transverse count): `size(level)` is
/// a level's cost in evaluations, `evaluate(level)` its values and cost. Levels grow until two
/// successive ones agree to the tolerance (see the module docs for the estimate).
fn run_ladder(
    settings: &LadderSettings,
    p: &Placement,
    start: u16,
    size: impl Fn(u16) -> usize,
    mut evaluate: impl FnMut(u16) -> Result<(Values, usize), InteractionError>,
) -> Result<Interaction, InteractionError> {
    let tolerance = settings.tolerance;
    let method = match p.side {
        Side::A => Method::SurfaceOverA,
        Side::B => Method::SurfaceOverB,
    };
    let growth = settings.growth;
    let mut level = start;
    // With a small budget, start low enough for two levels to fit (a reported best result
    // with its estimate is worth more than no result).
    while level > 2 {
        let pair = size(level) + size(next_transverse(level, growth));
        if pair <= settings.max_evaluations {
            break;
        }
        level = ((Real::from(level) / growth).floor() as u16)
            .min(level - 1)
            .max(2);
    }
    let mut previous: Option<Values> = None;
    let mut previous_change: Option<Real> = None;
    let mut previous_level = level;
    let mut jumped = false;
    let mut previous_force_change: Option<Real> = None;
    let mut evaluations = 0usize;
    let mut best: Option<Interaction> = None;
    loop {
        let cost = size(level);
        if evaluations + cost > settings.max_evaluations {
            return match best {
                Some(best) => Err(not_met(tolerance, best)),
                None => Err(InteractionError::BudgetTooSmall {
                    max_evaluations: settings.max_evaluations,
                    minimum: evaluations + cost,
                }),
            };
        }
        let (values, cost) = evaluate(level)?;
        evaluations += cost;
        let force_change_before = previous_force_change;
        previous_force_change = previous.map(|coarse| values.force_change(&coarse));
        if let Some(coarse) = previous {
            let change = values.relative_change(&coarse);
            // From the third level on (the start prediction was too low: a harder regime,
            // near contact or far from the equator), convergence in t can be uneven:
            // Gauss–Legendre on the split halves gives errors 4.0e-11 at t = 28 and
            // 3.0e-11 at t = 32 for a close prolate–oblate pair, and the fine level's
            // error reached 1.2 times the last change (3.65e-14 against 3.05e-14). There the
            // estimate is twice the change, or the tail of a geometric series with the
            // observed ratio ρ of the last two changes, change·ρ/(1 − ρ), if larger.
            let slow = previous_change.map_or(0.0, |before: Real| {
                let ratio = if before > 0.0 { change / before } else { 1.0 };
                let ratio = ratio.min(0.99);
                (2.0 * change).max(change * ratio / (1.0 - ratio))
            });
            previous_change = Some(change);
            let estimate = change
                .max(slow)
                .max(values.form_discrepancy(values.torque_on_a.norm()))
                .max(values.rounding);
            let result = values.finish(method, Some(p.side), evaluations, estimate, Some(level))?;
            if estimate <= tolerance {
                return Ok(result);
            }
            if values.relative_change(&coarse) <= values.rounding {
                // The levels agree to rounding: refining cannot lower the estimate.
                return Err(not_met(tolerance, result));
            }
            best = Some(result);
        }
        if level >= MAX_TRANSVERSE {
            return match best {
                Some(best) => Err(not_met(tolerance, best)),
                None => Err(InteractionError::NonFiniteResult {
                    what: "no resolution level could be evaluated",
                }),
            };
        }
        let mut next = if settings.single_step {
            (level + 1).max((growth * Real::from(level)).ceil() as u16)
        } else {
            next_transverse(level, growth)
        };
        let mut jump = false;
        if let (true, false, Some(before), Some(change)) = (
            settings.jump,
            jumped,
            force_change_before,
            previous_force_change,
        ) {
            // Errors falling like exp(−r t): the rate from the last two changes of the force
            // (each the error of its coarser level; the force alone, so that a force-only
            // evaluation takes the same levels and stops no later), and the level whose
            // error would be half the tolerance; the level after it then certifies. Never
            // two jumps in a row: the change after a jump measures the level before it.
            let from = Real::from(previous_level);
            let rate = (before / change).ln() / (Real::from(level) - from);
            if rate.is_finite() && rate > 0.0 {
                let needed = from + (2.0 * change / tolerance).ln() / rate;
                let capped = needed.min(1.5 * Real::from(level)).ceil();
                if capped > Real::from(next) {
                    next = capped as u16;
                    jump = true;
                }
            }
        }
        jumped = jump;
        previous_level = level;
        previous = Some(values);
        level = next.min(MAX_TRANSVERSE);
    }
}

fn not_met(tolerance: Real, best: Interaction) -> InteractionError {
    InteractionError::ToleranceNotMet {
        tolerance,
        error_estimate: best.error_estimate,
        evaluations: best.evaluations,
        best: Box::new(best),
    }
}

fn nearest_clustering(eps: Real) -> u8 {
    let mut best = 0usize;
    for (i, &c) in CLUSTERING.iter().enumerate() {
        if (c - eps).abs() < (CLUSTERING[best] - eps).abs() {
            best = i;
        }
    }
    best as u8
}

/// World-frame values from integrals over X in its integration frame: force and torque on X.
fn assemble(
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
fn solid_values(mut s: SolidSums, density: Real, p: &Placement) -> Values {
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

/// Runs the monomorphised loop for Y's field kind over X's table (dispatch once per table).
fn evaluate_table(
    x: &Body,
    y: &Body,
    table: &NodeTable,
    p: &Placement,
    request: Request,
) -> Values {
    let force_only = request == Request::Force;
    match table {
        NodeTable::Solid(t) => {
            let sums = match (p.far, force_only) {
                (true, true) => {
                    with_field!(&y.field, |f| solid_table_sums::<_, true, false>(
                        t, f, &p.map
                    ))
                }
                (false, true) => {
                    with_field!(&y.field, |f| solid_table_sums::<_, false, false>(
                        t, f, &p.map
                    ))
                }
                (true, false) => {
                    with_field!(&y.field, |f| solid_table_sums::<_, true, true>(
                        t, f, &p.map
                    ))
                }
                (false, false) => {
                    with_field!(&y.field, |f| solid_table_sums::<_, false, true>(
                        t, f, &p.map
                    ))
                }
            };
            let mut values = solid_values(sums, x.density, p);
            values.request = request;
            values
        }
        NodeTable::Lamina(t) => {
            let mut s = with_field!(&y.field, |f| lamina_sums(t, f, &p.map));
            if p.half_azimuth {
                s = symmetrise_lamina(&s, 1);
            }
            let r = s.integrals(x.density, &t.normal(), table.len());
            let mut values = assemble(
                p,
                &r.force,
                &r.torque,
                &r.torque_area_form,
                r.potential_energy,
            );
            let sigma = x.density;
            values.rounding = relative_from_absolute(
                &values,
                ROUNDING_PER_TERM * sigma * s.force_magnitude,
                ROUNDING_PER_TERM * sigma * s.moment_magnitude,
                ROUNDING_PER_TERM * values.potential_energy.abs(),
                (p.position_y - p.position_x).norm(),
            );
            values
        }
    }
}

/// The length $R$ for which the potential form's terms exceed the force $\mathbf F =
/// -\rho\oint\Phi\\,\mathrm d\mathbf S$ by about distance$/R$ (see [`FAR_FIELD_RATIO`]): the
/// ratio is $|\Phi|\\,\mathrm{area}/(|\nabla\Phi|\\,\mathrm{volume}) \approx d\\,A/V$, and for an
/// ellipsoid $A/V \approx 1/a + 1/b + 1/c$ (exact for a sphere, $3/R$; 102 against the exact
/// 150 for a = b = 1, c = 0.01), so $R = 3/(1/a + 1/b + 1/c)$, which a flat body makes small.
/// Other shapes: the bounding radius.
fn cancellation_radius(x: &Body) -> Real {
    match x.shape() {
        BodyShape::Solid(e) => {
            let inverse = 1.0 / e.x_semi_axis() + 1.0 / e.y_semi_axis() + 1.0 / e.z_semi_axis();
            (3.0 / inverse).min(x.bounding_radius())
        }
        _ => x.bounding_radius(),
    }
}

fn symmetrise_solid(s: &SolidSums, axis: usize) -> SolidSums {
    s.symmetrised(axis)
}

fn symmetrise_lamina(s: &LaminaSums, axis: usize) -> LaminaSums {
    s.plus(&s.mirrored(axis))
}

/// Checks every node of X's table against Y's region (for a body of unknown shape).
fn check_nodes(table: &NodeTable, y: &Body, map: &FrameMap) -> Result<(), InteractionError> {
    let field = y.potential();
    let separation = map.offset.norm();
    let check = |points: &[Vec3]| -> Result<(), InteractionError> {
        for r in points {
            match field.region(&map.apply(r)) {
                Region::Outside => {}
                Region::OnSurface => return Err(InteractionError::Touching { separation }),
                Region::Inside => return Err(InteractionError::Overlap { separation }),
            }
        }
        Ok(())
    };
    match table {
        NodeTable::Solid(t) => check(t.points()),
        NodeTable::Lamina(t) => {
            check(t.area_points())?;
            check(t.rim_points())
        }
    }
}

/// Neither centroid inside the other body (for bodies of unknown shape), by each body's region
/// test and, for X's surface, the solid angle it subtends at Y's centroid.
fn check_centroids(
    x: &Body,
    pose_x: &Pose,
    y: &Body,
    pose_y: &Pose,
    separation: Real,
) -> Result<(), InteractionError> {
    if y.potential().region(&pose_y.to_body(&pose_x.position)) != Region::Outside
        || x.potential().region(&pose_x.to_body(&pose_y.position)) != Region::Outside
    {
        return Err(InteractionError::Overlap { separation });
    }
    if let BodyShape::Surface(_) = x.shape() {
        let q = pose_x.to_body(&pose_y.position);
        let table = x.table(TableKey {
            parametrisation: Parametrisation::AzimuthHeight,
            transverse: 40,
            ratio: 4,
            clustering: 0,
            half_transverse: false,
            half_azimuth: false,
        })?;
        if let NodeTable::Solid(t) = table {
            let solid_angle = t.integrate_flux(|r| {
                let d = r - q;
                d / d.norm().powi(3)
            });
            if solid_angle.abs() > std::f64::consts::TAU {
                return Err(InteractionError::Overlap { separation });
            }
        }
    }
    Ok(())
}

/// Before the point formula with a body O of unknown shape: S's centre, and the nodes of a
/// sphere's surface when the bounding spheres meet, must lie outside O.
fn check_point_formula(
    a: &Body,
    pose_a: &Pose,
    b: &Body,
    pose_b: &Pose,
    separation: Real,
) -> Result<(), InteractionError> {
    let (s, pose_s, o, pose_o) = if a.is_spherically_symmetric() {
        (a, pose_a, b, pose_b)
    } else {
        (b, pose_b, a, pose_a)
    };
    let region_error = |region: Region| match region {
        Region::Outside => Ok(()),
        Region::OnSurface => Err(InteractionError::Touching { separation }),
        Region::Inside => Err(InteractionError::Overlap { separation }),
    };
    region_error(o.potential().region(&pose_o.to_body(&pose_s.position)))?;
    if s.has_surface() && separation <= s.bounding_radius() + o.bounding_radius() {
        let table = s.table(TableKey {
            parametrisation: Parametrisation::AzimuthHeight,
            transverse: 24,
            ratio: 4,
            clustering: 0,
            half_transverse: false,
            half_azimuth: false,
        })?;
        let map = FrameMap::between(pose_s, pose_o)?;
        check_nodes(&table, o, &map)?;
    }
    Ok(())
}

/// The point formula: S (a point or a sphere) feels the other body's field at its centre.
fn analytic_point(
    a: &Body,
    pose_a: &Pose,
    b: &Body,
    pose_b: &Pose,
) -> Result<Interaction, InteractionError> {
    let (s, pose_s, o, pose_o, s_is_a) = if a.is_spherically_symmetric() {
        (a, pose_a, b, pose_b, true)
    } else {
        (b, pose_b, a, pose_a, false)
    };
    let field = o.potential().field_in_world(pose_o, &pose_s.position);
    let m = s.mass();
    let f_s = field.acceleration * m;
    let energy = field.potential * m;
    let m_o = -(pose_s.position - pose_o.position).cross(&f_s);
    let values = if s_is_a {
        Values {
            force_on_a: f_s,
            torque_on_a: Vec3::zeros(),
            torque_on_b: m_o,
            potential_energy: energy,
            torque_form_gap: 0.0,
            rounding: 0.0,
            request: Request::Everything,
        }
    } else {
        Values {
            force_on_a: -f_s,
            torque_on_a: m_o,
            torque_on_b: Vec3::zeros(),
            potential_energy: energy,
            torque_form_gap: 0.0,
            rounding: 0.0,
            request: Request::Everything,
        }
    };
    values.finish(
        Method::AnalyticPoint,
        None,
        1,
        ANALYTIC_RELATIVE_ERROR,
        None,
    )
}

/// Conway's closed form when both bodies are disks in one plane; `None` otherwise.
fn analytic_disk_pair(
    a: &Body,
    pose_a: &Pose,
    b: &Body,
    pose_b: &Pose,
) -> Result<Option<Interaction>, InteractionError> {
    let (BodyShape::Disk(la), BodyShape::Disk(lb)) = (a.shape(), b.shape()) else {
        return Ok(None);
    };
    let na = pose_a.rotation * Vec3::z();
    let nb = pose_b.rotation * Vec3::z();
    let d = pose_b.position - pose_a.position;
    let distance = d.norm();
    if na.cross(&nb).norm() > ALIGNMENT || na.dot(&d).abs() > ALIGNMENT * distance {
        return Ok(None);
    }
    let g = a.potential().gravitational_constant();
    let disk = |radius: Real, body: &Body| -> Result<UniformDisk, InteractionError> {
        UniformDisk::new(radius, body.mass())
            .and_then(|disk| disk.with_gravitational_constant(g))
            .map_err(|_| InteractionError::NonFiniteResult {
                what: "a uniform disk for the closed form",
            })
    };
    let pair = CoplanarDiskPair::new(&disk(la.radius(), a)?, &disk(lb.radius(), b)?)?;
    let interaction = pair.interaction(distance)?;
    let force_on_b = d * (interaction.radial_force / distance);
    let values = Values {
        force_on_a: -force_on_b,
        torque_on_a: Vec3::zeros(),
        torque_on_b: Vec3::zeros(),
        potential_energy: interaction.potential_energy,
        torque_form_gap: 0.0,
        rounding: 0.0,
        request: Request::Everything,
    };
    values
        .finish(
            Method::AnalyticDiskPair,
            None,
            1,
            ANALYTIC_RELATIVE_ERROR,
            None,
        )
        .map(Some)
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
            let phi = field.potential;
            let a = p.map.back(&field.acceleration);
            let half_x2 = 0.5 * r.norm_squared();
            let flux = w * ((phi - reference) * distance);
            let moment = r.cross(&w) * (phi - reference);
            let gradient = w.cross(&a) * half_x2;
            out[0] = flux.x;
            out[1] = flux.y;
            out[2] = flux.z;
            out[3] = moment.x;
            out[4] = moment.y;
            out[5] = moment.z;
            out[6] = gradient.x;
            out[7] = gradient.y;
            out[8] = gradient.z;
            out[9] = (r * phi + a * half_x2).dot(&w);
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

fn relative_from_absolute(
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
            let (sin, cos) = phi.sin_cos();
            let r = Vec3::new(s * cos, s * sin, 0.0);
            let field = f.field(&p.map.apply(&r));
            let a = p.map.back(&field.acceleration);
            let an = a.z;
            let rim = Vec3::new(radius * cos, radius * sin, 0.0);
            let rim_phi = f.potential(&p.map.apply(&rim)) - reference;
            out[0] = s * field.potential;
            out[1] = s * an * distance;
            out[2] = s * an * r.y;
            out[3] = -s * an * r.x;
            out[4] = rim_phi * cos * distance;
            out[5] = rim_phi * sin * distance;
            out[6] = s * (r.x * a.y - r.y * a.x);
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
