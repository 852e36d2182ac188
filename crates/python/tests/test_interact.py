"""interact and interact_batch: the command line, the third law, batches, bad input."""

import numpy as np
import pytest

import surfgrav as sg
from conftest import vec


def rotation_matrix(rv):
    """Rodrigues' formula, independent of the package."""
    rv = np.asarray(rv, dtype=float)
    angle = np.linalg.norm(rv)
    if angle == 0:
        return np.eye(3)
    k = rv / angle
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


CASES = [
    # (a, b, position, orientation_a, orientation_b)
    (
        "spheroid:equatorial=1,polar=0.25,mass=1",
        "spheroid:equatorial=1,polar=0.25,mass=1",
        (3.0, 0.0, 0.0),
        (0.0, 0.0, 0.0),
        (0.0, 0.0, 0.0),
    ),
    (
        "ellipsoid:a=1,b=0.7,c=0.3,mass=2",
        "spheroid:equatorial=0.25,polar=1,mass=1",
        (2.2, 1.1, -0.4),
        (0.3, -0.2, 0.9),
        (1.1, 0.4, 0.0),
    ),
    (
        "disk:radius=1,mass=1",
        "disk:radius=1,mass=1",
        (2.5, 0.0, 0.0),
        (0.0, 0.0, 0.0),
        (0.0, 0.0, 0.0),
    ),
    ("point:mass=3", "sphere:radius=1,density=2", (0.0, 4.0, 0.0), (0, 0, 0), (0.2, 0, 0)),
]


def body_of(spec, G=1.0):
    kind, rest = spec.split(":")
    kv = dict(item.split("=") for item in rest.split(","))
    amount = {k: float(kv.pop(k)) for k in ("mass", "density") if k in kv}
    kv = {k: float(v) for k, v in kv.items()}
    if kind == "point":
        return sg.PointMass(amount["mass"], G=G)
    if kind == "sphere":
        return sg.Sphere(kv["radius"], **amount, G=G)
    if kind == "spheroid":
        return sg.Spheroid(kv["equatorial"], kv["polar"], **amount, G=G)
    if kind == "ellipsoid":
        return sg.Ellipsoid(a=kv["a"], b=kv["b"], c=kv["c"], **amount, G=G)
    return sg.Disk(kv["radius"], **amount, G=G)


@pytest.mark.parametrize("spec_a, spec_b, position, rot_a, rot_b", CASES)
def test_interact_matches_the_command_line_bit_for_bit(cli, spec_a, spec_b, position, rot_a, rot_b):
    a, b = body_of(spec_a), body_of(spec_b)
    assert a.spec == spec_a and b.spec == spec_b
    for tolerance in (1e-12, 1e-8):
        r = sg.interact(a, b, position, orientation_a=rot_a, orientation_b=rot_b, tolerance=tolerance)
        expected = cli.json(
            "interact", "--a", spec_a, "--b", spec_b, "--position", vec(position),
            "--orientation-a", vec(rot_a), "--orientation-b", vec(rot_b),
            "--tolerance", repr(tolerance),
        )
        assert r.to_dict() == expected
        assert list(r.force_on_a) == expected["force_on_a"]
        assert r.method == expected["method"] and r.evaluations == expected["evaluations"]


def test_third_law_and_balance_of_angular_momentum():
    a = sg.Ellipsoid((1.0, 0.7, 0.3), 2.0)
    b = sg.Spheroid(0.25, 1.0, 1.0)
    position = np.array([2.2, 1.1, -0.4])
    r = sg.interact(a, b, position, orientation_a=[0.3, -0.2, 0.9], orientation_b=[1.1, 0.4, 0.0])
    assert (r.force_on_b == -r.force_on_a).all()
    # M_B = −M_A − (c_A − c_B) × F_A about each centroid.
    np.testing.assert_allclose(
        r.torque_on_b, -r.torque_on_a - np.cross(-position, r.force_on_a), atol=1e-12
    )
    assert np.linalg.norm(r.torque_on_a) > 1e-3  # a real torque, not a trivial zero
    # Swapping the bodies: the same energy, the forces exchanged (B at the origin, A at −position).
    s = sg.interact(b, a, -position, orientation_a=[1.1, 0.4, 0.0], orientation_b=[0.3, -0.2, 0.9])
    assert s.potential_energy == pytest.approx(r.potential_energy, rel=1e-11)
    np.testing.assert_allclose(s.force_on_a, r.force_on_b, rtol=1e-10)
    np.testing.assert_allclose(s.torque_on_a, r.torque_on_b, rtol=1e-9, atol=1e-13)


def test_force_is_minus_the_gradient_of_the_energy():
    a = sg.Ellipsoid((1.0, 0.7, 0.3), 1.0)
    b = sg.Spheroid(1.0, 0.25, 1.0)
    p = np.array([2.5, 0.7, 0.3])
    h = 1e-4
    grad = []
    for k in range(3):
        e = np.eye(3)[k] * h
        vp = sg.interact(a, b, p + e, orientation_b=[0.2, 0.1, 0]).potential_energy
        vm = sg.interact(a, b, p - e, orientation_b=[0.2, 0.1, 0]).potential_energy
        grad.append((vp - vm) / (2 * h))
    f_b = sg.interact(a, b, p, orientation_b=[0.2, 0.1, 0]).force_on_b
    np.testing.assert_allclose(f_b, -np.array(grad), rtol=1e-6)


