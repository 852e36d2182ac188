"""surfgrav.sweep: the same tasks and results as `surfgrav sweep`, through any executor."""

import csv
import io
import json
import shutil
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import surfgrav as sg

SWEEP = """\
base = "paper-2s"
name = "py-grid"

[set]
t_end = 4.0

[[vary]]
field = "body_b.mass"
values = [0.5, 1.0]

[[vary]]
field = "body_b.angular_velocity[2]"
values = [0.0, 0.1]
"""


@pytest.fixture()
def sweep_file(tmp_path):
    path = tmp_path / "grid.toml"
    path.write_text(SWEEP)
    return path


def cli_results(cli, sweep_file, out):
    done = cli.run("sweep", sweep_file, "--out", out, "--quiet")
    assert done.returncode == 0, done.stderr
    return (out / "results.csv").read_text()


def without_wall_time(text):
    """results.csv's rows as lists of cells, the wall_seconds column blanked."""
    rows = list(csv.reader(io.StringIO(text)))
    column = rows[0].index("wall_seconds")
    for row in rows[1:]:
        assert row[column] == "" or float(row[column]) > 0
        row[column] = ""
    return rows


def comparable(result):
    """The result without the wall times, as plain lists (NaN made None so rows compare)."""
    return {
        k: [None if isinstance(x, float) and np.isnan(x) else x for x in v.tolist()]
        for k, v in result.items()
        if k != "wall_seconds"
    }


def test_default_executor_matches_the_command_line_row_for_row(cli, sweep_file, tmp_path):
    result = sg.sweep(sweep_file, out=tmp_path / "py")
    expected = cli_results(cli, sweep_file, tmp_path / "cli")
    # results.csv written from Python: the command line's, cell for cell (but the wall time).
    written = (tmp_path / "py" / "results.csv").read_text()
    assert without_wall_time(written) == without_wall_time(expected)
    # The returned columns: results.csv's, in its order, with the same numbers.
    table = list(csv.DictReader(io.StringIO(expected)))
    assert list(result.keys()) == list(table[0].keys())
    assert all(len(column) == len(table) == 4 for column in result.values())
    assert result["task"].dtype == np.int64 and result["steps"].dtype == np.int64
    assert result["energy_drift"].dtype == np.float64
    assert result["body_b.mass"].dtype == np.float64
    for k, line in enumerate(table):
        assert result["status"][k] == "done" and result["message"][k] is None
        assert result["wall_seconds"][k] > 0
        for key, cell in line.items():
            value = result[key][k]
            if key == "wall_seconds":
                continue
            if cell == "":
                assert value is None or np.isnan(value), (key, value)
            elif isinstance(value, str):
                assert value == cell
            else:
                assert value == type(value)(float(cell)), (key, value, cell)
    assert list(result["body_b.mass"]) == [0.5, 0.5, 1.0, 1.0]
    assert list(result["body_b.angular_velocity[2]"]) == [0.0, 0.1, 0.0, 0.1]
    # The folder is the command line's: every task folder and the manifest.
    for k in range(4):
        assert (tmp_path / "py" / "tasks" / f"{k:05}" / "summary.json").is_file()
    manifest = json.loads((tmp_path / "py" / "manifest.json").read_text())
    assert [t["status"] for t in manifest["tasks"]] == ["done"] * 4


def test_pandas_makes_the_table(sweep_file):
    pandas = pytest.importorskip("pandas", reason="pandas is not installed")
    result = sg.sweep(sweep_file)
    frame = pandas.DataFrame(result)
    assert list(frame.columns) == list(result.keys()) and len(frame) == 4
    assert frame["steps"].dtype == np.int64 and frame["min_separation"].dtype == np.float64
    assert (frame["termination"] == "completed").all()
    assert frame.loc[frame["body_b.mass"] == 1.0, "mass_b"].tolist() == [1.0, 1.0]


