//! The polyhedron against independent figures: the cube's analytic potential (mpmath, committed
//! JSON), ellipsoid meshes converging to the ellipsoid's closed form, the Fahnestock et al.
//! (2006) octahedra's published mass properties, the real meshes' independently measured
//! volumes and inertia, and bad meshes rejected with the face or edge named.
//!
//! `cargo test -p surfgrav-potentials --test polyhedron -- --nocapture` prints the measured
//! errors (worst per group of points, errors against distance, the convergence rate).

use std::f64::consts::{E, PI};
use std::path::PathBuf;

use nalgebra::Matrix3;
use serde_json::Value;
use surfgrav_potentials::polyhedron::FAR_FIELD_RADII;
use surfgrav_potentials::tolerance::POLYHEDRON_REL;
use surfgrav_potentials::{
    Ellipsoid, LengthUnit, Mesh, MeshError, Polyhedron, PolyhedronError, Potential, Region, Vec3,
};

fn shapes() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../data/shapes")
}

fn kw4_alpha() -> Mesh {
    Mesh::read_obj(shapes().join("kw4_alpha.obj"), LengthUnit::Kilometres).unwrap()
}

fn kw4_beta() -> Mesh {
    Mesh::read_obj(shapes().join("kw4_beta.obj"), LengthUnit::Kilometres).unwrap()
}

fn didymos() -> Mesh {
    Mesh::read_vertex_facet_csv(
        shapes().join("Didymos_A_vert_met.csv"),
        shapes().join("Didymos_A_facet.csv"),
        LengthUnit::Metres,
    )
    .unwrap()
}

fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

fn number(v: &Value) -> f64 {
    v.as_str().unwrap().parse().unwrap()
}

/// The cube [-1, 1]³ of mass 1 against the corner-sum antiderivative evaluated at 80 digits by
/// `tests/reference/polyhedron_cube.py` (see its docstring: an independent route, validated
/// against numerical differentiation and brute-force triple integrals).
#[test]
fn cube_against_analytic_reference() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/reference/polyhedron_cube.json");
    let doc: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let body = Polyhedron::with_mass(&Mesh::cube(2.0), 1.0).unwrap();
    let mut failures = Vec::new();
    let mut worst = (0.0f64, String::new());
    for case in doc["cases"].as_array().unwrap() {
        let label = case["label"].as_str().unwrap();
        let p: Vec<f64> = case["point"]
            .as_array()
            .unwrap()
            .iter()
            .map(number)
            .collect();
        let p = Vec3::new(p[0], p[1], p[2]);
        let phi_ref = number(&case["potential"]);
        let a: Vec<f64> = case["acceleration"]
            .as_array()
            .unwrap()
            .iter()
            .map(number)
            .collect();
        let a_ref = Vec3::new(a[0], a[1], a[2]);
        let f = body.field(&p);
        let e_phi = rel(f.potential, phi_ref);
        let e_a = (f.acceleration - a_ref).norm() / a_ref.norm().max(f64::MIN_POSITIVE);
        let e_a = if a_ref.norm() == 0.0 {
            f.acceleration.norm()
        } else {
            e_a
        };
        println!("cube {label:32} Φ {e_phi:.1e}  a {e_a:.1e}");
        let e = e_phi.max(e_a);
        if e > worst.0 {
            worst = (e, label.to_string());
        }
        if e_phi > POLYHEDRON_REL || e_a > POLYHEDRON_REL {
            failures.push(format!("{label}: Φ rel {e_phi:e}, a rel {e_a:e}"));
        }
        let region = body.region(&p);
        let expected = match case["region"].as_str().unwrap() {
            "inside" => Region::Inside,
            "surface" => Region::OnSurface,
            _ => Region::Outside,
        };
        if region != expected {
            failures.push(format!("{label}: region {region:?}, expected {expected:?}"));
        }
    }
    println!("cube: worst {:.2e} at {}", worst.0, worst.1);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Fahnestock et al. (2006), Table 1: B2 with vertices ±1.0, ±1.5, ±0.9 m on the axes,
