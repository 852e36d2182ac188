"""Simulation: conservation, the command line's run, rotation, contact, output, bad input."""

import json

import numpy as np
import pytest

import surfgrav as sg


def paper_2s(integrator="rk4", **settings):
    body = sg.Spheroid(1.0, 0.25, mass=1.0)
    sim = sg.Simulation(integrator, **settings)
    sim.add(body, position=[-3.5, 0.0, 0.0], velocity=[0.0, 0.2, 0.0])
    sim.add(body, position=[3.5, 0.0, 0.0], velocity=[0.0, -0.2, 0.0])
    return sim


def test_paper_2s_conserves_energy_and_matches_the_command_line(cli, tmp_path):
    run = paper_2s(step=0.1).integrate(300.0)
    s = run.summary
    assert (s["steps"], s["force_evaluations"], len(run)) == (3000, 12001, 3001)
    assert s["motion_path"] == "translation" and s["model"] == "tabulated V(r)"
    assert s["termination"] == "completed" and s["event_time"] is None and s["t_end"] == 300.0
    drift = np.abs(run.energy / run.energy[0] - 1)
    assert drift.max() < 1e-7 and drift.max() > 0  # RK4 drifts, slightly
    j = run.angular_momentum
    assert np.abs(j[:, :2]).max() == 0.0  # the orbit stays in the x-y plane
    assert np.abs(j - j[0]).max() < 1e-7 * np.linalg.norm(j[0])
    assert run.positions.shape == (3001, 2, 3) and run.orientations.shape == (3001, 2, 4)
    np.testing.assert_array_equal(run.positions[:, 0], -run.positions[:, 1])

    done = cli.run("run", "paper-2s", "--out", tmp_path / "out", "--quiet")
    assert done.returncode == 0, done.stderr
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert (summary["steps"], summary["force_evaluations"]) == (3000, 12001)
    assert summary["energy"]["initial"] == run.energy[0]
    assert summary["angular_momentum"]["initial"] == pytest.approx(np.linalg.norm(j[0]), rel=1e-15)
    assert summary["energy"]["max_relative_drift"] == pytest.approx(drift.max(), rel=1e-9)
    assert summary["min_separation"] == pytest.approx(
        np.linalg.norm(run.positions[:, 1] - run.positions[:, 0], axis=1).min(), rel=1e-6
    )


@pytest.mark.parametrize(
    "integrator, settings, bound",
    [("yoshida6", dict(step=0.2), 1e-8), ("leapfrog", dict(step=0.05), 3e-4), ("dop853", dict(tolerance=1e-12), 1e-10)],
)
def test_other_integrators_conserve_energy(integrator, settings, bound):
    run = paper_2s(integrator, **settings).integrate(300.0)
    assert np.abs(run.energy / run.energy[0] - 1).max() < bound
    assert run.summary["integrator"] == integrator


def test_rotation_conserves_energy_and_angular_momentum():
    a = sg.Ellipsoid((1.0, 0.7, 0.4), 1.0)
    b = sg.Spheroid(1.0, 0.25, 1.0)
    sim = sg.Simulation("dop853", tolerance=1e-11)
    sim.add(a, position=[-3.0, 0, 0], velocity=[0, 0.25, 0.02], orientation=[0.3, 0.2, 0.1], angular_velocity=[0, 0, 0.4])
    sim.add(b, position=[3.0, 0, 0], velocity=[0, -0.25, -0.02], orientation=[0, 0.5, 0], angular_velocity=[0.1, 0, 0])
    run = sim.integrate(40.0, interval=0.5)
    assert run.summary["motion_path"] == "rotation" and run.summary["termination"] == "completed"
    assert run.summary["model"] == "direct surface integral"
    np.testing.assert_allclose(run.t, np.arange(81) * 0.5, rtol=0, atol=1e-12)
    assert np.abs(run.energy / run.energy[0] - 1).max() < 1e-8
    assert np.abs(run.angular_momentum - run.angular_momentum[0]).max() < 1e-8
    np.testing.assert_allclose(np.linalg.norm(run.orientations, axis=2), 1.0, rtol=1e-12)
    # The torques did something: A's spin changed by more than round-off.
    assert np.abs(run.angular_velocities[-1, 0] - [0, 0, 0.4]).max() > 1e-4
    # The simulation moved on to the end of the run.
    assert sim.t == 40.0
    np.testing.assert_array_equal(sim.positions, run.positions[-1])
    np.testing.assert_array_equal(sim.orientations, run.orientations[-1])


