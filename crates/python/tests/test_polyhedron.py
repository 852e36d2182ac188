"""Polyhedron: arrays and files in, the cube's analytic field, Didymos's mass properties, bad
meshes refused with the validator's message, the third law with an ellipsoid, a simulation."""

import json
import pathlib

import numpy as np
import pytest

import surfgrav as sg

ROOT = pathlib.Path(__file__).resolve().parents[3]
SHAPES = ROOT / "data" / "shapes"

# The cube [-1, 1]^3: vertex k has coordinates (±1, ±1, ±1) by the bits of k; twelve
# triangles, counter-clockwise seen from outside.
CUBE_VERTICES = np.array(
    [[(1.0 if k & 1 else -1.0), (1.0 if k & 2 else -1.0), (1.0 if k & 4 else -1.0)] for k in range(8)]
)
CUBE_FACES = np.array(
    [
        [0, 2, 3], [0, 3, 1],  # z = -1
        [4, 5, 7], [4, 7, 6],  # z = +1
        [0, 1, 5], [0, 5, 4],  # y = -1
        [2, 6, 7], [2, 7, 3],  # y = +1
        [0, 4, 6], [0, 6, 2],  # x = -1
        [1, 3, 7], [1, 7, 5],  # x = +1
    ],
    dtype=np.int64,
)


def cube(**kwargs):
    if "density" not in kwargs:
        kwargs.setdefault("mass", 1.0)
    return sg.Polyhedron(CUBE_VERTICES, CUBE_FACES, **kwargs)


def test_cube_matches_the_analytic_reference():
    """Against tests/reference/polyhedron_cube.json: the corner-sum antiderivative at 80 digits
    (tests/reference/polyhedron_cube.py, accuracy ~1e-60). Tolerance 1e-13 relative: the
    Rust crate's POLYHEDRON_REL (the face/edge sum cancels; the Rust test holds the same)."""
    doc = json.loads((ROOT / "tests" / "reference" / "polyhedron_cube.json").read_text())
    body = cube()
    points = np.array([[float(x) for x in c["point"]] for c in doc["cases"]])
    phi, acc = body.field(points)
    worst = 0.0
    for k, case in enumerate(doc["cases"]):
        phi_ref = float(case["potential"])
        a_ref = np.array([float(x) for x in case["acceleration"]])
        e_phi = abs(phi[k] - phi_ref) / abs(phi_ref)
        scale = np.linalg.norm(a_ref)
        e_a = np.linalg.norm(acc[k] - a_ref) / scale if scale > 0 else np.linalg.norm(acc[k])
        worst = max(worst, e_phi, e_a)
        assert e_phi <= 1e-13 and e_a <= 1e-13, (case["label"], e_phi, e_a)
    assert len(doc["cases"]) == 39 and worst > 0.0


def test_arrays_obj_and_csv_give_the_same_body(tmp_path):
    obj = tmp_path / "cube.obj"
    obj.write_text(
        "".join(f"v {x} {y} {z}\n" for x, y, z in CUBE_VERTICES)
        + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in CUBE_FACES)
    )
    vertices = tmp_path / "cube_vert.csv"
    facets = tmp_path / "cube_facet.csv"
    # Kilometres here: the CSV body is the same cube once converted to metres.
    vertices.write_text("".join(f"0,{x / 1000},{y / 1000},{z / 1000}\n" for x, y, z in CUBE_VERTICES))
    facets.write_text("".join(f"{a + 1},{b + 1},{c + 1},,\n" for a, b, c in CUBE_FACES))
    from_arrays = cube(density=0.125)
    from_obj = sg.Polyhedron.from_obj(obj, density=0.125)
    from_csv = sg.Polyhedron.from_csv(vertices, facets, density=0.125, units="km")
    points = np.array([[0.3, -0.2, 0.5], [1.7, 0.4, -0.9], [30.0, 20.0, 10.0]])
    expected = from_arrays.field(points)
    for body in (from_obj, from_csv):
        assert isinstance(body, sg.Polyhedron) and isinstance(body, sg.Body)
        assert body.kind == "polyhedron" and body.spec is None
        assert body.mass == pytest.approx(1.0, rel=1e-15)  # 8 m³ × 0.125
        phi, acc = body.field(points)
        # The same vertices after conversion, the same faces: the same sums, bit for bit.
        np.testing.assert_array_equal(phi, expected[0])
        np.testing.assert_array_equal(acc, expected[1])
    assert from_csv.units == "km" and from_obj.source == str(obj)
    # The OBJ reader may number the vertices in another order: the same triangles in space.
    np.testing.assert_array_equal(from_obj.vertices[from_obj.faces], CUBE_VERTICES[CUBE_FACES])
    np.testing.assert_array_equal(from_arrays.faces, CUBE_FACES)
    assert from_arrays.volume == pytest.approx(8.0, rel=1e-15)
    assert "Polyhedron(" in repr(from_obj) and "faces=12" in repr(from_obj)