/// V = 1.800 m³, m = 4500 kg, I = (1377.0, 814.5, 1462.5) kg m²; B1 with ±1, ±1/e, ±1/π m,
/// V = 0.1561 m³, m = 390.3 kg, I = (9.24, 42.99, 44.32) kg m². Both have density 2500 kg/m³
/// (4500 / 1.8). Tolerance: half a unit in the last published digit.
#[test]
fn fahnestock_octahedra_mass_properties() {
    let cases = [
        (
            "B2",
            [1.0, 1.5, 0.9],
            1.800,
            0.0005,
            4500.0,
            0.5,
            [1377.0, 814.5, 1462.5],
            0.05,
        ),
        (
            "B1",
            [1.0, 1.0 / E, 1.0 / PI],
            0.1561,
            0.00005,
            390.3,
            0.05,
            [9.24, 42.99, 44.32],
            0.005,
        ),
    ];
    for (name, [a, b, c], volume, dv, mass, dm, inertia, di) in cases {
        let body = Polyhedron::with_density(&Mesh::octahedron(a, b, c), 2500.0).unwrap();
        println!(
            "{name}: V = {:.6} m³, m = {:.4} kg, I = {:.4?}",
            body.volume(),
            body.mass(),
            body.inertia_tensor().diagonal()
        );
        assert!((body.volume() - volume).abs() <= dv, "{name} volume");
        assert!((body.mass() - mass).abs() <= dm, "{name} mass");
        let i = body.inertia_tensor();
        for k in 0..3 {
            assert!(
                (i[(k, k)] - inertia[k]).abs() <= di,
                "{name} I[{k}] = {}",
                i[(k, k)]
            );
        }
        // The trait's validated tensor is the same.
        assert_eq!(*body.inertia().unwrap().tensor(), body.inertia_tensor());
        // Principal axes: off-diagonal products vanish to rounding.
        assert!((i - Matrix3::from_diagonal(&i.diagonal())).norm() < 1e-12 * i.norm());
        assert!(body.centroid().norm() < 1e-15);
    }
}

/// The real meshes validate and their volumes, centroid and inertia match the independent
/// numpy figures of `data/shapes/README.md` (given to 7 significant digits, Didymos's volume
/// to 13); Didymos's ρ·I also matches GUBAS's systemdata I_A (17 digits, its own tetrahedra
/// sum in double precision).
#[test]
fn real_meshes_validate_with_independent_mass_properties() {
    let alpha = Polyhedron::with_density(&kw4_alpha(), 1970.0).unwrap();
    let beta = Polyhedron::with_density(&kw4_beta(), 2810.0).unwrap();
    println!(
        "KW4 Alpha V = {:.7e} m³, Beta V = {:.7e} m³",
        alpha.volume(),
        beta.volume()
    );
    assert!(rel(alpha.volume(), 1.195308e9) < 5e-7);
    assert!(rel(beta.volume(), 4.803451e7) < 5e-7);
    assert_eq!(alpha.faces().len(), 9168);
    assert_eq!(beta.faces().len(), 2292);

    let rho = 2103.985767887719; // 2103.98576788771879 in the systemdata
    let d = Polyhedron::with_density(&didymos(), rho).unwrap();
    println!(
        "Didymos V = {:.4} m³, centroid {:?}, I/ρ = {:.6e}",
        d.volume(),
        d.centroid(),
        d.inertia_tensor().diagonal() / rho
    );
    assert!((d.volume() - 248548158.0017).abs() < 1e-4 * 0.5 + 1e-15 * d.volume());
    assert!(d.centroid().norm() < 1e-9, "centroid {:?}", d.centroid());
    let per_density = d.inertia_tensor() / rho;
    for (k, expected) in [1.489954e13, 1.517132e13, 1.558490e13].iter().enumerate() {
        assert!(rel(per_density[(k, k)], *expected) < 5e-7);
    }
    // GUBAS systemdata_standard: I_A = diag(3.1348424975008636e16, 3.1920248302583308e16,
    // 3.2790416201495100e16) kg m², off-diagonal entries ≤ 1.1 kg m².
    let i = d.inertia_tensor();
    for (k, expected) in [
        3.1348424975008636e16,
        3.1920248302583308e16,
        3.27904162014951e16,
    ]
    .iter()
    .enumerate()
    {
        println!(
            "Didymos I[{k}] rel diff to GUBAS {:.1e}",
            rel(i[(k, k)], *expected)
        );
        assert!(rel(i[(k, k)], *expected) < 1e-12);
    }
    for (r, c) in [(0, 1), (0, 2), (1, 2)] {
        assert!(i[(r, c)].abs() < 1e3, "I[{r}{c}] = {}", i[(r, c)]);
    }
}

