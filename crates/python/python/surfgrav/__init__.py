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


def _run_sweep_task(scene_text: str, index: int) -> Dict[str, Any]:
    """Runs one sweep task: its scene's TOML text, as ``surfgrav sweep`` runs it.

    Module-level and taking plain data, so it pickles for process and Dask executors. Returns
    ``{"task", "status", <result columns>}`` (``status`` is ``done``, or ``failed`` with
    ``message``).
    """
    return _surfgrav._sweep_task(scene_text, index)


def sweep(
    sweep_file: Union[str, "os.PathLike[str]"],
    executor: Optional[Executor] = None,
    out: Optional[Union[str, "os.PathLike[str]"]] = None,
) -> List[Dict[str, Any]]:
    """Runs a sweep file's tasks through an executor and returns one dict per task.

    The sweep is expanded exactly as ``surfgrav sweep SWEEP.toml`` expands it (same tasks,
    same validation: bad input raises ``InputError`` with the command line's message, before
    anything runs). Each task's scene runs through ``executor.map`` — any
    ``concurrent.futures.Executor``: a Dask ``Client.get_executor()`` runs the sweep on a Dask
    cluster, a ``ProcessPoolExecutor`` on local processes. The default is a local
    ``ThreadPoolExecutor`` with one thread per core (runs release the GIL). Nothing is written
    per task (no task folders, trajectories or figures).

    Returns one dict per task, sorted by task index, with the columns of the command line's
    ``results.csv``: ``task``, ``status`` (``done`` or ``failed``), the varied fields by their
    dotted names, then ``mass_a``, ``mass_b``, ``t_reached``, ``steps``, ``min_separation``,
    ``energy_drift``, ``angular_momentum_drift``, ``angular_momentum_vector_drift``,
    ``precession_angle_deg``, ``final_spin_a``, ``final_spin_b``, ``termination``,
    ``contact_time``, ``escape_time``, ``wall_seconds`` and ``message`` (``None`` where the CSV
    cell is empty). A task whose run fails has ``status`` ``failed`` and the message; the
    other tasks still run.

    If ``out`` (a folder) is given, writes ``out/results.csv`` in the command line's format
    (every value but ``wall_seconds`` is the command line's, digit for digit).
    """
    path = os.fspath(sweep_file)
    fields, tasks = _surfgrav._sweep_plan(path)
    own = executor is None
    if own:
        executor = ThreadPoolExecutor(max_workers=os.cpu_count() or 1)
    try:
        outcomes = list(
            executor.map(
                _run_sweep_task,
                [scene_text for _, _, scene_text in tasks],
                [index for index, _, _ in tasks],
            )
        )
    finally:
        if own:
            executor.shutdown()
    rows = []
    for (index, parameters, _), outcome in zip(tasks, outcomes):
        row: Dict[str, Any] = {"task": index, "status": outcome["status"]}
        for field in fields:
            row[field] = parameters.get(field)
        for key, value in outcome.items():
            if key not in ("task", "status"):
                row[key] = value
        rows.append(row)
    if out is not None:
        folder = os.fspath(out)
        os.makedirs(folder, exist_ok=True)
        text = _surfgrav._sweep_csv(path, outcomes)
        target = os.path.join(folder, "results.csv")
        staging = os.path.join(folder, ".results.csv.tmp")
        with open(staging, "w", encoding="utf-8", newline="") as f:
            f.write(text)
        os.replace(staging, target)
    return rows
