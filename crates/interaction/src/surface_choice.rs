//! The surface choice: where the integrated body X and the source Y are in X's integration
//! frame ([`Placement`]: the turn about an axis of symmetry, the mirror symmetries, the gap to
//! Y's singular set, the clustering), and which body to integrate over, by the predicted cost
//! of each choice ([`predicted_cost`]; see the [module docs](super), "Which surface").

use super::aimed;
use super::body::{mirrors, Body, BodyShape, ALIGNMENT};
use super::error::{InteractionError, Side};
use super::kernel::FrameMap;
use super::options::{InteractionOptions, MethodChoice, SurfaceChoice};
use super::rules::{
    Parametrisation, TransverseRatio, CLUSTERING, MAX_TRANSVERSE, TRANSVERSE_RATIO,
};
use super::strategy::ladder::far_lamina_start;
use nalgebra::UnitQuaternion;
use surfgrav_potentials::{Pose, PoseExt};
use surfgrav_surfaces::{Real, Vec3};

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

/// Where the integrated body X and the source body Y are, in X's integration frame.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Placement {
    pub(crate) side: Side,
    /// X's integration frame → world (X's body frame, possibly turned about its axis).
    pub(crate) rotation: UnitQuaternion<Real>,
    pub(crate) position_x: Vec3,
    pub(crate) position_y: Vec3,
    pub(crate) map: FrameMap,
    pub(crate) half_transverse: bool,
    pub(crate) half_azimuth: bool,
    pub(crate) clustering: u8,
    /// Index of the transverse-to-azimuth ratio κ.
    pub(crate) ratio: u8,
    /// Whether the azimuth nodes are clustered.
    pub(crate) clustered: bool,
    /// Sine of Y's elevation above X's equatorial plane.
    pub(crate) sin_elevation: Real,
    /// Gap between X's bounding sphere and Y's singular set (over a disk, its nearest point,
    /// [`singular_distance`]; over a solid, the ball of Y's singular radius), over X's
    /// bounding radius.
    pub(crate) gap_ratio: Real,
    /// Whether the integration nodes must be checked against Y's region (shape unknown).
    pub(crate) node_check: bool,
    /// Whether the centroids are more than [`FAR_FIELD_RATIO`] of X's bounding radii apart.
    pub(crate) far: bool,
    /// The aimed rule's pole and clustering, where the fixed rules use it over X
    /// ([`Parametrisation::Aimed`], or [`Parametrisation::Automatic`] without both mirror
    /// symmetries).
    pub(crate) aim: Option<aimed::Aim>,
    /// The aimed lamina rule's plan, where X is a disk and the aimed rule is wanted.
    pub(crate) lamina_aim: Option<aimed::lamina::LaminaAim>,
    /// Whether every aimed rule of this side loses to the other side's predicted cost
    /// ([`Rival`]): then this side is not chosen, and it has no aim.
    pub(crate) outcompeted: bool,
    /// The first transverse count the fixed lamina table needs for the angular singularity
    /// of Y on X's rim, where X is a disk without the aimed lamina rule (otherwise 0; see
    /// `far_lamina_start` in `strategy/ladder.rs`): the ladder starts there and the surface
    /// choice predicts from it.
    pub(crate) lamina_start: u16,
    /// Whether Y is a disk that the aimed lamina rule integrates over (a disk's side is placed
    /// first, [`likely_first`]): only then does the aimed rule over X beside its rim carry
    /// [`AIMED_DISK_PENALTY`].
    pub(crate) beside_lamina: bool,
}

impl Placement {
    /// This placement with the aimed rule's aim where the fixed rules use it over X: an
    /// ellipsoid whose nodes need no check, with [`Parametrisation::Aimed`], or with
    /// [`Parametrisation::Automatic`] unless the pose has both mirror symmetries (then the
    /// azimuth–height table, clustered toward the other body and quartered, is cheaper).
    fn aimed(self, x: &Body, y: &Body, options: InteractionOptions, rival: Rival) -> Self {
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
        let mut outcompeted = false;
        let aim = match x.shape() {
            BodyShape::Solid(e) if wanted && !self.node_check => {
                let beside = self.beside_lamina;
                let loses =
                    |cluster: u8, size: usize| rival.beats(aimed_cost(y, cluster, size, beside));
                let aim = aimed::aim(e, y, &self.map, options.relative_tolerance, &loses);
                outcompeted = aim.is_none();
                aim
            }
            _ => None,
        };
        let lamina_aim = match x.shape() {
            BodyShape::Disk(l) if wanted && !self.node_check => {
                aimed::lamina::lamina_aim(l, y, &self.map, options.relative_tolerance)
            }
            _ => None,
        };
        Self {
            aim,
            lamina_aim,
            outcompeted,
            ..self
        }
    }