/// Principal axes: the moved body is diagonal with A ≤ B ≤ C, its centroid at the origin, and
/// the reported rotation maps the old frame's field onto the new one's.
#[test]
fn principal_axes_of_a_rotated_shifted_ellipsoid_mesh() {
    let mut mesh = Mesh::ellipsoid(3.0, 2.0, 1.0, 2);
    let rot = nalgebra::Rotation3::from_scaled_axis(Vec3::new(0.3, -0.5, 0.8));
    let shift = Vec3::new(10.0, -4.0, 2.5);
    for v in &mut mesh.vertices {
        *v = rot * *v + shift;
    }
    let body = Polyhedron::with_mass(&mesh, 2.0).unwrap();
    let (moved, frame) = body.to_principal_axes();
    assert!((frame.centroid - shift).norm() < 1e-13 * shift.norm());
    assert!(moved.centroid().norm() < 1e-14);
    let i = moved.inertia_tensor();
    let scale = i.norm();
    for (r, c) in [(0, 1), (0, 2), (1, 2)] {
        assert!(i[(r, c)].abs() < 1e-14 * scale);
    }
    assert!(i[(0, 0)] <= i[(1, 1)] && i[(1, 1)] <= i[(2, 2)]);
    // The long axis (3) ends up along x: the rotation undoes `rot` up to axis signs.
    let back = frame.rotation * rot;
    for k in 0..3 {
        assert!((back[(k, k)].abs() - 1.0).abs() < 1e-12, "{back}");
    }
    let p_old = Vec3::new(14.0, 1.0, -3.0);
    let p_new = frame.rotation * (p_old - frame.centroid);
    let (f_old, f_new) = (body.field(&p_old), moved.field(&p_new));
    let e_phi = rel(f_new.potential, f_old.potential);
    let e_a = (frame.rotation * f_old.acceleration - f_new.acceleration).norm()
        / f_old.acceleration.norm();
    println!("principal frame: field moved with the body to Φ {e_phi:.1e}, a {e_a:.1e}");
    // Both evaluations are within POLYHEDRON_REL of the exact field (the vertices carry
    // different roundings in the two frames).
    assert!(e_phi < POLYHEDRON_REL && e_a < POLYHEDRON_REL);
}

/// Meshes of an ellipsoid inscribed in it (icosahedron subdivided L times, 20·4^L faces,
/// edge h ∝ 2^-L) converge to the closed form like h²: the volume deficit of an inscribed
/// faceting is O(h²) per unit area. The test measures the order from the last three levels.
#[test]
fn ellipsoid_meshes_converge_at_second_order() {
    let (a, b, c) = (1.5, 1.0, 0.7);
    let density = 1.0;
    let exact = Ellipsoid::with_density(a, b, c, density).unwrap();
    let points = [
        Vec3::new(2.5, 0.4, -0.3),
        Vec3::new(-0.5, 1.8, 0.9),
        Vec3::new(0.3, -0.2, 0.1),
        Vec3::new(20.0, 10.0, -7.0),
    ];
    let mut errors = Vec::new();
    for level in 2..=5 {
        let body = Polyhedron::with_density(&Mesh::ellipsoid(a, b, c, level), density).unwrap();
        let err = points
            .iter()
            .map(|p| rel(body.potential(p), exact.potential(p)))
            .fold(0.0, f64::max);
        let err_a = points
            .iter()
            .map(|p| {
                let e = exact.acceleration(p);
                (body.acceleration(p) - e).norm() / e.norm()
            })
            .fold(0.0, f64::max);
        println!(
            "ellipsoid level {level} ({} faces): Φ err {err:.3e}, a err {err_a:.3e}",
            body.faces().len()
        );
        errors.push((err, err_a));
    }
    for k in 1..errors.len() {
        let order_phi = (errors[k - 1].0 / errors[k].0).log2();
        let order_a = (errors[k - 1].1 / errors[k].1).log2();
        println!(
            "observed order, levels {}→{}: Φ {order_phi:.3}, a {order_a:.3}",
            k + 1,
            k + 2
        );
        if k + 1 >= 4 {
            assert!((order_phi - 2.0).abs() < 0.1, "Φ order {order_phi}");
            assert!((order_a - 2.0).abs() < 0.1, "a order {order_a}");
        }
    }
}

