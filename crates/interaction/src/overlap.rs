//! Overlap and contact tests.
//!
//! For bodies of known convex shape (points, ellipsoids, disks) the test is exact: the
//! Perram–Wertheim contact function (J. Comput. Phys. 58, 1985)
//!
//! $$ F = \max\_{0\le\lambda\le1}\ \lambda(1-\lambda)\\,\mathbf d^{\mathsf T}\big[(1-\lambda)\\,\mathsf A + \lambda\\,\mathsf B\big]^{-1}\mathbf d, $$
//!
//! with $\mathbf d$ the centroid separation and $\mathsf A = R\\,\mathrm{diag}(a^2, b^2, c^2)\\,R^{\mathsf T}$
//! the (world-frame) shape matrix of each ellipsoid, is the square of the factor by which both
//! bodies must be scaled about their centroids to touch: $F > 1$ apart, $F = 1$ touching,
//! $F < 1$ overlapping (for two spheres $F = d^2/(R_A + R_B)^2$). The function of $\lambda$ is
//! concave, so a golden-section search finds its maximum; any $\lambda$ with $F(\lambda) > 1$
//! already proves separation, which is tried first. Points and disks are degenerate
//! ellipsoids; the pairs whose matrix pencil is singular (point–point, point–anything, parallel
//! disks) are decided directly.
//!
//! Bodies whose shape is not known ([`BodyShape::FieldOnly`], [`BodyShape::Surface`]) are
//! tested by the engine on the integration nodes themselves (every node must lie outside the
//! other body, neither centroid inside the other body).

use super::body::{Body, BodyShape, ALIGNMENT};
use super::error::InteractionError;
use super::kernel::FrameMap;
use super::rules::{NodeTable, Parametrisation, TableKey};
use nalgebra::Matrix3;
use surfgrav_potentials::{Pose, PoseExt, Region};
use surfgrav_surfaces::{Real, Vec3};

/// $F$ within this of 1 counts as touching: two rounding errors of a contact function of
/// order 1, i.e. a gap below about $10^{-15}$ of the bodies' size.
pub(crate) const CONTACT_MARGIN: Real = 16.0 * Real::EPSILON;

/// Outcome of the exact test.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Contact {
    Separated,
    Touching,
    Overlapping,
    /// A shape is unknown: the engine must check the integration nodes.
    Unknown,
}

/// The world-frame shape matrix of a body of known convex shape.
fn shape_matrix(body: &Body, pose: &Pose) -> Option<Matrix3<Real>> {
    let diag = match body.shape() {
        BodyShape::Point => Vec3::zeros(),
        BodyShape::Solid(e) => e.semi_axes().component_mul(&e.semi_axes()),
        BodyShape::Disk(l) => Vec3::new(l.radius() * l.radius(), l.radius() * l.radius(), 0.0),
        BodyShape::Surface(_) | BodyShape::FieldOnly | BodyShape::Mesh(_) => return None,
    };
    let r = pose.rotation.to_rotation_matrix();
    Some(r.matrix() * Matrix3::from_diagonal(&diag) * r.matrix().transpose())
}

/// $\lambda(1-\lambda)\\,\mathbf d^{\mathsf T}C^{-1}\mathbf d$, or `None` where $C$ is singular.
fn contact_function(lambda: Real, a: &Matrix3<Real>, b: &Matrix3<Real>, d: &Vec3) -> Option<Real> {
    let c = a * (1.0 - lambda) + b * lambda;
    let u = c.lu().solve(d)?;
    let value = lambda * (1.0 - lambda) * d.dot(&u);
    value.is_finite().then_some(value)
}

fn classify(f: Real) -> Contact {
    if f > 1.0 + CONTACT_MARGIN {
        Contact::Separated
    } else if f >= 1.0 - CONTACT_MARGIN {
        Contact::Touching
    } else {
        Contact::Overlapping
    }
}

fn region_contact(region: Region) -> Contact {
    match region {
        Region::Outside => Contact::Separated,
        Region::OnSurface => Contact::Touching,
        Region::Inside => Contact::Overlapping,
    }
}

