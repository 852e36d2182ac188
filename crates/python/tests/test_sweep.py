"""surfgrav.sweep: the same tasks and results as `surfgrav sweep`, through any executor."""

import csv
import io
from concurrent.futures import ThreadPoolExecutor

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


def comparable(rows):
    return [{k: v for k, v in row.items() if k != "wall_seconds"} for row in rows]


def test_default_executor_matches_the_command_line_row_for_row(cli, sweep_file, tmp_path):
    rows = sg.sweep(sweep_file, out=tmp_path / "py")
    expected = cli_results(cli, sweep_file, tmp_path / "cli")
    # results.csv written from Python: the command line's, cell for cell (but the wall time).
    written = (tmp_path / "py" / "results.csv").read_text()
    assert without_wall_time(written) == without_wall_time(expected)
    # The returned dicts: the same columns in the same order, the same numbers.
    table = list(csv.DictReader(io.StringIO(expected)))
    assert len(rows) == len(table) == 4
    assert list(rows[0].keys()) == list(table[0].keys())
    for row, line in zip(rows, table):
        assert row["status"] == "done" and row["message"] is None
        assert row["wall_seconds"] > 0
        for key, cell in line.items():
            value = row[key]
            if key == "wall_seconds":
                continue
            if value is None:
                assert cell == ""
            elif isinstance(value, str):
                assert value == cell
            else:
                assert value == type(value)(float(cell)), (key, value, cell)
    assert [r["body_b.mass"] for r in rows] == [0.5, 0.5, 1.0, 1.0]
    assert [r["body_b.angular_velocity[2]"] for r in rows] == [0.0, 0.1, 0.0, 0.1]


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
        rows = sg.sweep(sweep_file, executor=client.get_executor(), out=tmp_path / "dask")
    assert comparable(rows) == comparable(expected)
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