/// Continuity on and across faces, edges and vertices of a real mesh: the field at a vertex,
/// an edge's midpoint and a face's centroid, and at δ along the face normal on either side,
/// differs by O(δ) in Φ and O(δ ln δ) in a.
#[test]
fn continuous_on_faces_edges_and_vertices() {
    let body = Polyhedron::with_density(&didymos(), 2100.0).unwrap();
    let faces = body.faces();
    let v = body.vertices();
    let radius = body.circumscribing_radius();
    for face in [0usize, 500, 1234] {
        let [i, j, k] = faces[face].map(|x| v[x as usize]);
        let normal = (j - i).cross(&(k - i)).normalize();
        for (what, p) in [
            ("vertex", i),
            ("edge", (i + j) / 2.0),
            ("face", (i + j + k) / 3.0),
        ] {
            let f0 = body.field(&p);
            assert!(f0.potential.is_finite() && f0.acceleration.iter().all(|x| x.is_finite()));
            assert_eq!(body.region(&p), Region::OnSurface, "{what} of face {face}");
            for delta in [1e-12, 1e-9, 1e-6] {
                for side in [1.0, -1.0] {
                    let q = p + normal * (side * delta * radius);
                    let f = body.field(&q);
                    let dphi = rel(f.potential, f0.potential);
                    let da = (f.acceleration - f0.acceleration).norm() / f0.acceleration.norm();
                    // |∇Φ| r / |Φ| ≤ ~2 and |∇a| r/|a| ≤ ~ 2 + ln(1/δ) near an edge.
                    assert!(
                        dphi < 4.0 * delta + 1e-14,
                        "{what} {face} δ {delta}: ΔΦ {dphi:e}"
                    );
                    assert!(
                        da < 10.0 * delta * (1.0 + (1.0 / delta).ln()) + 1e-13,
                        "{what} {face} δ {delta}: Δa {da:e}"
                    );
                }
            }
        }
    }
}