    /// This placement with [`Placement::lamina_start`] set, where X is a disk that the fixed
    /// lamina table integrates over.
    fn with_lamina_start(self, x: &Body, y: &Body, options: &InteractionOptions) -> Self {
        let lamina_start = match x.shape() {
            BodyShape::Disk(_) if self.lamina_aim.is_none() => {
                far_lamina_start(x, y, &self, options)
            }
            _ => 0,
        };
        Self {
            lamina_start,
            ..self
        }
    }
}

/// The other candidate surface's predicted cost, where it was placed first
/// ([`choose_surface`]): a rule of this side that would not be chosen over it need not be
/// planned.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Rival {
    /// No other candidate (or not placed yet).
    None,
    /// This is side B, A costs this: B is chosen only below it.
    A(Real),
    /// This is side A, B costs this: A is chosen unless B is below it.
    B(Real),
}

impl Rival {
    /// Whether the rival is chosen over this side at a predicted cost of `cost` (the same
    /// comparison as [`choose_surface`]'s; it then holds for every larger cost too).
    fn beats(self, cost: Real) -> bool {
        match self {
            Rival::None => false,
            // Not below (NaN included: then A is chosen, as in `choose_surface`).
            Rival::A(a) => cost.partial_cmp(&(a * CHOICE_MARGIN)) != Some(std::cmp::Ordering::Less),
            Rival::B(b) => b < cost * CHOICE_MARGIN,
        }
    }
}

/// B is integrated over only where its predicted cost is below this factor times A's (ties
/// go to A).
const CHOICE_MARGIN: Real = 1.0 - 1e-9;
/// The integration surface: the one forced by the options, the only one there is, or the
/// one with the lower predicted cost ([`predicted_cost`]); ties go to A.
#[allow(clippy::type_complexity)]
pub(crate) fn choose_surface<'b>(
    options: &InteractionOptions,
    a: &'b Body,
    pose_a: &'b Pose,
    b: &'b Body,
    pose_b: &'b Pose,
    unknown: bool,
) -> Result<(Placement, &'b Body, &'b Pose, &'b Body, &'b Pose), InteractionError> {
    let over_a = |rival: Rival, beside_lamina: bool| -> Result<_, InteractionError> {
        Ok((
            place(
                options,
                Side::A,
                a,
                pose_a,
                b,
                pose_b,
                unknown,
                rival,
                beside_lamina,
            )?,
            a,
            pose_a,
            b,
            pose_b,
        ))
    };
    let over_b = |rival: Rival, beside_lamina: bool| -> Result<_, InteractionError> {
        Ok((
            place(
                options,
                Side::B,
                b,
                pose_b,
                a,
                pose_a,
                unknown,
                rival,
                beside_lamina,
            )?,
            b,
            pose_b,
            a,
            pose_a,
        ))
    };
    let forced = match options.surface {
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
            over_a(Rival::None, false)
        } else {
            over_b(Rival::None, false)
        };
    }
    match (a.has_surface(), b.has_surface()) {
        (false, false) => Err(InteractionError::NoSurface {
            reason: "neither body has a surface (give one a shape)",
        }),
        (true, false) => over_a(Rival::None, false),
        (false, true) => over_b(Rival::None, false),
        (true, true) => {
            // The side likely to win first (a disk's lamina rule, or the cheaper source
            // field), so that the other's planning stops at the rules that cannot beat it.
            // The choice is the same in either order (`Rival`).
            // The second side is placed knowing whether the first is a disk with an aimed
            // lamina plan (`Placement::beside_lamina`).
            let first_b = likely_first(b, a) && !likely_first(a, b);
            let (candidate_a, candidate_b) = if first_b {
                let candidate_b = over_b(Rival::None, false)?;
                let cost_b = predicted_cost(options, &candidate_b.0, a);
                let lamina = candidate_b.0.lamina_aim.is_some();
                (over_a(Rival::B(cost_b), lamina)?, candidate_b)
            } else {
                let candidate_a = over_a(Rival::None, false)?;
                let cost_a = predicted_cost(options, &candidate_a.0, b);
                let lamina = candidate_a.0.lamina_aim.is_some();
                (candidate_a, over_b(Rival::A(cost_a), lamina)?)
            };
            let cost_a = predicted_cost(options, &candidate_a.0, b);
            let cost_b = predicted_cost(options, &candidate_b.0, a);
            Ok(if cost_b < cost_a * CHOICE_MARGIN {
                candidate_b
            } else {
                candidate_a
            })
        }
    }
}

