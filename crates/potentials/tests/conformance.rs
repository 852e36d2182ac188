//! One conformance suite, run on every implementor of `Potential` (statrs-style): each check is
//! a law the field must obey whatever the body, so a wrong formula fails here even where no
//! reference value exists.
//!
//! - acceleration = −∇Φ (Richardson-extrapolated central differences);
//! - Laplace's equation outside, Poisson's ∇·a = −4πGρ inside (differences of the acceleration);
//! - Gauss's law: ∮ a·dS = −4πGM on an enclosing sphere;
//! - far field: Φ + GM/r tends to MacCullagh's quadrupole −G(tr I − 3 I_rr)/(2r³), and to
//!   −GM/r to round-off at 1e8 body sizes;
//! - continuity of Φ and a across a solid's surface;
//! - the body's mirror and rotational symmetries.
//!
//! Polyhedra run the same checks: probes are placed along rays through their surface (found
//! by intersecting the ray with the mesh) instead of an ellipsoid, MacCullagh's formula takes
//! the full inertia tensor, and a body without central symmetry is allowed its octupole.

use std::f64::consts::PI;

use nalgebra::Matrix3;
use surfgrav_potentials::tolerance::{FINITE_DIFFERENCE_REL, POLYHEDRON_SYMMETRY_REL};
use surfgrav_potentials::{
    Ellipsoid, LengthUnit, Mesh, PointMass, Polyhedron, Potential, Region, Sphere, Spheroid,
    UniformDisk, Vec3,
};
use surfgrav_quadrature::{GaussLegendre, Rule1D};

/// What the suite needs to know about a body beyond the trait.
struct Case<'a> {
    name: String,
    body: &'a dyn Potential,
    /// Inertia tensor about the centroid in the body axes, for MacCullagh's formula.
    inertia: Matrix3<f64>,
    /// The surface on which probes are placed.
    probe: Probe,
    /// Volume density of a solid (None for laminas and point masses).
    density: Option<f64>,
    /// Rotational symmetry about z.
    axisymmetric: bool,
    /// Mirror symmetry in each coordinate plane, and the relative tolerance of the check
    /// (`None`: no mirror symmetry and, the body lacking central symmetry, an octupole).
    mirror: Option<f64>,
}

/// Where probes go.
enum Probe {
    /// Semi-axes of an ellipsoid (solids: the body itself; the disk: a thin ellipsoid around
    /// the lamina; the point mass: a unit sphere).
    Ellipsoid([f64; 3]),
    /// A closed triangle mesh, star-shaped about the origin along the probe rays.
    Mesh(Vec<[Vec3; 3]>),
}

impl Probe {
    /// The largest distance from the origin to the surface.
    fn size(&self) -> f64 {
        match self {
            Probe::Ellipsoid(axes) => axes.iter().cloned().fold(0.0, f64::max),
            Probe::Mesh(faces) => faces
                .iter()
                .flat_map(|f| f.iter().map(|v| v.norm()))
                .fold(0.0, f64::max),
        }
    }
}

/// Distance along the unit ray `dir` from the origin to the mesh (Möller–Trumbore); the ray
/// must cross it exactly once (star-shaped along this ray).
fn ray_mesh(faces: &[[Vec3; 3]], dir: &Vec3) -> f64 {
    let mut hits = Vec::new();
    for [a, b, c] in faces {
        let (e1, e2) = (b - a, c - a);
        let p = dir.cross(&e2);
        let det = e1.dot(&p);
        if det.abs() < 1e-300 {
            continue;
        }
        let t_vec = -a;
        let u = t_vec.dot(&p) / det;
        let q = t_vec.cross(&e1);
        let v = dir.dot(&q) / det;
        let t = e2.dot(&q) / det;
        if (0.0..=1.0).contains(&u) && v >= 0.0 && u + v <= 1.0 && t > 0.0 {
            hits.push(t);
        }
    }
    hits.sort_by(f64::total_cmp);
    let (first, last) = (hits[0], hits[hits.len() - 1]);
    assert!(
        (last - first) <= 1e-12 * last,
        "the probe mesh is not star-shaped along {dir:?}: crossings {hits:?}"
    );
    first
}

/// Deterministic, well-spread directions (a Fibonacci sphere).
fn directions(n: usize) -> Vec<Vec3> {
    let golden = (1.0 + 5f64.sqrt()) / 2.0;
    (0..n)
        .map(|k| {
            let z = 1.0 - 2.0 * (k as f64 + 0.5) / n as f64;
            let phi = 2.0 * PI * (k as f64 / golden).fract();
            let s = (1.0 - z * z).sqrt();
            Vec3::new(s * phi.cos(), s * phi.sin(), z)
        })
        .collect()
}