/// Direct sum against the certified expansion, and the direct sum's rounding against
/// distance: at the switch the two agree within the tolerance (the field is continuous
/// there to that accuracy); farther out the direct sum drifts like ε (r/R)² while the
/// expansion does not (printed: the errors against distance; the cube's reference test
/// measures the absolute accuracy of both branches).
#[test]
fn far_field_direct_sum_and_expansion() {
    for (name, body) in [
        (
            "KW4 Beta",
            Polyhedron::with_density(&kw4_beta(), 2810.0).unwrap(),
        ),
        (
            "Didymos",
            Polyhedron::with_density(&didymos(), 2100.0).unwrap(),
        ),
    ] {
        let radius = body.circumscribing_radius();
        let dir = Vec3::new(0.36, -0.48, 0.8).normalize();
        for k in [FAR_FIELD_RADII, 8.0, 16.0, 64.0, 256.0, 1e3, 1e4, 1e6] {
            let p = body.centroid() + dir * (k * radius);
            let Some(m) = body.field_multipole(&p) else {
                println!("{name} at {k} radii: expansion degree exceeds storage");
                continue;
            };
            let d = body.field_direct(&p);
            let e_phi = rel(d.potential, m.potential);
            let e_a = (d.acceleration - m.acceleration).norm() / m.acceleration.norm();
            println!("{name} at {k:>8} radii: direct vs expansion Φ {e_phi:.1e}, a {e_a:.1e}");
            if k == FAR_FIELD_RADII {
                assert!(e_phi < POLYHEDRON_REL && e_a < POLYHEDRON_REL, "{name} {k}");
            }
            // Far away: the expansion tends to the point mass, to rounding; and beyond 1e20
            // radii the field is the point mass's without overflow.
            let huge = body.centroid() + dir * (1e200 * radius);
            let f = body.field(&huge);
            let kepler = -body.gravitational_parameter() / (1e200 * radius);
            assert!(
                rel(f.potential, kepler) < 1e-14,
                "{name} at 1e200 radii: {f:?}"
            );
            if k >= 1e6 {
                let r = p - body.centroid();
                let kepler = -body.gravitational_parameter() / r.norm();
                assert!(rel(m.potential, kepler) < 1e-12);
            }
        }
    }
}

fn expect_error(mesh: &Mesh) -> MeshError {
    match Polyhedron::with_mass(mesh, 1.0) {
        Err(PolyhedronError::Mesh(e)) => {
            println!("{e}");
            e
        }
        other => panic!("expected a mesh error, got {other:?}"),
    }
}

