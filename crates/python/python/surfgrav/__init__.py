"""Exact gravitational interactions of extended rigid bodies, and their two-body motion.

Bodies (``Sphere``, ``Spheroid``, ``Ellipsoid``, ``Disk``, ``PointMass``, ``Polyhedron``)
evaluate their field over an (N, 3) array of points; ``interact`` and ``interact_batch`` give the force, torques and
mutual energy of two bodies; ``Simulation`` integrates their motion; ``Scene`` runs a scene file
or preset exactly as the ``surfgrav`` command line does; ``sweep`` runs a sweep file's tasks
through any ``concurrent.futures.Executor`` (a Dask ``Client.get_executor()`` for a cluster).

Conventions: the potential is negative (Φ → −GM/r far away), the acceleration is a = −∇Φ, the
mutual energy V is negative; an orientation takes the body frame to the world frame, given as a
rotation vector (axis × angle, radians) or a unit quaternion scalar first (w, x, y, z).

Bad input raises ``InputError`` (a ``ValueError``) with the command line's one-line message; a
run that starts and then fails raises ``RunError`` (a ``RuntimeError``).
"""

import os
from concurrent.futures import Executor, ThreadPoolExecutor
from typing import Any, Dict, List, Optional, Union

import numpy as np

from . import _surfgrav
from ._surfgrav import (
    BatchInteraction,
    Body,
    Disk,
    Ellipsoid,
    InputError,
    Interaction,
    InternalError,
    PointMass,
    Polyhedron,
    RunError,
    Scene,
    SceneRun,
    Simulation,
    Sphere,
    Spheroid,
    Trajectory,
    __version__,
    interact,
    interact_batch,
)

__all__ = [
    "BatchInteraction",
    "Body",
    "Disk",
    "Ellipsoid",
    "InputError",
    "Interaction",
    "InternalError",
    "PointMass",
    "Polyhedron",
    "RunError",
    "Scene",
    "SceneRun",
    "Simulation",
    "Sphere",
    "Spheroid",
    "Trajectory",
    "__version__",
    "interact",
    "interact_batch",
    "sweep",
]


def _run_sweep_task(
    scene_text: str,
    index: int,
    out: Optional[str] = None,
    parameters: Optional[str] = None,
    trajectory: bool = False,
    figures: bool = False,
) -> Dict[str, Any]:
    """Runs one sweep task: its scene's TOML text, as ``surfgrav sweep`` runs it.

    Module-level and taking plain data, so it pickles for process and Dask executors. With
    ``out`` (a folder reachable from where the task runs) the task writes its folder
    ``out/tasks/NNNNN`` as the command line does; ``parameters`` is the task's parameters as
    TOML. Returns ``{"task", "status", <result columns>}`` (``status`` is ``done``, or
    ``failed`` with ``message``).
    """
    return _surfgrav._sweep_task(scene_text, index, out, parameters, trajectory, figures)


def _column(values: List[Any]) -> "np.ndarray":
    """One column as a numpy array: int64 if every value is an int (a missing one is -1),
    float64 if every value is a number (a missing one is NaN), else an object array."""
    present = [v for v in values if v is not None]
    if present and all(isinstance(v, int) and not isinstance(v, bool) for v in present):
        return np.array([-1 if v is None else v for v in values], dtype=np.int64)
    if present and all(
        isinstance(v, (int, float)) and not isinstance(v, bool) for v in present
    ):
        return np.array([np.nan if v is None else v for v in values], dtype=np.float64)
    column = np.empty(len(values), dtype=object)
    for k, v in enumerate(values):
        column[k] = tuple(v) if isinstance(v, list) else v
    return column