/// The point where the ray along `dir` crosses the probe surface, scaled by `factor`.
fn on_ray(probe: &Probe, dir: &Vec3, factor: f64) -> Vec3 {
    let t = match probe {
        Probe::Ellipsoid(semi) => {
            1.0 / ((dir.x / semi[0]).powi(2)
                + (dir.y / semi[1]).powi(2)
                + (dir.z / semi[2]).powi(2))
            .sqrt()
        }
        Probe::Mesh(faces) => ray_mesh(faces, &dir.normalize()) / dir.norm(),
    };
    dir * (t * factor)
}

/// Fourth-order central difference (Richardson on steps h and h/2).
fn richardson<F: Fn(f64) -> f64>(f: F, h: f64) -> f64 {
    let d = |h: f64| (f(h) - f(-h)) / (2.0 * h);
    (4.0 * d(h / 2.0) - d(h)) / 3.0
}

fn gradient_error(case: &Case, r: &Vec3, h: f64) -> Option<String> {
    let a = case.body.acceleration(r);
    let mut fd = Vec3::zeros();
    for i in 0..3 {
        let e = Vec3::ith(i, 1.0);
        fd[i] = -richardson(|t| case.body.potential(&(r + e * t)), h);
    }
    // Cancellation in the difference quotient is ≈ ε|Φ|/h: scale by max(|a|, |Φ|/|r|).
    let scale = a.norm().max(case.body.potential(r).abs() / r.norm());
    let err = (a - fd).norm() / scale;
    (err > FINITE_DIFFERENCE_REL).then(|| {
        format!(
            "{}: a ≠ −∇Φ at {r:?}: a = {a:?}, −∇Φ (FD) = {fd:?}, rel {err:.2e}",
            case.name
        )
    })
}

fn divergence(case: &Case, r: &Vec3, h: f64) -> f64 {
    (0..3)
        .map(|i| {
            let e = Vec3::ith(i, 1.0);
            richardson(|t| case.body.acceleration(&(r + e * t))[i], h)
        })
        .sum()
}

