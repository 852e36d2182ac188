"""Bodies and their fields: closed forms, the command line, bad input, arrays, the GIL."""

import threading
import time

import numpy as np
import pytest

import surfgrav as sg
from conftest import vec


def test_sphere_field_is_the_point_mass_field_outside_and_quadratic_inside():
    G, M, R = 6.6743e-11, 5.972e24, 6.371e6
    s = sg.Sphere(radius=R, mass=M, G=G)
    rng = np.random.default_rng(7)
    d = rng.normal(size=(1000, 3))
    d /= np.linalg.norm(d, axis=1)[:, None]
    r = R * rng.uniform(1.0001, 50.0, size=1000)
    pts = d * r[:, None]
    phi, acc = s.field(pts)
    assert phi.shape == (1000,) and acc.shape == (1000, 3)
    assert phi.dtype == np.float64 and acc.dtype == np.float64
    np.testing.assert_allclose(phi, -G * M / r, rtol=1e-14)
    np.testing.assert_allclose(acc, -G * M * pts / r[:, None] ** 3, rtol=1e-13, atol=0)
    # Inside: Φ = −GM(3R² − r²)/(2R³), a = −GM x / R³.
    inside = d[:100] * (R * rng.uniform(0, 0.999, size=100))[:, None]
    ri = np.linalg.norm(inside, axis=1)
    phi, acc = s.field(inside)
    np.testing.assert_allclose(phi, -G * M * (3 * R**2 - ri**2) / (2 * R**3), rtol=1e-14)
    np.testing.assert_allclose(acc, -G * M * inside / R**3, rtol=1e-13)


def test_far_field_of_every_body_tends_to_minus_gm_over_r():
    bodies = [
        sg.PointMass(2.0),
        sg.Sphere(1.0, 2.0),
        sg.Spheroid(1.0, 0.25, 2.0),
        sg.Spheroid(0.25, 1.0, density=3.0),
        sg.Ellipsoid((1.0, 0.7, 0.3), 2.0),
        sg.Ellipsoid(a=1.0, b=0.7, c=0.3, mass=2.0),
        sg.Disk(1.0, 2.0),
    ]
    pts = np.array([[1e4, 0, 0], [0, 1e4, 0], [0, 0, 1e4], [6e3, 0, 8e3]])
    for body in bodies:
        phi, _ = body.field(pts)
        # The quadrupole term is ~ (a/r)² = 1e-8 of the monopole.
        np.testing.assert_allclose(phi, -body.G * body.mass / 1e4, rtol=1e-7, err_msg=repr(body))


@pytest.mark.parametrize(
    "body, spec",
    [
        (sg.PointMass(1.5), "point:mass=1.5"),
        (sg.Sphere(1.0, density=2.0), "sphere:radius=1,density=2"),
        (sg.Spheroid(1.0, 0.25, 1.0), "spheroid:equatorial=1,polar=0.25,mass=1"),
        (sg.Ellipsoid((1.0, 0.7, 0.3), 2.0), "ellipsoid:a=1,b=0.7,c=0.3,mass=2"),
        (sg.Disk(1.0, 1.0), "disk:radius=1,mass=1"),
    ],
)
def test_field_matches_the_command_line_bit_for_bit(cli, body, spec):
    assert body.spec == spec
    pts = np.array([[0.3, -0.2, 0.1], [2.0, 1.0, -0.5], [0.0, 0.0, 3.0], [1.7, 0.0, 0.01]])
    phi, acc = body.field(pts)
    for i, p in enumerate(pts):
        out = cli.json("potential", "--body", spec, "--at", vec(p))
        assert phi[i] == out["potential"]
        assert list(acc[i]) == out["acceleration"]


def test_parallel_evaluation_equals_row_by_row():
    body = sg.Ellipsoid((1.0, 0.7, 0.3), 2.0)
    pts = np.random.default_rng(3).normal(size=(5000, 3)) * 3
    phi, acc = body.field(pts)
    for i in range(0, 5000, 499):
        p1, a1 = body.field(pts[i : i + 1])
        assert p1[0] == phi[i] and (a1[0] == acc[i]).all()
    # A non-contiguous view is read correctly.
    view = np.asfortranarray(pts)[::7]
    pv, _ = body.field(view)
    assert (pv == phi[::7]).all()


@pytest.mark.parametrize(
    "make, spec",
    [
        (lambda: sg.Sphere(-1.0, 1.0), "sphere:radius=-1,mass=1"),
        (lambda: sg.Spheroid(1.0, -0.25, 1.0), "spheroid:equatorial=1,polar=-0.25,mass=1"),
        (lambda: sg.Ellipsoid((1.0, 0.0, 1.0), 1.0), "ellipsoid:a=1,b=0,c=1,mass=1"),
        (lambda: sg.Disk(1.0, float("nan")), "disk:radius=1,mass=nan"),
        (lambda: sg.PointMass(0.0), "point:mass=0"),
        (lambda: sg.Sphere(1.0, 1e-320), "sphere:radius=1,mass=1e-320"),
    ],
)
def test_bad_bodies_raise_the_command_lines_message(cli, make, spec):
    with pytest.raises(sg.InputError) as info:
        make()
    assert isinstance(info.value, ValueError)
    assert str(info.value) == cli.error("potential", "--body", spec, "--at", "1,2,3")


