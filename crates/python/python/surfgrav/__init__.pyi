"""Type stubs of the surfgrav package (the compiled module surfgrav._surfgrav)."""

import os
from concurrent.futures import Executor
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

FloatArray = npt.NDArray[np.float64]
#: Three numbers (a tuple, list or (3,) float64 array).
Vector = Union[Sequence[float], FloatArray]
#: A rotation vector (3 numbers, axis × angle in radians) or a unit quaternion (w, x, y, z).
Orientation = Union[Sequence[float], FloatArray]

class InputError(ValueError):
    """Bad input; the message is the command line's one-line message."""

class RunError(RuntimeError):
    """A run that started and then failed."""

class InternalError(RuntimeError):
    """A bug in surfgrav (a Rust panic, caught)."""

class Body:
    """A homogeneous body (build a Sphere, Spheroid, Ellipsoid, Disk, PointMass or Polyhedron)."""

    @property
    def mass(self) -> float: ...
    @property
    def G(self) -> float: ...
    @property
    def density(self) -> Optional[float]: ...
    @property
    def volume(self) -> float: ...
    @property
    def bounding_radius(self) -> float: ...
    @property
    def kind(self) -> str: ...
    @property
    def spec(self) -> Optional[str]:
        """The command line's body spec; None for a Polyhedron."""
    def field(self, points: FloatArray) -> Tuple[FloatArray, FloatArray]:
        """Φ (N,) and a = −∇Φ (N, 3) at an (N, 3) float64 array of body-frame points."""
    def inertia(self) -> Optional[FloatArray]:
        """The (3, 3) inertia tensor about the centroid, body frame; None for a point mass."""

class PointMass(Body):
    def __init__(self, mass: float, *, G: float = 1.0) -> None: ...

class Sphere(Body):
    def __init__(
        self,
        radius: float,
        mass: Optional[float] = None,
        *,
        density: Optional[float] = None,
        G: float = 1.0,
    ) -> None: ...
    @property
    def radius(self) -> float: ...

class Spheroid(Body):
    def __init__(
        self,
        equatorial_radius: float,
        polar_radius: float,
        mass: Optional[float] = None,
        *,
        density: Optional[float] = None,
        G: float = 1.0,
    ) -> None: ...
    @property
    def equatorial_radius(self) -> float: ...
    @property
    def polar_radius(self) -> float: ...

class Ellipsoid(Body):
    def __init__(
        self,
        semi_axes: Optional[Vector] = None,
        mass: Optional[float] = None,
        *,
        a: Optional[float] = None,
        b: Optional[float] = None,
        c: Optional[float] = None,
        density: Optional[float] = None,
        G: float = 1.0,
    ) -> None: ...
    @property
    def semi_axes(self) -> Tuple[float, float, float]: ...

class Disk(Body):
    def __init__(self, radius: float, mass: float, *, G: float = 1.0) -> None: ...
    @property
    def radius(self) -> float: ...

PathLike = Union[str, "os.PathLike[str]"]
IntArray = npt.NDArray[np.integer[Any]]