/// The exact contact test (see the module docs).
pub(crate) fn contact(a: &Body, pose_a: &Pose, b: &Body, pose_b: &Pose) -> Contact {
    let d = pose_b.position() - pose_a.position();
    let distance = d.norm();
    if distance > a.bounding_radius() + b.bounding_radius() {
        return Contact::Separated;
    }
    let point_a = matches!(a.shape(), BodyShape::Point);
    let point_b = matches!(b.shape(), BodyShape::Point);
    if point_a && point_b {
        return if distance > 0.0 {
            Contact::Separated
        } else {
            Contact::Touching
        };
    }
    // A point against a body: where the point lies in the body (its own exact region test).
    if point_a && !matches!(b.shape(), BodyShape::FieldOnly | BodyShape::Surface(_)) {
        return region_contact(b.potential().region(&pose_b.to_body(&pose_a.position())));
    }
    if point_b && !matches!(a.shape(), BodyShape::FieldOnly | BodyShape::Surface(_)) {
        return region_contact(a.potential().region(&pose_a.to_body(&pose_b.position())));
    }
    let (Some(ma), Some(mb)) = (shape_matrix(a, pose_a), shape_matrix(b, pose_b)) else {
        return Contact::Unknown;
    };
    if let (BodyShape::Disk(da), BodyShape::Disk(db)) = (a.shape(), b.shape()) {
        let na = pose_a.rotation * Vec3::z();
        let nb = pose_b.rotation * Vec3::z();
        if na.cross(&nb).norm() <= ALIGNMENT {
            // Parallel planes: apart unless coplanar; coplanar disks touch at R_A + R_B.
            if na.dot(&d).abs() > ALIGNMENT * distance {
                return Contact::Separated;
            }
            let contact = da.radius() + db.radius();
            let f = (distance / contact) * (distance / contact);
            return classify(f);
        }
    }
    // Guess: λ at the ratio of the bounding radii (exact for two spheres).
    let (ra, rb) = (a.bounding_radius(), b.bounding_radius());
    let guess = if ra + rb > 0.0 { ra / (ra + rb) } else { 0.5 };
    if contact_function(guess, &ma, &mb, &d).is_some_and(|f| f > 1.0 + CONTACT_MARGIN) {
        return Contact::Separated;
    }
    // Golden-section search for the maximum of the concave F(λ) on [0, 1].
    let ratio = 0.5 * (5.0f64.sqrt() - 1.0);
    let (mut lo, mut hi) = (0.0, 1.0);
    let eval = |l: Real| contact_function(l, &ma, &mb, &d).unwrap_or(0.0);
    let mut x1 = hi - ratio * (hi - lo);
    let mut x2 = lo + ratio * (hi - lo);
    let (mut f1, mut f2) = (eval(x1), eval(x2));
    let mut best = f1.max(f2);
    for _ in 0..100 {
        if best > 1.0 + CONTACT_MARGIN {
            return Contact::Separated;
        }
        if f1 < f2 {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + ratio * (hi - lo);
            f2 = eval(x2);
        } else {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - ratio * (hi - lo);
            f1 = eval(x1);
        }
        best = best.max(f1).max(f2);
        // Run to the ends of [0, 1] if need be: for a disk resting face-on, F(λ) = λ and the
        // supremum 1 is only approached as λ → 1.
        if hi - lo < 2.0 * Real::EPSILON {
            break;
        }
    }
    classify(best)
}

/// Checks every node of X's table against Y's region (for a body of unknown shape).
pub(crate) fn check_nodes(
    table: &NodeTable,
    y: &Body,
    map: &FrameMap,
) -> Result<(), InteractionError> {
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
pub(crate) fn check_centroids(
    x: &Body,
    pose_x: &Pose,
    y: &Body,
    pose_y: &Pose,
    separation: Real,
) -> Result<(), InteractionError> {
    if y.potential().region(&pose_y.to_body(&pose_x.position())) != Region::Outside
        || x.potential().region(&pose_x.to_body(&pose_y.position())) != Region::Outside
    {
        return Err(InteractionError::Overlap { separation });
    }
    if let BodyShape::Surface(_) = x.shape() {
        let q = pose_x.to_body(&pose_y.position());
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