def sweep(
    sweep_file: Union[str, "os.PathLike[str]"],
    executor: Optional[Executor] = None,
    out: Optional[Union[str, "os.PathLike[str]"]] = None,
) -> Dict[str, "np.ndarray"]:
    """Runs a sweep file's tasks through an executor; returns the results as a dict of numpy
    columns (``pandas.DataFrame(result)`` makes the table).

    The sweep is expanded exactly as ``surfgrav sweep SWEEP.toml`` expands it (same tasks,
    same validation: bad input raises ``InputError`` with the command line's message, before
    anything runs). Each task's scene runs through ``executor.map`` — any
    ``concurrent.futures.Executor``: a Dask ``Client.get_executor()`` runs the sweep on a Dask
    cluster, a ``ProcessPoolExecutor`` on local processes. The default is a local
    ``ThreadPoolExecutor`` with one thread per core (runs release the GIL).

    Without ``out`` nothing is written. With ``out`` (a folder) the sweep is written as
    ``surfgrav sweep SWEEP.toml --out OUT`` writes it — ``tasks/NNNNN/`` per task (its scene,
    summary, key results, and the trajectory and figures if the sweep asks), ``manifest.json``
    and ``results.csv`` — and it resumes: a re-run into the same folder (from Python or the
    command line) skips the finished tasks and reads their results back. Tasks write their
    folders where they run, so ``out`` must be on a filesystem the workers share.

    The result has one entry per column of the command line's ``results.csv``, in its order,
    each an array with one row per task sorted by task index: ``task`` (int64), ``status``
    (``done`` or ``failed``), the varied fields by their dotted names (float64 or int64 for
    numbers, object arrays of tuples for vectors and of str for text), then ``mass_a``,
    ``mass_b``, ``t_reached``, ``steps`` (int64; -1 for a failed task), ``min_separation``,
    ``energy_drift``, ``angular_momentum_drift``, ``angular_momentum_vector_drift``,
    ``precession_angle_deg``, ``final_spin_a``, ``final_spin_b`` (float64; NaN where the CSV
    cell is empty), ``termination`` (object: ``completed``, ``contact``, ``escape`` or None),
    ``contact_time``, ``escape_time``, ``wall_seconds`` (float64, NaN when absent) and
    ``message`` (object: None, or why the task failed). A task whose run fails has ``status``
    ``failed``; the other tasks still run.
    """
    path = os.fspath(sweep_file)
    plan = _surfgrav._sweep_plan(path)
    tasks = plan["tasks"]
    folder = None if out is None else os.fspath(out)
    finished: Dict[int, Dict[str, Any]] = {}
    if folder is not None:
        finished = {d["task"]: d for d in _surfgrav._sweep_open(path, folder)}
    pending = [t for t in tasks if t[0] not in finished]
    outcomes: List[Dict[str, Any]] = []
    if pending:
        own = executor is None
        if own:
            executor = ThreadPoolExecutor(max_workers=os.cpu_count() or 1)
        assert executor is not None
        n = len(pending)
        try:
            outcomes = list(
                executor.map(
                    _run_sweep_task,
                    [scene_text for _, _, scene_text, _ in pending],
                    [index for index, _, _, _ in pending],
                    [folder] * n,
                    [toml for _, _, _, toml in pending],
                    [plan["trajectory"]] * n,
                    [plan["figures"]] * n,
                )
            )
        finally:
            if own:
                executor.shutdown()
    if folder is not None:
        _surfgrav._sweep_finish(path, folder, outcomes)
    by_index = dict(finished)
    by_index.update((o["task"], o) for o in outcomes)
    rows = [(parameters, by_index[index]) for index, parameters, _, _ in tasks]
    result: Dict[str, np.ndarray] = {
        "task": np.array([o["task"] for _, o in rows], dtype=np.int64),
        "status": _column([o["status"] for _, o in rows]),
    }
    for field in plan["fields"]:
        result[field] = _column([parameters.get(field) for parameters, _ in rows])
    for column in plan["columns"]:
        values = [o[column] for _, o in rows]
        if column == "steps":
            result[column] = np.array([-1 if v is None else v for v in values], dtype=np.int64)
        elif column in ("termination", "message"):
            result[column] = np.array(values, dtype=object)
        else:
            result[column] = np.array(
                [np.nan if v is None else v for v in values], dtype=np.float64
            )
    return result