def test_quaternions_and_rotation_vectors_agree():
    a = sg.Ellipsoid((1.0, 0.7, 0.3), 1.0)
    b = sg.Sphere(0.5, 1.0)
    rv = np.array([0.3, -0.2, 0.9])
    angle = np.linalg.norm(rv)
    q = np.concatenate([[np.cos(angle / 2)], np.sin(angle / 2) * rv / angle])
    r1 = sg.interact(a, b, [2.0, 0.5, 0.1], orientation_a=rv)
    r2 = sg.interact(a, b, [2.0, 0.5, 0.1], orientation_a=q)
    np.testing.assert_allclose(r1.force_on_a, r2.force_on_a, rtol=1e-13)
    # Rotating the whole scene rotates the force: A turned by R, B at R p.
    p = np.array([2.0, 0.5, 0.1])
    R = rotation_matrix(rv)
    r0 = sg.interact(a, b, p)
    assert np.abs(r1.force_on_a - r0.force_on_a).max() > 1e-3  # the orientation matters
    r3 = sg.interact(a, b, R @ p, orientation_a=rv)
    np.testing.assert_allclose(r3.force_on_a, R @ r0.force_on_a, rtol=1e-11)


def test_batch_equals_single_calls():
    a = sg.Ellipsoid((1.0, 0.7, 0.3), 1.0)
    b = sg.Spheroid(1.0, 0.25, 1.0)
    rng = np.random.default_rng(5)
    n = 40
    d = rng.normal(size=(n, 3))
    positions = d / np.linalg.norm(d, axis=1)[:, None] * rng.uniform(2.5, 6.0, size=n)[:, None]
    rot_b = rng.normal(size=(n, 3))
    batch = sg.interact_batch(a, b, positions, orientations_b=rot_b, orientations_a=[0.1, 0.2, 0.3])
    assert len(batch) == n
    assert batch.force_on_a.shape == (n, 3) and batch.potential_energy.shape == (n,)
    assert batch.evaluations.dtype == np.int64 and len(batch.method) == n
    for i in range(0, n, 7):
        r = sg.interact(a, b, positions[i], orientation_a=[0.1, 0.2, 0.3], orientation_b=rot_b[i])
        assert (batch.force_on_a[i] == r.force_on_a).all()
        assert (batch.torque_on_b[i] == r.torque_on_b).all()
        assert batch.potential_energy[i] == r.potential_energy
        assert batch.method[i] == r.method and batch.evaluations[i] == r.evaluations
    np.testing.assert_array_equal(batch.force_on_b, -batch.force_on_a)


def test_batch_errors_name_the_row():
    a = sg.Sphere(1.0, 1.0)
    positions = np.array([[3.0, 0, 0], [1.5, 0, 0], [5.0, 0, 0]])
    with pytest.raises(sg.InputError, match=r"positions\[1\]: bodies A and B overlap"):
        sg.interact_batch(a, a, positions)
    with pytest.raises(sg.InputError, match="orientations_b has 2 rows but positions has 3"):
        sg.interact_batch(a, a, positions + 3, orientations_b=np.zeros((2, 3)))
    with pytest.raises(sg.InputError, match=r"shape \(N, 3\) or \(N, 4\)"):
        sg.interact_batch(a, a, positions + 3, orientations_b=np.zeros((3, 5)))
    with pytest.raises(sg.InputError, match=r"orientations_a\[0\] as a quaternion"):
        sg.interact_batch(a, a, positions + 3, orientations_a=np.ones((3, 4)))
    with pytest.raises(sg.InputError, match="dtype float64"):
        sg.interact_batch(a, a, positions.astype(np.float32))


@pytest.mark.parametrize(
    "spec_a, spec_b, position, extra",
    [
        ("sphere:radius=1,mass=1", "sphere:radius=1,mass=1", (1.5, 0.0, 0.0), []),
        ("spheroid:equatorial=1,polar=0.25,mass=1", "spheroid:equatorial=1,polar=0.25,mass=1", (2.0, 0.0, 0.0), []),
        ("sphere:radius=1,mass=1", "sphere:radius=1,mass=1", (3.0, 0.0, 0.0), ["--tolerance", "2"]),
    ],
)
def test_bad_interactions_raise_the_command_lines_message(cli, spec_a, spec_b, position, extra):
    tolerance = float(extra[1]) if extra else 1e-12
    with pytest.raises(sg.InputError) as info:
        sg.interact(body_of(spec_a), body_of(spec_b), position, tolerance=tolerance)
    expected = cli.error("interact", "--a", spec_a, "--b", spec_b, "--position", vec(position), *extra)
    assert str(info.value) == expected


def test_other_bad_input():
    s = sg.Sphere(1.0, 1.0)
    with pytest.raises(sg.InputError, match="different gravitational constants"):
        sg.interact(s, sg.Sphere(1.0, 1.0, G=2.0), [3.0, 0, 0])
    for tolerance in (0.0, -1.0, float("nan"), float("inf")):
        with pytest.raises(sg.InputError, match="tolerance must be a positive finite number"):
            sg.interact(s, s, [3.0, 0, 0], tolerance=tolerance)
    for position, words in [
        ([3.0, 0], "three finite numbers"),
        ([3.0, np.nan, 0], "three finite numbers"),
        ("3,0,0", "position must be 3 numbers"),
        (np.array([3, 0, 0]), "dtype float64"),
    ]:
        with pytest.raises(sg.InputError, match=words):
            sg.interact(s, s, position)
    with pytest.raises(sg.InputError, match="unit norm"):
        sg.interact(s, s, [3.0, 0, 0], orientation_a=[1.0, 1.0, 0.0, 0.0])
    with pytest.raises(sg.InputError, match="got 2 numbers"):
        sg.interact(s, s, [3.0, 0, 0], orientation_b=[1.0, 1.0])
    with pytest.raises(TypeError):
        sg.interact(s, "sphere", [3.0, 0, 0])