#[test]
fn bad_meshes_are_rejected_naming_the_face_or_edge() {
    // Open: drop face 7.
    let mut open = Mesh::cube(1.0);
    let removed = open.faces.remove(7);
    match expect_error(&open) {
        MeshError::OpenEdge { from, to, face } => {
            // The edge's reverse belonged to the removed face.
            let pairs = [
                (removed[0], removed[1]),
                (removed[1], removed[2]),
                (removed[2], removed[0]),
            ];
            assert!(
                pairs.contains(&(to, from)),
                "edge {from}->{to} of face {face}"
            );
        }
        e => panic!("{e:?}"),
    }

    // One flipped face.
    let mut flipped = Mesh::cube(1.0);
    flipped.faces[5].swap(1, 2);
    match expect_error(&flipped) {
        MeshError::InconsistentEdge { first, second, .. } => {
            assert!(first == 5 || second == 5, "faces {first}, {second}")
        }
        e => panic!("{e:?}"),
    }

    // Inside out: every face reversed.
    let mut inverted = Mesh::cube(1.0);
    for f in &mut inverted.faces {
        f.swap(1, 2);
    }
    assert!(matches!(expect_error(&inverted), MeshError::InsideOut { volume, .. } if volume < 0.0));

    // Degenerate: a repeated vertex, and collinear vertices.
    let mut repeated = Mesh::cube(1.0);
    repeated.faces[3] = [2, 2, 6];
    assert!(matches!(
        expect_error(&repeated),
        MeshError::DegenerateFace { face: 3, .. }
    ));
    let mut collinear = Mesh::octahedron(1.0, 1.0, 1.0);
    // Vertex 4 (+z) moved onto the segment between vertices 0 (+x) and 2 (+y).
    collinear.vertices[4] = Vec3::new(0.5, 0.5, 0.0);
    let first_with = collinear
        .faces
        .iter()
        .position(|f| f.contains(&0) && f.contains(&2) && f.contains(&4))
        .unwrap();
    match expect_error(&collinear) {
        MeshError::DegenerateFace { face, .. } => assert_eq!(face, first_with),
        e => panic!("{e:?}"),
    }

    // Self-intersecting: two overlapping cubes in one mesh, and a vertex pushed through the
    // opposite side.
    let mut two = Mesh::cube(1.0);
    let other = Mesh::cube(1.0);
    let base = two.vertices.len();
    two.vertices
        .extend(other.vertices.iter().map(|v| v + Vec3::new(0.5, 0.3, 0.2)));
    two.faces
        .extend(other.faces.iter().map(|f| f.map(|i| i + base)));
    match expect_error(&two) {
        MeshError::SelfIntersection { first, second } => {
            assert!(first < 12 && second >= 12, "faces {first}, {second}")
        }
        e => panic!("{e:?}"),
    }
    // The sphere mesh's vertex farthest along +x pushed through the body and out at −x: its
    // fan crosses the far side.
    let mut pushed = Mesh::ellipsoid(1.0, 1.0, 1.0, 1);
    let tip = (0..pushed.vertices.len())
        .max_by(|&i, &j| pushed.vertices[i].x.total_cmp(&pushed.vertices[j].x))
        .unwrap();
    pushed.vertices[tip] = Vec3::new(-1.5, 0.01, 0.02);
    match expect_error(&pushed) {
        MeshError::SelfIntersection { first, second } => {
            let fan = |f: usize| pushed.faces[f].contains(&tip);
            assert!(fan(first) || fan(second), "faces {first}, {second}")
        }
        e => panic!("{e:?}"),
    }

    // Two tetrahedra touching at one vertex: a non-manifold vertex.
    let tet = |o: Vec3, s: f64| [Vec3::zeros(), Vec3::x(), Vec3::y(), Vec3::z()].map(|v| o + v * s);
    let mut bow = Mesh::default();
    bow.vertices.extend(tet(Vec3::zeros(), 1.0));
    bow.vertices.extend(tet(Vec3::zeros(), -1.0).iter().skip(1));
    let t = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
    bow.faces.extend(t);
    bow.faces
        .extend(t.map(|f| f.map(|i| if i == 0 { 0 } else { i + 3 })));
    match expect_error(&bow) {
        MeshError::NonManifoldVertex { vertex, .. } => assert_eq!(vertex, 0),
        e => panic!("{e:?}"),
    }

    // Bad indices and coordinates.
    let mut out_of_range = Mesh::cube(1.0);
    out_of_range.faces[9][1] = 99;
    assert!(matches!(
        expect_error(&out_of_range),
        MeshError::IndexOutOfRange {
            face: 9,
            index: 99,
            ..
        }
    ));
    let mut nan = Mesh::cube(1.0);
    nan.vertices[6].y = f64::NAN;
    assert!(matches!(
        expect_error(&nan),
        MeshError::NonFiniteVertex { vertex: 6, .. }
    ));
    let mut few = Mesh::cube(1.0);
    few.faces.truncate(3);
    assert!(matches!(
        expect_error(&few),
        MeshError::TooFewFaces { faces: 3 }
    ));
}