class Polyhedron(Body):
    """A homogeneous polyhedron (closed triangle mesh; Werner & Scheeres 1997). Coordinates in
    `units` ("m" or "km") are converted to metres; the mesh is validated (a bad one raises
    InputError naming the face, edge or vertex). The body frame has its origin at the mesh's
    centroid (`centroid`, subtracted from every vertex) and the mesh's axes."""

    def __init__(
        self,
        vertices: FloatArray,
        faces: IntArray,
        mass: Optional[float] = None,
        *,
        density: Optional[float] = None,
        units: str = "m",
        G: float = 1.0,
    ) -> None:
        """`vertices` (N, 3) float64; `faces` (M, 3) integer, 0-based vertex indices,
        counter-clockwise seen from outside. Give mass or density."""
    @staticmethod
    def from_obj(
        path: PathLike,
        mass: Optional[float] = None,
        *,
        density: Optional[float] = None,
        units: str = "m",
        G: float = 1.0,
    ) -> "Polyhedron":
        """Reads a Wavefront OBJ file (`v` and `f` lines, triangles)."""
    @staticmethod
    def from_csv(
        vertex_file: PathLike,
        facet_file: PathLike,
        mass: Optional[float] = None,
        *,
        density: Optional[float] = None,
        units: str = "m",
        G: float = 1.0,
    ) -> "Polyhedron":
        """Reads a vertex/facet CSV pair (`filler,x,y,z`; 1-based `i,j,k,,`), as the Didymos
        radar model is distributed."""
    @property
    def vertices(self) -> FloatArray:
        """(N, 3) vertices in the body frame (centroid at the origin), metres."""
    @property
    def faces(self) -> npt.NDArray[np.int64]:
        """(M, 3) 0-based vertex indices, counter-clockwise seen from outside."""
    @property
    def centroid(self) -> FloatArray:
        """(3,) the input mesh's centroid in its own frame (metres)."""
    @property
    def units(self) -> str: ...
    @property
    def source(self) -> str:
        """"arrays", the OBJ file, or "VERTICES + FACETS"."""

class Interaction:
    """Force, torques (about each centroid) and mutual energy; world frame."""

    @property
    def force_on_a(self) -> FloatArray: ...
    @property
    def force_on_b(self) -> FloatArray: ...
    @property
    def torque_on_a(self) -> FloatArray: ...
    @property
    def torque_on_b(self) -> FloatArray: ...
    @property
    def potential_energy(self) -> float: ...
    @property
    def method(self) -> str: ...
    @property
    def evaluations(self) -> int: ...
    @property
    def error_estimate(self) -> float: ...
    def to_dict(self) -> dict:
        """The keys and values of `surfgrav interact`'s JSON."""

class BatchInteraction:
    """One row per pose: (N, 3) forces and torques, (N,) energies, evaluations, errors."""

    @property
    def force_on_a(self) -> FloatArray: ...
    @property
    def force_on_b(self) -> FloatArray: ...
    @property
    def torque_on_a(self) -> FloatArray: ...
    @property
    def torque_on_b(self) -> FloatArray: ...
    @property
    def potential_energy(self) -> FloatArray: ...
    @property
    def evaluations(self) -> npt.NDArray[np.int64]: ...
    @property
    def error_estimate(self) -> FloatArray: ...
    @property
    def method(self) -> Tuple[str, ...]: ...
    def __len__(self) -> int: ...

def interact(
    a: Body,
    b: Body,
    position: Vector,
    orientation_a: Optional[Orientation] = None,
    orientation_b: Optional[Orientation] = None,
    tolerance: float = 1e-12,
) -> Interaction:
    """A at the origin, B at `position`; orientations body → world."""

def interact_batch(
    a: Body,
    b: Body,
    positions: FloatArray,
    orientations_a: Optional[Union[Orientation, FloatArray]] = None,
    orientations_b: Optional[Union[Orientation, FloatArray]] = None,
    tolerance: float = 1e-12,
) -> BatchInteraction:
    """interact for an (N, 3) array of positions, with (N, 3)/(N, 4) or shared orientations."""

class Trajectory:
    """Rows of a Simulation.integrate run."""

    @property
    def t(self) -> FloatArray: ...
    @property
    def positions(self) -> FloatArray:
        """(M, 2, 3) centroid positions of A and B."""
    @property
    def velocities(self) -> FloatArray: ...
    @property
    def orientations(self) -> FloatArray:
        """(M, 2, 4) unit quaternions, scalar first, body → world."""
    @property
    def angular_velocities(self) -> FloatArray: ...
    @property
    def energy(self) -> FloatArray: ...
    @property
    def angular_momentum(self) -> FloatArray:
        """(M, 3) total angular momentum about the origin, orbital and spin."""
    @property
    def summary(self) -> dict:
        """steps, rejected_steps, force_evaluations, motion_path ("translation" or "rotation"),
        motion_reason, model, integrator, termination ("completed", "contact", "escape"),
        event_time, t_start, t_end, wall_seconds."""
    def __len__(self) -> int: ...