fn run_suite(case: &Case) {
    let mut failures = Vec::new();
    let size = case.probe.size();
    let g = case.body.gravitational_constant();
    let gm = case.body.gravitational_parameter();
    let dirs = directions(40);

    // Gradient and Laplace outside, from 1.05 to 20 times the probe ellipsoid along each ray.
    for dir in &dirs {
        for factor in [1.05, 1.5, 3.0, 20.0] {
            let r = on_ray(&case.probe, dir, factor);
            // Distance to the probe surface along the ray. With h = 1e-3 gap the Richardson
            // truncation is O((h/gap)⁴) ≈ 1e-12 and the cancellation ε|Φ|/h ≤ 5e-11 of |a|.
            let gap = (factor - 1.0) * r.norm() / factor;
            let h = 1e-3 * gap;
            failures.extend(gradient_error(case, &r, h));
            let div = divergence(case, &r, h);
            let scale = case.body.acceleration(&r).norm() / gap;
            if div.abs() > FINITE_DIFFERENCE_REL * scale {
                failures.push(format!(
                    "{}: Laplace fails outside at {r:?}: ∇·a = {div:e} (scale {scale:e})",
                    case.name
                ));
            }
        }
    }

    // Poisson inside a solid: ∇·a = −4πGρ.
    if let Some(rho) = case.density {
        let expected = -4.0 * PI * g * rho;
        for dir in dirs.iter().take(12) {
            for factor in [0.1, 0.5, 0.9] {
                let r = on_ray(&case.probe, dir, factor);
                let h = 1e-3 * (1.0 - factor) * r.norm() / factor;
                if case.body.region(&r) != Region::Inside {
                    failures.push(format!("{}: {r:?} should be inside", case.name));
                }
                failures.extend(gradient_error(case, &r, h));
                let div = divergence(case, &r, h);
                if (div - expected).abs() > FINITE_DIFFERENCE_REL * expected.abs() {
                    failures.push(format!(
                        "{}: Poisson fails inside at {r:?}: ∇·a = {div:e}, −4πGρ = {expected:e}",
                        case.name
                    ));
                }
            }
        }
    }

    // Gauss's law on spheres of 1.5 and 4 times the bounding radius.
    for factor in [1.5, 4.0] {
        let radius = factor * case.body.bounding_radius().max(size);
        let flux = sphere_flux(case.body, radius);
        let expected = -4.0 * PI * gm;
        // 48 × 96 nodes integrate this analytic integrand to ~1e-15; 1e-12 is round-off margin.
        if ((flux - expected) / expected).abs() > 1e-12 {
            failures.push(format!(
                "{}: Gauss's law on radius {radius}: flux {flux:e}, −4πGM {expected:e}",
                case.name
            ));
        }
    }

    // Far field: Φ + GM/r → MacCullagh's quadrupole; Φ and a → Kepler to round-off at 1e8 sizes.
    let trace = case.inertia.trace();
    for dir in &dirs {
        let r = dir * (100.0 * size);
        let rn = r.norm();
        let i_rr = dir.dot(&(case.inertia * dir));
        let quadrupole = -g * (trace - 3.0 * i_rr) / (2.0 * rn.powi(3));
        let excess = case.body.potential(&r) + gm / rn;
        // The next multipole is O((size/r)²) = 1e-4 of the quadrupole's magnitude G tr I / r³
        // (not of its local value, which vanishes where P₂ does); 1e-3 covers it, and
        // 1e-14 GM/r covers the rounding of the sum Φ + GM/r. A body without central symmetry
        // has odd multipoles from the octupole on: |Σ_{n≥3}| ≤ GM/r Σ q^n = GM q³/(r(1 − q)),
        // q = size/r = 0.01 (all mass lies within `size` of the origin).
        let odd = if case.mirror.is_none() {
            let q = size / rn;
            gm * q.powi(3) / (rn * (1.0 - q))
        } else {
            0.0
        };
        let tol = 1e-3 * g * trace / rn.powi(3) + 1e-14 * gm / rn + odd;
        if (excess - quadrupole).abs() > tol {
            failures.push(format!(
                "{}: far field at {r:?}: Φ + GM/r = {excess:e}, MacCullagh {quadrupole:e}",
                case.name
            ));
        }
        let r_far = dir * (1e8 * size);
        let kepler = -gm / r_far.norm();
        let phi_far = case.body.potential(&r_far);
        if ((phi_far - kepler) / kepler).abs() > 1e-14 {
            failures.push(format!(
                "{}: at 1e8 sizes Φ = {phi_far:e}, −GM/r = {kepler:e}",
                case.name
            ));
        }
        let a_far = case.body.acceleration(&r_far);
        let a_kepler = -r_far * (gm / r_far.norm().powi(3));
        if (a_far - a_kepler).norm() > 1e-13 * a_kepler.norm() {
            failures.push(format!(
                "{}: at 1e8 sizes a = {a_far:?}, −GMr/r³ = {a_kepler:?}",
                case.name
            ));
        }
    }

    // Continuity across a solid's surface: 1e-10 inside and outside agree to O(1e-10).
    if case.density.is_some() {
        for dir in &dirs {
            let inside = on_ray(&case.probe, dir, 1.0 - 1e-10);
            let outside = on_ray(&case.probe, dir, 1.0 + 1e-10);
            let (fi, fo) = (case.body.field(&inside), case.body.field(&outside));
            let dphi = ((fi.potential - fo.potential) / fo.potential).abs();
            let da = (fi.acceleration - fo.acceleration).norm() / fo.acceleration.norm();
            if dphi > 1e-9 || da > 1e-8 {
                failures.push(format!(
                    "{}: discontinuous at the surface along {dir:?}: ΔΦ/Φ {dphi:e}, Δa/a {da:e}",
                    case.name
                ));
            }
        }
    }

    // Mirror symmetries under x → −x, y → −y, z → −z, where the body has them. The closed
    // forms are symmetric to a few ulp (4ε in Φ, 8ε in a); a polyhedron sums its faces in an
    // order the mirror permutes, so it is held to its own tolerance.
    for dir in &dirs {
        let r = on_ray(&case.probe, dir, 1.3);
        let f = case.body.field(&r);
        let (tol_phi, tol_a) = match case.mirror {
            Some(t) if t == 4.0 * f64::EPSILON => (t, 2.0 * t),
            Some(t) => (t, t),
            None => (0.0, 0.0),
        };
        for axis in 0..3 {
            if case.mirror.is_none() {
                break;
            }
            let mut m = r;
            m[axis] = -m[axis];
            let fm = case.body.field(&m);
            let mut am = fm.acceleration;
            am[axis] = -am[axis];
            if (fm.potential - f.potential).abs() > tol_phi * f.potential.abs()
                || (am - f.acceleration).norm() > tol_a * f.acceleration.norm()
            {
                failures.push(format!(
                    "{}: mirror symmetry in axis {axis} broken at {r:?}",
                    case.name
                ));
            }
        }
        if case.axisymmetric {
            let rot = nalgebra::Rotation3::from_axis_angle(&Vec3::z_axis(), 0.7);
            let fr = case.body.field(&(rot * r));
            let back = rot.inverse() * fr.acceleration;
            if (fr.potential - f.potential).abs() > 1e-14 * f.potential.abs()
                || (back - f.acceleration).norm() > 1e-13 * f.acceleration.norm()
            {
                failures.push(format!("{}: not axisymmetric at {r:?}", case.name));
            }
        }
    }

    assert!(
        failures.is_empty(),
        "{} conformance failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// ∮ a·n dS over an origin-centred sphere: Gauss–Legendre in cos θ (the field is analytic on the
/// sphere) times the trapezoid rule in φ (periodic).
fn sphere_flux(body: &dyn Potential, radius: f64) -> f64 {
    let rule = GaussLegendre::standard(48).expect("a valid order");
    let n_phi = 96;
    let mut flux = 0.0;
    for (&mu, &w) in rule.nodes().iter().zip(rule.weights()) {
        let s = (1.0 - mu * mu).sqrt();
        for k in 0..n_phi {
            let phi = 2.0 * PI * k as f64 / n_phi as f64;
            let n = Vec3::new(s * phi.cos(), s * phi.sin(), mu);
            flux += w * body.acceleration(&(n * radius)).dot(&n);
        }
    }
    flux * (2.0 * PI / n_phi as f64) * radius * radius
}

fn ellipsoid_inertia(m: f64, [a, b, c]: [f64; 3]) -> Matrix3<f64> {
    Matrix3::from_diagonal(&Vec3::new(
        m * (b * b + c * c) / 5.0,
        m * (a * a + c * c) / 5.0,
        m * (a * a + b * b) / 5.0,
    ))
}

/// Mirror tolerance of the closed forms: 4ε in Φ (and 8ε in a, see `run_suite`).
const CLOSED_FORM_MIRROR: Option<f64> = Some(4.0 * f64::EPSILON);

fn ellipsoid_density(m: f64, axes: [f64; 3]) -> f64 {
    m / (4.0 / 3.0 * PI * axes.iter().product::<f64>())
}

#[test]
fn point_mass_conforms() {
    let body = PointMass::new(2.5)
        .unwrap()
        .with_gravitational_constant(0.7)
        .unwrap();
    run_suite(&Case {
        name: "point mass".into(),
        body: &body,
        inertia: Matrix3::zeros(),
        probe: Probe::Ellipsoid([1.0; 3]),
        density: None,
        axisymmetric: true,
        mirror: CLOSED_FORM_MIRROR,
    });
}

#[test]
fn sphere_conforms() {
    let body = Sphere::new(1.3, 2.0)
        .unwrap()
        .with_gravitational_constant(1.7)
        .unwrap();
    run_suite(&Case {
        name: "sphere".into(),
        body: &body,
        inertia: ellipsoid_inertia(2.0, [1.3; 3]),
        probe: Probe::Ellipsoid([1.3; 3]),
        density: Some(ellipsoid_density(2.0, [1.3; 3])),
        axisymmetric: true,
        mirror: CLOSED_FORM_MIRROR,
    });
}

#[test]
fn spheroids_conform() {
    let shapes = [
        (1.0, 0.25),
        (0.25, 1.0),
        (1.0, 0.99),
        (1.0, 1.0 - 1e-9),
        (1.0, 1.0),
        (1.0, 1.0 + 1e-9),
        (2.0, 0.02),
        (0.05, 3.0),
    ];
    for (a, c) in shapes {
        let m = 1.5;
        let body = Spheroid::new(a, c, m).unwrap();
        run_suite(&Case {
            name: format!("spheroid a={a} c={c}"),
            body: &body,
            inertia: ellipsoid_inertia(m, [a, a, c]),
            probe: Probe::Ellipsoid([a, a, c]),
            density: Some(ellipsoid_density(m, [a, a, c])),
            axisymmetric: true,
            mirror: CLOSED_FORM_MIRROR,
        });
    }
}

#[test]
fn ellipsoids_conform() {
    let shapes = [
        [3.0, 2.0, 1.0],
        [1.0, 2.0, 3.0],
        [2.0, 1.0, 3.0],
        [1.0, 0.5, 0.01],
        [1.0, 1.0 + 1e-7, 1.0 - 1e-7],
    ];
    for axes in shapes {
        let m = 0.8;
        let body = Ellipsoid::new(axes[0], axes[1], axes[2], m).unwrap();
        run_suite(&Case {
            name: format!("ellipsoid {axes:?}"),
            body: &body,
            inertia: ellipsoid_inertia(m, axes),
            probe: Probe::Ellipsoid(axes),
            density: Some(ellipsoid_density(m, axes)),
            axisymmetric: false,
            mirror: CLOSED_FORM_MIRROR,
        });
    }
}

#[test]
fn uniform_disk_conforms() {
    let (r, m) = (1.2, 0.9);
    let body = UniformDisk::new(r, m).unwrap();
    run_suite(&Case {
        name: "uniform disk".into(),
        body: &body,
        inertia: Matrix3::from_diagonal(&Vec3::new(
            m * r * r / 4.0,
            m * r * r / 4.0,
            m * r * r / 2.0,
        )),
        probe: Probe::Ellipsoid([r, r, 0.3 * r]),
        density: None,
        axisymmetric: true,
        mirror: CLOSED_FORM_MIRROR,
    });
}

/// The lamina's own laws: Φ is continuous through the disk and the normal acceleration jumps by
/// −4πGσ from below to above (a_z points down above the disk, up below it).
#[test]
fn uniform_disk_jump_across_the_lamina() {
    let (radius, m) = (1.2, 0.9);
    let body = UniformDisk::new(radius, m).unwrap();
    let sigma = m / (PI * radius * radius);
    for rho in [0.0, 0.3, 0.7, 1.1] {
        let eps = 1e-9;
        let above = body.field(&Vec3::new(rho, 0.0, eps));
        let below = body.field(&Vec3::new(rho, 0.0, -eps));
        let jump = above.acceleration.z - below.acceleration.z;
        let expected = -4.0 * PI * sigma;
        // The jump's smooth part changes by O(eps/R) between the two points.
        assert!(
            ((jump - expected) / expected).abs() < 1e-7,
            "ρ = {rho}: jump {jump}, expected {expected}"
        );
        assert!(((above.potential - below.potential) / above.potential).abs() < 1e-14);
    }
}

fn mesh_faces(body: &Polyhedron) -> Vec<[Vec3; 3]> {
    let v = body.vertices();
    body.faces()
        .iter()
        .map(|f| f.map(|i| v[i as usize]))
        .collect()
}

/// Polyhedra: the cube, a Fahnestock octahedron at SI magnitudes, an ellipsoid mesh (all
/// mirror symmetric) and the Didymos radar model in SI units (no symmetry), each with the
/// inertia tensor computed by signed tetrahedra (checked independently in
/// `tests/polyhedron.rs`).
#[test]
fn polyhedra_conform() {
    let shapes = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../data/shapes");
    let didymos = Mesh::read_vertex_facet_csv(
        shapes.join("Didymos_A_vert_met.csv"),
        shapes.join("Didymos_A_facet.csv"),
        LengthUnit::Metres,
    )
    .unwrap();
    let g_si = 6.6743e-11;
    let cases = [
        (
            "cube",
            Polyhedron::with_mass(&Mesh::cube(2.0), 1.3)
                .unwrap()
                .with_gravitational_constant(0.7)
                .unwrap(),
            true,
        ),
        (
            "octahedron B2 (SI)",
            Polyhedron::with_density(&Mesh::octahedron(1.0, 1.5, 0.9), 2500.0)
                .unwrap()
                .with_gravitational_constant(g_si)
                .unwrap(),
            true,
        ),
        (
            "ellipsoid mesh 3:2:1, 320 faces",
            Polyhedron::with_mass(&Mesh::ellipsoid(3.0, 2.0, 1.0, 2), 0.8).unwrap(),
            true,
        ),
        (
            "Didymos (SI)",
            Polyhedron::with_density(&didymos, 2104.0)
                .unwrap()
                .with_gravitational_constant(g_si)
                .unwrap(),
            false,
        ),
    ];
    for (name, body, symmetric) in &cases {
        run_suite(&Case {
            name: name.to_string(),
            body,
            inertia: body.inertia_tensor(),
            probe: Probe::Mesh(mesh_faces(body)),
            density: Some(body.density()),
            axisymmetric: false,
            mirror: symmetric.then_some(POLYHEDRON_SYMMETRY_REL),
        });
    }
}