def test_bad_constructor_combinations_raise_input_error():
    for make, words in [
        (lambda: sg.Sphere(1.0), "needs `mass`"),
        (lambda: sg.Sphere(1.0, 1.0, density=1.0), "not both"),
        (lambda: sg.Ellipsoid(a=1.0, b=1.0, mass=1.0), "needs `c`"),
        (lambda: sg.Ellipsoid((1.0, 1.0), 1.0), "three finite numbers"),
        (lambda: sg.Ellipsoid((1.0, 1.0, 1.0), 1.0, a=2.0), "not both"),
        (lambda: sg.Sphere(1.0, 1.0, G=-1.0), "gravitational"),
    ]:
        with pytest.raises(sg.InputError, match=words):
            make()
    with pytest.raises(TypeError):
        sg.Disk(1.0, 1.0, density=1.0)


def test_wrong_arrays_are_refused_clearly():
    body = sg.Sphere(1.0, 1.0)
    cases = [
        ([[1.0, 2.0, 3.0]], "numpy array of shape (N, 3) and dtype float64, got a list"),
        (np.zeros((4, 2)), "must have shape (N, 3), got shape (4, 2)"),
        (np.zeros(3), "must have shape (N, 3), got shape (3,)"),
        (np.zeros((2, 3, 1)), "got shape (2, 3, 1)"),
        (np.zeros((4, 3), dtype=np.int64), "must have dtype float64, got int64"),
        (np.zeros((4, 3), dtype=np.float32), "must have dtype float64, got float32"),
        (np.array([[1.0, np.nan, 0.0]]), "points[0] must be three finite numbers"),
        (np.array([[0.0, 0.0, 2.0], [np.inf, 0.0, 0.0]]), "points[1] must be three finite"),
    ]
    for points, words in cases:
        with pytest.raises(sg.InputError) as info:
            body.field(points)
        assert words in str(info.value)
    phi, acc = body.field(np.zeros((0, 3)))
    assert phi.shape == (0,) and acc.shape == (0, 3)


def test_infinite_fields_raise_instead_of_returning_nan(cli):
    with pytest.raises(sg.InputError, match="position of the point mass"):
        sg.PointMass(1.0).field(np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 0.0]]))
    with pytest.raises(sg.InputError) as info:
        sg.Disk(1.0, 1.0).field(np.array([[1.0, 0.0, 0.0]]))
    expected = cli.error("potential", "--body", "disk:radius=1,mass=1", "--at", "1,0,0")
    assert str(info.value) == expected.replace("--at 1,0,0", "points[0] = (1, 0, 0)")


def test_properties():
    s = sg.Spheroid(1.0, 0.25, density=2.0, G=2.0)
    assert s.equatorial_radius == 1.0 and s.polar_radius == 0.25 and s.G == 2.0
    assert s.mass == pytest.approx(4 / 3 * np.pi * 0.25 * 2.0, rel=1e-15)
    assert isinstance(s, sg.Body) and s.kind == "spheroid"
    np.testing.assert_allclose(np.diag(s.inertia()), s.mass / 5 * np.array([1.0625, 1.0625, 2.0]))
    assert sg.PointMass(1.0).inertia() is None and sg.PointMass(1.0).density is None
    assert sg.Ellipsoid(a=1.0, b=2.0, c=3.0, mass=1.0).semi_axes == (1.0, 2.0, 3.0)
    assert repr(sg.Disk(2.0, 3.0)) == "Disk(radius=2, mass=3)"


def test_the_gil_is_released_during_a_field_evaluation():
    body = sg.Ellipsoid((1.0, 0.7, 0.3), 1.0)
    pts = np.random.default_rng(0).normal(size=(2_000_000, 3))
    span = {}

    def work():
        span["start"] = time.perf_counter()
        body.field(pts)
        span["end"] = time.perf_counter()

    ticks = []
    worker = threading.Thread(target=work)
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
        time.sleep(0.001)
    worker.join()
    inside = [t for t in ticks if span["start"] < t < span["end"]]
    # With the GIL held this thread could not run until the call returned.
    assert span["end"] - span["start"] > 0.05
    assert len(inside) >= 10, (len(inside), span)


def test_a_rust_panic_is_an_exception_not_a_crash():
    from surfgrav import _surfgrav

    for _ in range(3):
        with pytest.raises(sg.InternalError, match="a deliberate panic for the tests"):
            _surfgrav._panic_for_tests()
    assert isinstance(sg.InternalError("x"), RuntimeError)
    # The interpreter and the module still work.
    phi, _ = sg.Sphere(1.0, 1.0).field(np.array([[2.0, 0.0, 0.0]]))
    assert phi[0] == -0.5