class Simulation:
    """Two bodies, their states and an integrator chosen by name."""

    t: float
    integrator: str
    step: Optional[float]
    tolerance: Optional[float]
    interaction_tolerance: float
    tabulate: bool
    escape_distance: Optional[float]
    def __init__(
        self,
        integrator: str = "rk4",
        step: Optional[float] = None,
        tolerance: Optional[float] = None,
        t: float = 0.0,
        interaction_tolerance: float = 1e-12,
        tabulate: bool = True,
        escape_distance: Optional[float] = None,
    ) -> None: ...
    @property
    def N(self) -> int: ...
    @property
    def bodies(self) -> Tuple[Body, ...]: ...
    @property
    def positions(self) -> FloatArray: ...
    @property
    def velocities(self) -> FloatArray: ...
    @property
    def orientations(self) -> FloatArray: ...
    @property
    def angular_velocities(self) -> FloatArray: ...
    def add(
        self,
        body: Body,
        position: Optional[Vector] = None,
        velocity: Optional[Vector] = None,
        orientation: Optional[Orientation] = None,
        angular_velocity: Optional[Vector] = None,
    ) -> None: ...
    def integrate(self, t_end: float, interval: Optional[float] = None) -> Trajectory: ...

class SceneRun:
    """Scene.run's result: the CLI's summary.json, trajectory.csv's rows, per-step E and |J|."""

    @property
    def summary(self) -> dict: ...
    @property
    def method(self) -> str: ...
    @property
    def t(self) -> FloatArray: ...
    @property
    def positions(self) -> FloatArray: ...
    @property
    def velocities(self) -> FloatArray: ...
    @property
    def orientations(self) -> FloatArray: ...
    @property
    def angular_velocities(self) -> FloatArray: ...
    @property
    def energy(self) -> FloatArray: ...
    @property
    def angular_momentum(self) -> FloatArray:
        """|J| about the origin per row, as in trajectory.csv."""
    @property
    def step_times(self) -> FloatArray: ...
    @property
    def step_energy(self) -> FloatArray: ...
    @property
    def step_angular_momentum(self) -> FloatArray: ...
    def __len__(self) -> int: ...

class Scene:
    """A validated scene file or preset, run as `surfgrav run` runs it."""

    @staticmethod
    def load(path: Union[str, "os.PathLike[str]"]) -> Scene: ...
    @staticmethod
    def preset(name: str) -> Scene: ...
    @staticmethod
    def parse(text: str, name: str = "<string>") -> Scene: ...
    @staticmethod
    def presets() -> List[str]: ...
    @staticmethod
    def preset_toml(name: str) -> str: ...
    def with_overrides(
        self,
        t_end: Optional[float] = None,
        dt: Optional[float] = None,
        integrator: Optional[str] = None,
        tolerance: Optional[float] = None,
    ) -> Scene: ...
    @property
    def name(self) -> str: ...
    @property
    def t_start(self) -> float: ...
    @property
    def t_end(self) -> float: ...
    @property
    def integrator(self) -> str: ...
    @property
    def G(self) -> float: ...
    @property
    def bodies(self) -> Tuple[str, str]: ...
    def run(self) -> SceneRun: ...

def sweep(
    sweep_file: Union[str, os.PathLike[str]],
    executor: Optional[Executor] = None,
    out: Optional[Union[str, os.PathLike[str]]] = None,
) -> Dict[str, npt.NDArray[Any]]:
    """Runs a sweep file's tasks (expanded as `surfgrav sweep` does) through `executor.map`
    (default: a local ThreadPoolExecutor; a Dask `Client.get_executor()` for a cluster).
    Returns results.csv's columns as numpy arrays, one row per task (`pandas.DataFrame(result)`
    makes the table): task, status, the varied fields, mass_a, ..., steps (int64, -1 if
    failed), ..., wall_seconds (float64, NaN where empty), message. With `out`, writes the
    folder as `surfgrav sweep --out` does (task folders, manifest.json, results.csv) and
    resumes it: finished tasks are skipped and read back."""