def test_the_body_frame_is_centred_on_the_centroid():
    shift = np.array([5.0, -3.0, 2.0])
    moved = sg.Polyhedron(CUBE_VERTICES + shift, CUBE_FACES, mass=1.0)
    np.testing.assert_allclose(moved.centroid, shift, rtol=1e-15)
    np.testing.assert_allclose(moved.vertices, CUBE_VERTICES, atol=1e-14)
    points = np.array([[0.3, -0.2, 0.5], [2.5, 1.0, 0.0]])
    # The field about the centroid is the centred cube's (to rounding of the shifted vertices).
    np.testing.assert_allclose(moved.field(points)[0], cube().field(points)[0], rtol=1e-14)


def test_field_is_vectorised_parallel_and_tends_to_a_point_mass():
    body = cube(mass=3.0, G=2.0)
    rng = np.random.default_rng(1)
    points = rng.uniform(-4.0, 4.0, size=(2000, 3))  # beyond one chunk: runs in parallel
    phi, acc = body.field(points)
    assert phi.shape == (2000,) and acc.shape == (2000, 3)
    # Each row equals the single-point call (the parallel split changes nothing).
    for k in (0, 777, 1999):
        one_phi, one_acc = body.field(points[k : k + 1])
        assert one_phi[0] == phi[k] and (one_acc[0] == acc[k]).all()
    # Far away: -GM/r. The cube's quadrupole vanishes (cubic symmetry), so the next term is
    # O((R/r)^4) ~ 1e-16 at r = 1e4 (R = √3).
    far = np.array([[1e4, 0.0, 0.0], [0.0, 6e3, 8e3]])
    np.testing.assert_allclose(body.field(far)[0], -6.0 / 1e4, rtol=1e-14)


def test_didymos_mesh_volume_and_mass():
    """Didymos (Naidu et al. 2020, data/shapes): volume 248548158.0017 m³ and inertia/density
    from the independent numpy figures of data/shapes/README.md (13 and 7 digits), and GUBAS's
    systemdata inertia (17 digits, the same tetrahedra sum: within 1e-12, as the Rust test)."""
    rho = 2103.985767887719
    body = sg.Polyhedron.from_csv(
        SHAPES / "Didymos_A_vert_met.csv", SHAPES / "Didymos_A_facet.csv", density=rho, G=6.6743e-11
    )
    assert body.faces.shape == (1996, 3) and body.vertices.shape == (1000, 3)
    assert abs(body.volume - 248548158.0017) < 0.5e-4 + 1e-15 * body.volume
    assert body.mass == pytest.approx(rho * 248548158.0017, rel=1e-12)
    # The engine's density is mass / volume again: ρ·V/V, two roundings.
    assert body.density == pytest.approx(rho, rel=4e-16 * 4)
    inertia = np.diag(body.inertia())
    np.testing.assert_allclose(
        inertia, [3.1348424975008636e16, 3.1920248302583308e16, 3.27904162014951e16], rtol=1e-12
    )
    np.testing.assert_allclose(inertia / rho, [1.489954e13, 1.517132e13, 1.558490e13], rtol=5e-7)


def flipped(faces, k):
    out = faces.copy()
    out[k] = out[k][::-1]
    return out


@pytest.mark.parametrize(
    "vertices, faces, message",
    [
        (CUBE_VERTICES, CUBE_FACES[:-1], "has no face running the other way: the mesh is open there"),
        (CUBE_VERTICES, flipped(CUBE_FACES, 3), "one of them is flipped"),
        (CUBE_VERTICES, np.where(CUBE_FACES == 7, 8, CUBE_FACES), "refers to vertex 8, but there are only 8"),
        (CUBE_VERTICES, CUBE_FACES[:3], "at least 4 faces, got 3"),
        (CUBE_VERTICES, np.where(CUBE_FACES == 0, -1, CUBE_FACES), r"faces\[0\] = \(-1, 2, 3\) has a negative index"),
        (CUBE_VERTICES, CUBE_FACES.astype(np.float64), "faces must have an integer dtype"),
        (CUBE_VERTICES, CUBE_FACES.tolist(), "faces must be a numpy array of shape"),
        (CUBE_VERTICES, CUBE_FACES[:, :2], r"faces must have shape \(M, 3\), got shape \(12, 2\)"),
        (CUBE_VERTICES[:, :2], CUBE_FACES, r"vertices must have shape \(N, 3\)"),
        (np.where(CUBE_VERTICES == 1.0, np.nan, CUBE_VERTICES), CUBE_FACES, r"vertices\[1\] must be three finite"),
    ],
    ids=["open", "flipped", "index-range", "too-few", "negative", "float-faces", "list", "faces-shape", "vertices-shape", "nan"],
)
def test_bad_meshes_raise_input_error(vertices, faces, message):
    with pytest.raises(sg.InputError, match=message):
        sg.Polyhedron(vertices, faces, mass=1.0)