def test_a_rerun_skips_finished_tasks(cli, sweep_file, tmp_path):
    out = tmp_path / "out"
    first = sg.sweep(sweep_file, out=out)
    summaries = {k: out / "tasks" / f"{k:05}" / "summary.json" for k in range(4)}
    stamps = {k: p.stat().st_mtime_ns for k, p in summaries.items()}
    # Task 2 lost (an interrupted run leaves no finished folder): only it runs again.
    shutil.rmtree(out / "tasks" / "00002")
    second = sg.sweep(sweep_file, out=out)
    for k in (0, 1, 3):
        assert summaries[k].stat().st_mtime_ns == stamps[k], f"task {k} ran again"
    assert summaries[2].is_file()
    # Skipped tasks come back with their recorded results, wall times included.
    assert comparable(second) == comparable(first)
    assert [second["wall_seconds"][k] == first["wall_seconds"][k] for k in range(4)] == [
        True,
        True,
        False,
        True,
    ]
    # The command line resumes the folder Python wrote: nothing left to run.
    done = cli.run("sweep", sweep_file, "--out", out)
    assert done.returncode == 0, done.stderr
    assert "0 run now, 4 already done" in done.stdout
    # And Python resumes the command line's folder.
    cli_out = tmp_path / "cli"
    cli_results(cli, sweep_file, cli_out)
    stamp = (cli_out / "tasks" / "00001" / "summary.json").stat().st_mtime_ns
    assert comparable(sg.sweep(sweep_file, out=cli_out)) == comparable(first)
    assert (cli_out / "tasks" / "00001" / "summary.json").stat().st_mtime_ns == stamp


def test_a_folder_of_another_sweep_is_refused(cli, sweep_file, tmp_path):
    out = tmp_path / "out"
    sg.sweep(sweep_file, out=out)
    other = tmp_path / "other.toml"
    other.write_text(SWEEP.replace("t_end = 4.0", "t_end = 3.0"))
    message = cli.error("sweep", other, "--out", out, "--quiet")
    with pytest.raises(sg.InputError) as raised:
        sg.sweep(other, out=out)
    assert str(raised.value) == message and "belongs to another sweep" in message


def test_any_executor_gives_the_serial_result(sweep_file):
    with ThreadPoolExecutor(max_workers=1) as serial:
        expected = comparable(sg.sweep(sweep_file, executor=serial))
    with ThreadPoolExecutor(max_workers=3) as pool:
        assert comparable(sg.sweep(sweep_file, executor=pool)) == expected


def test_a_dask_cluster_gives_the_serial_result(sweep_file, tmp_path):
    pytest.importorskip("dask", reason="dask is not installed (pip install dask distributed)")
    distributed = pytest.importorskip(
        "distributed", reason="dask.distributed is not installed (pip install distributed)"
    )
    with ThreadPoolExecutor(max_workers=1) as serial:
        expected = sg.sweep(sweep_file, executor=serial, out=tmp_path / "serial")
    cluster = distributed.LocalCluster(
        n_workers=1, threads_per_worker=2, processes=False, dashboard_address=None
    )
    with cluster, distributed.Client(cluster) as client:
        result = sg.sweep(sweep_file, executor=client.get_executor(), out=tmp_path / "dask")
    assert comparable(result) == comparable(expected)
    assert without_wall_time((tmp_path / "dask" / "results.csv").read_text()) == without_wall_time(
        (tmp_path / "serial" / "results.csv").read_text()
    )


def test_the_task_function_takes_plain_data_and_pickles(sweep_file):
    import pickle

    from surfgrav import _run_sweep_task

    assert pickle.loads(pickle.dumps(_run_sweep_task)) is _run_sweep_task
    scene = sg.Scene.preset_toml("paper-2s").replace("t_end = 300.0", "t_end = 1.0")
    outcome = _run_sweep_task(scene, 7)
    assert outcome["task"] == 7 and outcome["status"] == "done"
    assert outcome["t_reached"] == pytest.approx(1.0)
    pickle.dumps(outcome)


@pytest.mark.parametrize(
    "text",
    [
        SWEEP.replace('field = "body_b.mass"', 'field = "body_b.mas"'),
        SWEEP.replace("values = [0.5, 1.0]", "values = []"),
        SWEEP + '\n[[vary]]\nfield = "t_end"\nnormal = [1.0, -1.0]\n',
    ],
    ids=["unknown-field", "empty-range", "bad-distribution"],
)
def test_a_bad_sweep_file_raises_the_command_lines_message(cli, tmp_path, text):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    message = cli.error("sweep", path, "--out", tmp_path / "cli", "--quiet")
    out = tmp_path / "py"
    with pytest.raises(sg.InputError) as raised:
        sg.sweep(path, out=out)
    assert str(raised.value) == message
    assert not out.exists()


def test_a_missing_sweep_file_raises_input_error(tmp_path):
    with pytest.raises(sg.InputError, match="cannot read the sweep file"):
        sg.sweep(tmp_path / "absent.toml")