#[test]
fn unreadable_and_malformed_files_are_typed_errors() {
    let missing = Mesh::read_obj(shapes().join("no_such.obj"), LengthUnit::Metres);
    assert!(matches!(missing, Err(MeshError::Io { .. })));
    let dir = std::env::temp_dir().join(format!("surfgrav-poly-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (vp, fp) = (dir.join("v.csv"), dir.join("f.csv"));
    std::fs::write(&vp, "0,1,2,3\n0,1,x,3\n").unwrap();
    std::fs::write(&fp, "1,2,3,,\n").unwrap();
    match Mesh::read_vertex_facet_csv(&vp, &fp, LengthUnit::Metres) {
        Err(MeshError::Parse { line, .. }) => assert_eq!(line, 2),
        other => panic!("{other:?}"),
    }
    std::fs::write(&vp, "0,1,2,3\n").unwrap();
    std::fs::write(&fp, "1,2,3,4,\n").unwrap();
    assert!(matches!(
        Mesh::read_vertex_facet_csv(&vp, &fp, LengthUnit::Metres),
        Err(MeshError::Parse { line: 1, .. })
    ));
    assert!(matches!(
        "mi".parse::<LengthUnit>(),
        Err(MeshError::UnknownUnit { .. })
    ));
    std::fs::remove_dir_all(&dir).ok();
}

/// The batch API returns exactly what `field` returns, point by point.
#[test]
fn batch_matches_single_evaluations() {
    let body = Polyhedron::with_density(&kw4_beta(), 2810.0).unwrap();
    let r = body.circumscribing_radius();
    let points: Vec<Vec3> = (0..64)
        .map(|k| {
            let t = k as f64 / 64.0;
            Vec3::new((7.0 * t).cos(), (7.0 * t).sin(), 2.0 * t - 1.0) * r * (0.3 + 20.0 * t)
        })
        .collect();
    // A NaN travels as a NaN, not as a value.
    let nan = body.field(&Vec3::new(f64::NAN, 0.0, 0.0));
    assert!(nan.potential.is_nan() && nan.acceleration.iter().all(|x| x.is_nan()));
    let batch = body.fields(&points);
    for (p, f) in points.iter().zip(&batch) {
        assert_eq!(*f, body.field(p));
    }
}

/// The gravity-gradient tensor: central differences of the acceleration (inside, near the
/// surface, across the switch to the expansion), its trace (0 outside, −4πGρ inside), and the
/// direct sum against the certified expansion at the switch.
#[test]
fn gravity_gradient_tensor() {
    use surfgrav_potentials::polyhedron::GRADIENT_FAR_FIELD_RADII;
    let body = Polyhedron::with_density(&kw4_beta(), 2810.0)
        .unwrap()
        .with_gravitational_constant(6.6743e-11)
        .unwrap();
    let radius = body.circumscribing_radius();
    let c = body.centroid();
    let rho_g = 6.6743e-11 * 2810.0;
    let dir = Vec3::new(0.36, -0.48, 0.8);
    for k in [0.05, 0.2, 1.3, 3.0, 12.9, 13.1, 100.0] {
        let p = c + dir * (k * radius);
        let t = body.gravity_gradient(&p);
        // Fourth-order differences with h = 1e-4 R: truncation (h/d)⁴ ≲ 1e-12, cancellation
        // ε|a|/h ≲ 1e-11 of |T| R/|a| ~ 1.
        let h = 1e-4 * radius * k.max(1.0);
        let mut worst: f64 = 0.0;
        for b in 0..3 {
            let e = Vec3::ith(b, h);
            let d = |s: f64| body.acceleration(&(p + e * s));
            let fd = (d(-2.0) - d(2.0) + (d(1.0) - d(-1.0)) * 8.0) / (12.0 * h);
            for a in 0..3 {
                worst = worst.max((fd[a] - t[(a, b)]).abs() / t.norm());
            }
        }
        let region = body.region(&p);
        let trace = if region == Region::Inside {
            -4.0 * PI * rho_g
        } else {
            0.0
        };
        let e_trace = (t.trace() - trace).abs() / t.norm();
        println!("gradient at {k:>5} radii ({region:?}): vs differences {worst:.1e}, trace {e_trace:.1e}");
        assert!(worst < 1e-8, "{k}: {worst:e}");
        assert!(e_trace < 1e-13, "{k}: trace off by {e_trace:e}");
        assert_eq!(t, t.transpose());
    }
    for (name, body) in [
        ("KW4 Beta", body.clone()),
        (
            "KW4 Alpha",
            Polyhedron::with_density(&kw4_alpha(), 1970.0).unwrap(),
        ),
        (
            "Didymos",
            Polyhedron::with_density(&didymos(), 2104.0).unwrap(),
        ),
    ] {
        let (c, radius) = (body.centroid(), body.circumscribing_radius());
        let at = |k: f64| body.gravity_gradient(&(c + dir.normalize() * (k * radius)));
        let (a, b) = (
            at(GRADIENT_FAR_FIELD_RADII * (1.0 - 1e-15)),
            at(GRADIENT_FAR_FIELD_RADII * (1.0 + 1e-15)),
        );
        let jump = (a - b).norm() / b.norm();
        println!(
            "gradient, {name}: direct vs expansion at the switch ({GRADIENT_FAR_FIELD_RADII} radii): {jump:.1e}"
        );
        assert!(jump < POLYHEDRON_REL);
    }
}
