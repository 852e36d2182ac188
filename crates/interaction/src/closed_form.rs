//! Closed-form pairs, tried before any surface integral: the point formula (a point mass or a
//! homogeneous sphere with any body outside it) and Conway's coplanar disk pair (see the
//! [module docs](super), methods 1 and 2).

use super::assembly::Values;
use super::body::{Body, BodyShape, ALIGNMENT};
use super::error::InteractionError;
use super::kernel::FrameMap;
use super::options::{Interaction, Method, Request};
use super::overlap::{check_nodes, Contact};
use super::rules::{Parametrisation, TableKey};
use surfgrav_potentials::{CoplanarDiskPair, Pose, PoseExt, Region, UniformDisk};
use surfgrav_surfaces::{Real, Vec3};

/// The relative accuracy reported for the closed forms (the potentials crate's documented
/// accuracy of the acceleration, which dominates).
pub const ANALYTIC_RELATIVE_ERROR: Real = 1e-13;

/// Two bodies placed in the world, with what every pair rule needs computed once.
#[derive(Debug, Clone, Copy)]
pub struct Pair<'a> {
    /// Body A.
    pub a: &'a Body,
    /// A's pose.
    pub pose_a: &'a Pose,
    /// Body B.
    pub b: &'a Body,
    /// B's pose.
    pub pose_b: &'a Pose,
    /// Distance between the centroids.
    pub separation: Real,
    /// Whether the engine's exact contact test decided that the bodies are apart (both shapes
    /// known); `false`: a shape is unknown, and a rule must check what its formula assumes
    /// (the point formula checks the centre and, near contact, the sphere's nodes).
    pub separated: bool,
}

/// A closed form for some pairs of bodies, tried before any surface integral (parry's query
/// dispatcher is the model): the engine asks its rules in order and takes the first answer;
/// [`InteractionEngine::with_pair_rule`](super::InteractionEngine::with_pair_rule) puts a
/// user's rule in front of the built-in ones ([`PointFormula`], [`CoplanarDisks`]). A pair no
/// rule answers goes to the surface integral, and a pair without a surface to integrate over
/// is the typed error [`InteractionError::NoSurface`].
///
/// Rules see the bodies through [`Body::typed`] and the [`Potential`](surfgrav_potentials::Potential)
/// trait, so a rule for a user's kind needs no change to the engine. A rule's result should
/// name its method ([`Method::ClosedForm`] for a user's) and state its accuracy in
/// `error_estimate`.
pub trait PairRule: std::fmt::Debug + Send + Sync {
    /// The interaction of the pair, `Ok(None)` when this rule does not apply to it.
    ///
    /// # Errors
    /// What the rule finds wrong with a pair it applies to (bodies that overlap, a result
    /// that is not finite).
    fn interact(&self, pair: &Pair<'_>) -> Result<Option<Interaction>, InteractionError>;
}

/// The point formula: a point mass, a sphere, or any body whose field reports
/// [`Symmetry::Spherical`](surfgrav_potentials::Symmetry::Spherical), with any body outside it
/// (the [module docs](super), method 1).
#[derive(Debug, Clone, Copy, Default)]
pub struct PointFormula;

impl PairRule for PointFormula {
    fn interact(&self, pair: &Pair<'_>) -> Result<Option<Interaction>, InteractionError> {
        let Pair {
            a,
            pose_a,
            b,
            pose_b,
            separation,
            separated,
        } = *pair;
        if !(a.is_spherically_symmetric() || b.is_spherically_symmetric()) {
            return Ok(None);
        }
        if !separated {
            check_point_formula(a, pose_a, b, pose_b, separation)?;
        }
        analytic_point(a, pose_a, b, pose_b).map(Some)
    }
}

/// Conway's closed form for two uniform disks in one plane (the [module docs](super),
/// method 2).
#[derive(Debug, Clone, Copy, Default)]
pub struct CoplanarDisks;

impl PairRule for CoplanarDisks {
    fn interact(&self, pair: &Pair<'_>) -> Result<Option<Interaction>, InteractionError> {
        analytic_disk_pair(pair.a, pair.pose_a, pair.b, pair.pose_b)
    }
}

/// The built-in rules, in the order they are tried.
pub(crate) fn built_in_rules() -> Vec<std::sync::Arc<dyn PairRule>> {
    vec![
        std::sync::Arc::new(PointFormula),
        std::sync::Arc::new(CoplanarDisks),
    ]
}

/// The first answer of `rules` for this pair, `None` when none applies.
pub(crate) fn closed_form(
    rules: &[std::sync::Arc<dyn PairRule>],
    a: &Body,
    pose_a: &Pose,
    b: &Body,
    pose_b: &Pose,
    exact: Contact,
    separation: Real,
) -> Result<Option<Interaction>, InteractionError> {
    let pair = Pair {
        a,
        pose_a,
        b,
        pose_b,
        separation,
        separated: exact != Contact::Unknown,
    };
    for rule in rules {
        if let Some(result) = rule.interact(&pair)? {
            return Ok(Some(result));
        }
    }
    Ok(None)
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
    region_error(o.potential().region(&pose_o.to_body(&pose_s.position())))?;
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
    let field = o.potential().field_in_world(pose_o, &pose_s.position());
    let m = s.mass();
    let f_s = field.acceleration * m;
    let energy = field.potential * m;
    let m_o = -(pose_s.position() - pose_o.position()).cross(&f_s);
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
    let d = pose_b.position() - pose_a.position();
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