def test_integrate_continues_from_where_it_stopped():
    one = paper_2s(step=0.1)
    first = one.integrate(10.0)
    second = one.integrate(20.0)
    assert second.t[0] == 10.0 and second.t[-1] == 20.0
    np.testing.assert_array_equal(second.positions[0], first.positions[-1])
    whole = paper_2s(step=0.1).integrate(20.0)
    np.testing.assert_allclose(second.positions[-1], whole.positions[-1], rtol=0, atol=1e-12)


def test_point_masses_use_the_exact_model_and_a_quaternion_start():
    sim = sg.Simulation("yoshida8", step=0.05)
    sim.add(sg.PointMass(1.0), position=[-1.0, 0, 0], velocity=[0, -0.5, 0], orientation=[1.0, 0, 0, 0])
    sim.add(sg.PointMass(1.0), position=[1.0, 0, 0], velocity=[0, 0.5, 0])
    run = sim.integrate(2 * np.pi * 2 / np.sqrt(0.5))  # a few orbits
    assert run.summary["model"] == "point masses (exact)"
    assert np.abs(run.energy - run.energy[0]).max() < 1e-12


def test_contact_stops_the_run():
    sim = sg.Simulation("rk4", step=0.01)
    sim.add(sg.Sphere(1.0, 1.0), position=[-2.0, 0, 0])
    sim.add(sg.Sphere(1.0, 1.0), position=[2.0, 0, 0])
    run = sim.integrate(100.0)
    assert run.summary["termination"] == "contact"
    t = run.summary["event_time"]
    assert 0 < t < 100 and sim.t == t == run.t[-1]
    assert np.linalg.norm(sim.positions[1] - sim.positions[0]) == pytest.approx(2.0, rel=1e-9)


def test_bad_simulations_raise():
    body = sg.Sphere(1.0, 1.0)
    with pytest.raises(sg.InputError, match="unknown integrator 'rk45'; valid names: rk4, leapfrog"):
        sg.Simulation("rk45")
    with pytest.raises(sg.InputError, match="needs two bodies"):
        sg.Simulation(step=0.1).integrate(1.0)
    sim = sg.Simulation()
    sim.add(body, position=[-2.0, 0, 0])
    sim.add(body, position=[2.0, 0, 0])
    with pytest.raises(sg.InputError, match="holds two bodies"):
        sim.add(body)
    with pytest.raises(sg.InputError, match="the step of integrator 'rk4' must be positive"):
        sim.integrate(1.0)
    sim.integrator = "dop853"
    with pytest.raises(sg.InputError, match="the tolerance of integrator 'dop853'"):
        sim.integrate(1.0)
    sim.tolerance = 1e-10
    with pytest.raises(sg.InputError, match="t_end"):
        sim.integrate(-1.0)
    with pytest.raises(sg.InputError, match="unknown integrator"):
        sim.integrator = "euler"
    close = sg.Simulation(step=0.1)
    close.add(body, position=[0.0, 0, 0])
    close.add(body, position=[1.5, 0, 0])
    with pytest.raises(sg.InputError, match="overlap or touch at the start"):
        close.integrate(1.0)
    with pytest.raises(sg.InputError, match="velocity must be three finite numbers"):
        sg.Simulation().add(body, velocity=[0.0, np.nan, 0.0])
