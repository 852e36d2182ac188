"""Scene: the same results as `surfgrav run`, bit for bit; the same messages."""

import csv
import json

import numpy as np
import pytest

import surfgrav as sg


def cli_run(cli, scene, out, *extra):
    done = cli.run("run", scene, "--out", out, "--quiet", *extra)
    assert done.returncode == 0, done.stderr
    return json.loads((out / "summary.json").read_text())


def same_summary(python, command_line):
    python = dict(python)
    command_line = dict(command_line)
    assert python.pop("wall_seconds") > 0 and command_line.pop("wall_seconds") > 0
    assert python == command_line


@pytest.mark.parametrize("name", ["paper-2s", "paper-point", "paper-2s-prolate", "paper-2d"])
def test_presets_match_the_command_line_bit_for_bit(cli, tmp_path, name):
    run = sg.Scene.preset(name).run()
    summary = cli_run(cli, name, tmp_path / "out")
    same_summary(run.summary, summary)
    assert run.summary["steps"] > 0 and run.summary["precession_angle_deg"] is not None
    # The rows are trajectory.csv's.
    with open(tmp_path / "out" / "trajectory.csv") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == len(run) == summary["output"]["rows"]
    for i in (0, len(rows) // 2, len(rows) - 1):
        r = rows[i]
        assert float(r["t"]) == run.t[i]
        assert [float(r[k]) for k in ("xa", "ya", "za")] == list(run.positions[i, 0])
        assert [float(r[k]) for k in ("vxb", "vyb", "vzb")] == list(run.velocities[i, 1])
        assert float(r["energy"]) == run.energy[i]
        assert float(r["angular_momentum"]) == run.angular_momentum[i]
    assert len(run.step_times) == summary["steps"] + 1
    assert run.step_energy[0] == summary["energy"]["initial"]


def test_a_scene_file_matches_the_command_line(cli, tmp_path):
    text = sg.Scene.preset_toml("paper-2s")
    assert text == cli.run("presets", "--show", "paper-2s").stdout.rstrip("\n")
    text = text.replace('method = "rk4"', 'method = "dop853"').replace("step = 0.1", "tolerance = 1e-11")
    assert "\n[output]\n" in text
    text = text.replace("\n[output]\n", "\n[output]\ninterval = 0.5\n")
    path = tmp_path / "my.toml"
    path.write_text(text)
    scene = sg.Scene.load(str(path))
    assert scene.integrator == "dop853" and scene.name == "paper-2s"
    run = scene.run()
    same_summary(run.summary, cli_run(cli, str(path), tmp_path / "out"))
    np.testing.assert_allclose(np.diff(run.t)[:-1], 0.5, rtol=1e-12)
    # Scene.parse of the same text, and a pathlib.Path, give the same scene.
    assert sg.Scene.parse(text, "my.toml").run().summary["steps"] == run.summary["steps"]
    assert sg.Scene.load(path).t_end == 300.0


def test_overrides_match_the_command_lines(cli, tmp_path):
    scene = sg.Scene.preset("paper-2s").with_overrides(t_end=120.0, dt=0.05, integrator="YOSHIDA4")
    assert scene.t_end == 120.0 and scene.integrator == "yoshida4"
    summary = cli_run(cli, "paper-2s", tmp_path / "out", "--t-end", "120", "--dt", "0.05", "--integrator", "YOSHIDA4")
    same_summary(scene.run().summary, summary)


def test_bad_scenes_raise_the_command_lines_messages(cli, tmp_path):
    bad = sg.Scene.preset_toml("paper-2s").replace("polar_radius = 0.25", "polar_radius = -0.25", 1)
    path = tmp_path / "bad.toml"
    path.write_text(bad)
    with pytest.raises(sg.InputError) as info:
        sg.Scene.load(str(path))
    assert str(info.value) == cli.error("run", str(path), "--out", tmp_path / "never")
    assert "polar_radius" in str(info.value)
    assert not (tmp_path / "never").exists()

    overlapping = sg.Scene.preset_toml("paper-2s").replace("[-3.5, 0.0, 0.0]", "[-0.5, 0.0, 0.0]").replace("[3.5, 0.0, 0.0]", "[0.5, 0.0, 0.0]")
    path.write_text(overlapping)
    with pytest.raises(sg.InputError) as info:
        sg.Scene.load(str(path)).run()
    assert str(info.value) == cli.error("run", str(path), "--out", tmp_path / "never")

    with pytest.raises(sg.InputError) as info:
        sg.Scene.preset("paper-9")
    assert str(info.value) == cli.error("presets", "--show", "paper-9")
    with pytest.raises(sg.InputError, match="cannot read the scene file"):
        sg.Scene.load(str(tmp_path / "missing.toml"))
    with pytest.raises(sg.InputError) as info:
        sg.Scene.preset("paper-2s").with_overrides(dt=-1.0)
    expected = cli.error("run", "paper-2s", "--dt", "-1", "--out", tmp_path / "never")
    assert str(info.value) == expected.replace("--dt", "dt")
    with pytest.raises(sg.InputError, match="unknown integrator"):
        sg.Scene.preset("paper-2s").with_overrides(integrator="euler")


def test_presets_list():
    names = sg.Scene.presets()
    assert "paper-2s" in names and "paper-2d" in names
    assert sg.Scene.preset("paper-2d").bodies == ("disk:radius=1,mass=1", "disk:radius=1,mass=1")
