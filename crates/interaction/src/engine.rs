//! The interaction engine: validates a request, tries the closed-form pairs
//! ([`super::closed_form`]), chooses the surface to integrate over
//! ([`super::surface_choice`]) and hands the surface integral to the strategy the options name
//! ([`super::strategy`]); results are assembled in [`super::assembly`].

use super::assembly::not_met;
use super::body::Body;
use super::closed_form::{built_in_rules, closed_form, PairRule};
use super::error::{InteractionError, Side};
use super::options::{
    Evaluation, ForceInteraction, Interaction, InteractionOptions, MethodChoice, Request,
};
use super::overlap::{check_centroids, contact, Contact};
use super::rules::next_transverse;
use super::rules::MAX_TRANSVERSE;
use super::strategy::adaptive::Adaptive;
use super::strategy::aimed_ladder::AimedLadder;
use super::strategy::ladder::{growth, SingleLevel};
use super::strategy::nested_doubling::NestedDoubling;
use super::strategy::{Problem, Strategy};
use super::surface_choice::choose_surface;
use std::sync::Arc;
use surfgrav_potentials::{Pose, PoseExt};
use surfgrav_quadrature::MINIMUM_EVALUATION_BUDGET;

// The constants that were defined here, for the paths that name them.
pub use super::assembly::ROUNDING_PER_TERM;
pub use super::closed_form::ANALYTIC_RELATIVE_ERROR;
pub use super::surface_choice::{CANCELLATION_RATIO, FAR_FIELD_RATIO};

impl Default for InteractionEngine {
    fn default() -> Self {
        Self {
            options: InteractionOptions::default(),
            pair_rules: built_in_rules(),
            ladder: AimedLadder::default(),
            nested: NestedDoubling::default(),
            adaptive: Adaptive::default(),
        }
    }
}

/// Computes interactions of [`Body`] pairs (see the [module docs](super)); holds the options
/// and each strategy's workspace (the adaptive integrator's, the nested rule's line sums and
/// node geometry, the aimed rule's grids). Node tables are cached in the bodies.
#[derive(Debug, Clone)]
pub struct InteractionEngine {
    options: InteractionOptions,
    /// The closed forms, tried in order before any surface integral ([`PairRule`]).
    pair_rules: Vec<Arc<dyn PairRule>>,
    /// The ladder (fixed tables, or the aimed rule's grids where the placement is aimed).
    ladder: AimedLadder,
    /// The nested doubling rule.
    nested: NestedDoubling,
    /// The adaptive rule.
    adaptive: Adaptive,
}