/// Whether integrating over X in Y's field is worth placing before the other way round: X
/// a disk (its lamina rule usually wins) or Y's field the cheaper one to evaluate.
fn likely_first(x: &Body, y: &Body) -> bool {
    let disk = |b: &Body| matches!(b.shape(), BodyShape::Disk(_));
    // A disk beside a body of another kind always goes first, whatever the fields cost:
    // the other side's aimed rule is then placed knowing whether the disk has an aimed
    // lamina plan (`Placement::beside_lamina`).
    disk(x) || (!disk(y) && y.potential().field_cost() < x.potential().field_cost())
}

/// Predicted cost of integrating over X in Y's field: the predicted table size
/// ($\kappa N^2$ from [`start_transverse`]'s model, halved for each mirror symmetry)
/// times the relative cost of one evaluation of Y's field (measured: a spheroid 1, a
/// triaxial ellipsoid 3, a disk 3.5, a sphere or point 0.2). The model captures what the
/// measurements show: integrate over the body that is small and far from the other's
/// singular set (its focal set), seen at a high elevation, with a cheap field to evaluate.
pub(crate) fn predicted_cost(
    options: &InteractionOptions,
    placement: &Placement,
    y: &Body,
) -> Real {
    if placement.outcompeted {
        return Real::INFINITY;
    }
    let field_cost = y.potential().field_cost();
    if let Some(aim) = &placement.lamina_aim {
        return aim.size(aim.start) as Real * field_cost;
    }
    if let Some(aim) = &placement.aim {
        return aimed_cost(
            y,
            aim.cluster,
            aimed::grid_key(aim.start, aim).size(),
            placement.beside_lamina,
        );
    }
    let t = Real::from(start_transverse(options, placement).max(placement.lamina_start));
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

/// The predicted cost of the aimed rule over X with clustering index `cluster` and `size`
/// nodes at its first level, in Y's field ([`predicted_cost`]).
fn aimed_cost(y: &Body, cluster: u8, size: usize, beside_lamina: bool) -> Real {
    // Near a disk's rim (a singular curve running past the pole) the aimed rule
    // converges far more slowly than its point model predicts: measured on the
    // random-pose set (`pose_benchmark`, seed 12, gaps 0.05 to 1), the spheroid or
    // ellipsoid beside a disk took 1.3 to 8 times the time of the disk's own lamina
    // rule in five cases of six.
    // Where the disk has only its fixed table (far from X), the comparison behind the penalty
    // does not hold: `pose_benchmark` seed 40, a spheroid 1 from a disk, took 1,656
    // evaluations over the spheroid and 15,570 over the disk's table, which the penalty chose.
    let rim = if matches!(y.shape(), BodyShape::Disk(_)) && cluster > 0 && beside_lamina {
        AIMED_DISK_PENALTY
    } else {
        1.0
    };
    size as Real * y.potential().field_cost() * rim
}

/// X's placement in Y's field, with the aimed rule's plan where it is used; `rival`: the
/// other side's predicted cost, where it was placed first.
#[allow(clippy::too_many_arguments)]
pub(crate) fn place(
    options: &InteractionOptions,
    side: Side,
    x: &Body,
    pose_x: &Pose,
    y: &Body,
    pose_y: &Pose,
    unknown_shape: bool,
    rival: Rival,
    beside_lamina: bool,
) -> Result<Placement, InteractionError> {
    let relative = pose_x
        .rotation
        .inverse_transform_vector(&(pose_y.position() - pose_x.position()));
    let axisymmetric = x.is_axisymmetric_surface();
    // Turn an axisymmetric surface about its axis so that Y lies in its x–z plane, x > 0.
    let turn = if axisymmetric && (relative.x != 0.0 || relative.y != 0.0) {
        relative.y.atan2(relative.x)
    } else {
        0.0
    };
    let rotation = pose_x.rotation * UnitQuaternion::from_axis_angle(&Vec3::z_axis(), turn);
    let q = rotation.inverse_transform_vector(&(pose_y.position() - pose_x.position()));
    let integration_pose = Pose::from_position_rotation(pose_x.position(), rotation);
    let map = FrameMap::between(&integration_pose, pose_y)?;
    let distance = q.norm();
    let symmetric_tables = matches!(x.shape(), BodyShape::Solid(_) | BodyShape::Disk(_));
    let use_symmetry = options.exploit_symmetry && symmetric_tables;
    let mirror = |axis: usize| {
        let normal = map.rotation.column(axis).into_owned();
        q[axis].abs() <= ALIGNMENT * distance && mirrors(y.symmetry(), &normal)
    };
    let half_azimuth = use_symmetry && mirror(1);
    let half_transverse = use_symmetry && matches!(x.shape(), BodyShape::Solid(_)) && mirror(2);
    // Over a disk, the distance to Y's singular set itself; over a solid, to the ball of
    // its singular radius: the solids' fixed tables, started lower by the true distance, let
    // an estimate be exceeded (the independent reference of `pose_benchmark` seed 64,
    // spheroid-disk gap 0.05 #2, over the spheroid at 1e-13: 8.8e-14 certified, 2.4e-13 off).
    let to_set = match x.shape() {
        BodyShape::Disk(_) => singular_distance(y, &map),
        _ => None,
    }
    .unwrap_or(distance - y.singular_radius());
    let gap_ratio = ((to_set - x.bounding_radius()) / x.bounding_radius()).max(1e-3);
    let sin_elevation = if distance > 0.0 { q.z / distance } else { 1.0 };
    let clustering = if options.cluster_azimuth && axisymmetric {
        // Measured best strength for a body in the equatorial plane, faded out with the
        // elevation of the other body above it (see the module docs).
        let cos2 = 1.0 - sin_elevation * sin_elevation;
        let eps = 1.0 - cos2 * 0.5 / (1.0 + gap_ratio);
        nearest_clustering(eps)
    } else {
        0
    };
    let kappa = TransverseRatio::for_geometry(x.shape(), options.parametrisation, sin_elevation);
    let ratio = TransverseRatio::index(kappa);
    let bounding_overlap = distance <= x.bounding_radius() + y.bounding_radius();
    Ok(Placement {
        side,
        rotation,
        position_x: pose_x.position(),
        position_y: pose_y.position(),
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
        lamina_aim: None,
        outcompeted: false,
        lamina_start: 0,
        beside_lamina,
    }
    .aimed(x, y, *options, rival)
    .with_lamina_start(x, y, options))
}

/// The first transverse count of the ladder, predicted from the gap ratio $g$, the
/// elevation β and the tolerance τ so that it usually meets the tolerance, erring low (one
/// level too low costs less than one too high). Measured azimuth counts for $10^{-12}$
/// (founding paper's pair, equatorial plane): $N \approx 21\\,g^{-0.2}$ clustered,
/// $26\\,g^{-0.36}$ uniform; fewer out of the plane; proportional to $\log(1/\tau)$.
pub(crate) fn start_transverse(options: &InteractionOptions, placement: &Placement) -> u16 {
    let digits = -options.relative_tolerance.log10();
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

/// The distance from X's centroid (`map`'s origin) to the nearest point of Y's singular set
/// where the set is known (a built-in field: the focal ellipse, segment or circle,
/// [`aimed::singular_set`]); `None` otherwise (the caller takes the ball of
/// [`Body::singular_radius`] about Y's centroid). A body beside a prolate spheroid's equator
/// is far from the focal segment along its axis, which the ball of the segment's half-length
/// puts at contact: `pose_benchmark` seed 56, a disk 0.094 from a prolate spheroid of semi-axes
/// 1 and 1.96, started the disk's fixed table at level 71 and took 15,924 evaluations
/// (estimate 6.8e-15).
fn singular_distance(y: &Body, map: &FrameMap) -> Option<Real> {
    use surfgrav_potentials::TypedPotential;
    let known = !matches!(
        y.typed(),
        TypedPotential::Custom | TypedPotential::Polyhedron(_)
    ) && matches!(
        y.shape(),
        BodyShape::Point | BodyShape::Solid(_) | BodyShape::Disk(_)
    );
    let centre = map.offset;
    known.then(|| (centre - aimed::singular_set(y).nearest(&centre)).norm())
}

pub(crate) fn nearest_clustering(eps: Real) -> u8 {
    let mut best = 0usize;
    for (i, &c) in CLUSTERING.iter().enumerate() {
        if (c - eps).abs() < (CLUSTERING[best] - eps).abs() {
            best = i;
        }
    }
    best as u8
}

/// The length $R$ for which the potential form's terms exceed the force $\mathbf F =
/// -\rho\oint\Phi\\,\mathrm d\mathbf S$ by about distance$/R$ (see [`FAR_FIELD_RATIO`]): the
/// ratio is $|\Phi|\\,\mathrm{area}/(|\nabla\Phi|\\,\mathrm{volume}) \approx d\\,A/V$, and for an
/// ellipsoid $A/V \approx 1/a + 1/b + 1/c$ (exact for a sphere, $3/R$; 102 against the exact
/// 150 for a = b = 1, c = 0.01), so $R = 3/(1/a + 1/b + 1/c)$, which a flat body makes small.
/// Other shapes: the bounding radius.
pub(crate) fn cancellation_radius(x: &Body) -> Real {
    match x.shape() {
        BodyShape::Solid(e) => {
            let inverse = 1.0 / e.x_semi_axis() + 1.0 / e.y_semi_axis() + 1.0 / e.z_semi_axis();
            (3.0 / inverse).min(x.bounding_radius())
        }
        _ => x.bounding_radius(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::work_precision::pose_set;

    /// Placing the second side against the first one's cost ([`Rival`]) only skips rules that
    /// cannot be chosen: on the random-pose set (seeds 12 and 13, every pair of kinds, gaps
    /// 0.05 to 5) and with the bodies swapped, the chosen side, its aim (clustering and first
    /// level) and its predicted cost are those of placing both sides in full.
    #[test]
    fn a_rival_changes_no_choice() {
        let options = InteractionOptions::default();
        let mut outcompeted = 0;
        for seed in [12, 13] {
            for case in pose_set(seed, &[0.05, 0.2, 1.0, 5.0], 2) {
                for (a, pose_a, b, pose_b) in [
                    (&case.a, &case.pose_a, &case.b, &case.pose_b),
                    (&case.b, &case.pose_b, &case.a, &case.pose_a),
                ] {
                    // Each side in full, knowing whether the other is a disk with an aimed
                    // lamina plan (which does not depend on this side).
                    let lamina = |side: Side, x: &Body, px: &Pose, y: &Body, py: &Pose| {
                        place(&options, side, x, px, y, py, false, Rival::None, false)
                            .unwrap()
                            .lamina_aim
                            .is_some()
                    };
                    let lamina_a = lamina(Side::A, a, pose_a, b, pose_b);
                    let lamina_b = lamina(Side::B, b, pose_b, a, pose_a);
                    let full_a = place(
                        &options,
                        Side::A,
                        a,
                        pose_a,
                        b,
                        pose_b,
                        false,
                        Rival::None,
                        lamina_b,
                    )
                    .unwrap();
                    let full_b = place(
                        &options,
                        Side::B,
                        b,
                        pose_b,
                        a,
                        pose_a,
                        false,
                        Rival::None,
                        lamina_a,
                    )
                    .unwrap();
                    let (cost_a, cost_b) = (
                        predicted_cost(&options, &full_a, b),
                        predicted_cost(&options, &full_b, a),
                    );
                    let expected = if cost_b < cost_a * CHOICE_MARGIN {
                        (full_b, cost_b)
                    } else {
                        (full_a, cost_a)
                    };
                    let (chosen, x, ..) =
                        choose_surface(&options, a, pose_a, b, pose_b, false).unwrap();
                    let y = if std::ptr::eq(x, a) { b } else { a };
                    let label = &case.label;
                    assert_eq!(chosen.side, expected.0.side, "{label}");
                    assert_eq!(predicted_cost(&options, &chosen, y), expected.1, "{label}");
                    let key = |p: &Placement| p.aim.map(|aim| (aim.cluster, aim.start));
                    assert_eq!(key(&chosen), key(&expected.0), "{label}");
                    assert_eq!(chosen.lamina_aim, expected.0.lamina_aim, "{label}");
                    // How often the rival spared a whole plan.
                    for rival in [Rival::A(cost_a), Rival::B(cost_b)] {
                        let side = if matches!(rival, Rival::A(_)) {
                            place(
                                &options,
                                Side::B,
                                b,
                                pose_b,
                                a,
                                pose_a,
                                false,
                                rival,
                                lamina_a,
                            )
                        } else {
                            place(
                                &options,
                                Side::A,
                                a,
                                pose_a,
                                b,
                                pose_b,
                                false,
                                rival,
                                lamina_b,
                            )
                        };
                        outcompeted += usize::from(side.unwrap().outcompeted);
                    }
                }
            }
        }
        // The test would not see the pruning at work without sides that lose outright.
        assert!(outcompeted > 0);
    }
}