def test_other_bad_polyhedron_input(tmp_path):
    with pytest.raises(sg.InputError, match="not both"):
        cube(mass=1.0, density=1.0)
    with pytest.raises(sg.InputError, match="needs `mass`"):
        sg.Polyhedron(CUBE_VERTICES, CUBE_FACES)
    with pytest.raises(sg.InputError, match='unknown length unit "ft"'):
        cube(units="ft")
    with pytest.raises(sg.InputError, match="mass must be a positive finite number"):
        cube(mass=-1.0)
    with pytest.raises(sg.InputError, match="absent.obj"):
        sg.Polyhedron.from_obj(tmp_path / "absent.obj", mass=1.0)
    quad = tmp_path / "quad.obj"
    quad.write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n")
    with pytest.raises(sg.InputError, match="face 0 has 4 corners; only triangles"):
        sg.Polyhedron.from_obj(quad, mass=1.0)
    bad_csv = tmp_path / "bad_facet.csv"
    bad_csv.write_text("1,2\n")
    vert = tmp_path / "v.csv"
    vert.write_text("0,0,0,0\n")
    with pytest.raises(sg.InputError, match=r"bad_facet.csv:1: expected a triangle"):
        sg.Polyhedron.from_csv(vert, bad_csv, mass=1.0)


def test_third_law_with_an_ellipsoid():
    poly = cube(mass=2.0)
    ell = sg.Ellipsoid((1.0, 0.7, 0.4), 1.5)
    position = np.array([3.1, 0.9, -0.7])
    qa, qb = [0.3, -0.2, 0.9], [1.1, 0.4, 0.0]
    r = sg.interact(poly, ell, position, orientation_a=qa, orientation_b=qb, tolerance=1e-10)
    s = sg.interact(ell, poly, -position, orientation_a=qb, orientation_b=qa, tolerance=1e-10)
    assert np.linalg.norm(r.torque_on_a) > 1e-4  # a real torque on the cube
    # Swapping the bodies integrates over the other surface in the other field: two different
    # computations, each certified to 1e-10 relative (mesh pairs are certified at the engine's
    # tolerance); their difference is below 2e-10, asserted at 1e-9.
    assert s.potential_energy == pytest.approx(r.potential_energy, rel=1e-9)
    scale = np.linalg.norm(r.force_on_a)
    np.testing.assert_allclose(s.force_on_a, r.force_on_b, rtol=0, atol=1e-9 * scale)
    scale *= np.linalg.norm(position)
    np.testing.assert_allclose(s.torque_on_a, r.torque_on_b, rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(s.torque_on_b, r.torque_on_a, rtol=0, atol=1e-9 * scale)


@pytest.mark.parametrize("distance", [1e2, 3e2, 1e3, 1e4])
def test_a_far_pair_tends_to_point_masses(distance):
    poly = cube(mass=2.0)
    ell = sg.Ellipsoid((1.0, 0.7, 0.4), 1.5)
    far = sg.interact(poly, ell, [distance, 0.0, 0.0])
    # |F| -> G m_A m_B / r², to O((R/r)^2): 3e-4 at 100 apart (R ~ 1.7), 3e-6 at 1000.
    bound = 3.0 * (1.75 / distance) ** 2
    assert np.linalg.norm(far.force_on_a) == pytest.approx(2.0 * 1.5 / distance**2, rel=bound)


def test_a_polyhedron_moves_in_a_simulation():
    sim = sg.Simulation(integrator="dop853", tolerance=1e-10)
    sim.add(cube(mass=1.0), position=[-2.0, 0.0, 0.0], velocity=[0.0, -0.25, 0.0], angular_velocity=[0.0, 0.0, 0.3])
    sim.add(sg.Sphere(0.5, 1.0), position=[2.0, 0.0, 0.0], velocity=[0.0, 0.25, 0.0])
    traj = sim.integrate(5.0)
    assert traj.summary["motion_path"] == "rotation"
    assert traj.summary["termination"] == "completed" and traj.t[-1] == 5.0
    # DOP853 at 1e-10 over ~2/5 of an orbit: energy and J kept to ~1e-9 relative (drift grows
    # with the tolerance times the steps); 1e-8 is the bound asserted.
    assert np.max(np.abs(traj.energy / traj.energy[0] - 1)) < 1e-8
    j = np.linalg.norm(traj.angular_momentum - traj.angular_momentum[0], axis=1)
    assert np.max(j) < 1e-8 * np.linalg.norm(traj.angular_momentum[0])
    # The cube's spin changed: the sphere's field torques it.
    assert not np.allclose(traj.angular_velocities[-1, 0], [0.0, 0.0, 0.3], rtol=0, atol=1e-9)