fn check_pose(pose: &Pose, body: Side) -> Result<(), InteractionError> {
    if !pose.position().iter().all(|x| x.is_finite()) {
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
            ..Self::default()
        })
    }

    /// The options.
    pub fn options(&self) -> &InteractionOptions {
        &self.options
    }

    /// The same engine with `rule` tried first, before the other closed forms and the surface
    /// integral (with [`MethodChoice::Automatic`]; the other methods always integrate).
    ///
    /// ```
    /// use surfgrav_potentials::{Pose, PoseExt, Spheroid, TypedPotential, Vec3};
    /// use surfgrav_interaction::{
    ///     Body, Interaction, InteractionEngine, InteractionError, Method, Pair, PairRule,
    /// };
    ///
    /// /// Two spheroids far apart: the point-mass term alone (say a user knows it is enough).
    /// #[derive(Debug)]
    /// struct FarSpheroids;
    ///
    /// impl PairRule for FarSpheroids {
    ///     fn interact(&self, pair: &Pair<'_>) -> Result<Option<Interaction>, InteractionError> {
    ///         let both = matches!(
    ///             (pair.a.typed(), pair.b.typed()),
    ///             (TypedPotential::Spheroid(_), TypedPotential::Spheroid(_))
    ///         );
    ///         if !both || pair.separation < 1e6 {
    ///             return Ok(None);
    ///         }
    ///         let d = pair.pose_b.position() - pair.pose_a.position();
    ///         let gm = pair.a.mass() * pair.b.mass();
    ///         let force_on_a = d * (gm / pair.separation.powi(3));
    ///         Ok(Some(Interaction {
    ///             force_on_a,
    ///             force_on_b: -force_on_a,
    ///             torque_on_a: Vec3::zeros(),
    ///             torque_on_b: Vec3::zeros(),
    ///             potential_energy: -gm / pair.separation,
    ///             method: Method::ClosedForm("far spheroids"),
    ///             integrated_over: None,
    ///             evaluations: 0,
    ///             error_estimate: 1e-12,
    ///             level: None,
    ///         }))
    ///     }
    /// }
    ///
    /// let body = || Body::spheroid(Spheroid::new(1.0, 0.25, 1.0).unwrap()).unwrap();
    /// let mut engine = InteractionEngine::default().with_pair_rule(std::sync::Arc::new(FarSpheroids));
    /// let far = Pose::new(Vec3::new(1e7, 0.0, 0.0), Vec3::zeros());
    /// let near = Pose::new(Vec3::new(3.0, 0.0, 0.0), Vec3::zeros());
    /// assert_eq!(engine.interact(&body(), &Pose::identity(), &body(), &far)?.method.name(), "far spheroids");
    /// assert_eq!(engine.interact(&body(), &Pose::identity(), &body(), &near)?.method, Method::SurfaceOverA);
    /// # Ok::<(), InteractionError>(())
    /// ```
    pub fn with_pair_rule(mut self, rule: Arc<dyn PairRule>) -> Self {
        self.pair_rules.insert(0, rule);
        self
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
    /// use surfgrav_interaction::{Body, InteractionEngine, Request};
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
    /// # Ok::<(), surfgrav_interaction::InteractionError>(())
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
            return super::mesh_pair::interact(&self.options, request, a, pose_a, b, pose_b);
        }
        let separation = (pose_b.position() - pose_a.position()).norm();
        let exact = contact(a, pose_a, b, pose_b);
        match exact {
            Contact::Overlapping => return Err(InteractionError::Overlap { separation }),
            Contact::Touching => return Err(InteractionError::Touching { separation }),
            Contact::Separated | Contact::Unknown => {}
        }
        if self.options.method == MethodChoice::Automatic {
            let rules = &self.pair_rules;
            if let Some(result) = closed_form(rules, a, pose_a, b, pose_b, exact, separation)? {
                return Ok(result);
            }
        }
        let unknown = exact == Contact::Unknown;
        let (placement, x, pose_x, y, pose_y) =
            choose_surface(&self.options, a, pose_a, b, pose_b, unknown)?;
        if placement.node_check {
            check_centroids(x, pose_x, y, pose_y, separation)?;
        }
        let budget = self.options.max_evaluations;
        let problem = Problem {
            x,
            y,
            placement: &placement,
            options: &self.options,
            request,
            budget,
        };
        match self.options.method {
            MethodChoice::Adaptive => self.adaptive.refine(&problem),
            MethodChoice::Nested => self.nested.refine(&problem),
            MethodChoice::FixedLevel(transverse) => SingleLevel { transverse }.refine(&problem),
            MethodChoice::FixedRules => self.ladder.refine(&problem),
            MethodChoice::Automatic => match self.ladder.refine(&problem) {
                // The fallback: the ladder ran out of levels (its last level has no step
                // left below the top; not out of budget, not into rounding); the adaptive
                // rule gets the rest of the budget and the better result is kept. (Measured,
                // the ladder is cheaper in every case tried, even 0.003 from a disk's rim, so
                // this is a safety net; two parallel disks 0.02 apart are one it catches.)
                Err(InteractionError::ToleranceNotMet { best, .. })
                    if best.level.is_some_and(|level| {
                        next_transverse(level, growth(&self.options)) > MAX_TRANSVERSE
                    }) && budget - best.evaluations >= MINIMUM_EVALUATION_BUDGET =>
                {
                    let rest = Problem {
                        budget: budget - best.evaluations,
                        ..problem
                    };
                    match self.adaptive.refine(&rest) {
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
}
