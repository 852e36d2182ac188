"""Exact gravitational interactions of extended rigid bodies, and their two-body motion.

Bodies (``Sphere``, ``Spheroid``, ``Ellipsoid``, ``Disk``, ``PointMass``) evaluate their field
over an (N, 3) array of points; ``interact`` and ``interact_batch`` give the force, torques and
mutual energy of two bodies; ``Simulation`` integrates their motion; ``Scene`` runs a scene file
or preset exactly as the ``surfgrav`` command line does.

Conventions: the potential is negative (Φ → −GM/r far away), the acceleration is a = −∇Φ, the
mutual energy V is negative; an orientation takes the body frame to the world frame, given as a
rotation vector (axis × angle, radians) or a unit quaternion scalar first (w, x, y, z).

Bad input raises ``InputError`` (a ``ValueError``) with the command line's one-line message; a
run that starts and then fails raises ``RunError`` (a ``RuntimeError``).
"""

from ._surfgrav import (
    BatchInteraction,
    Body,
    Disk,
    Ellipsoid,
    InputError,
    Interaction,
    InternalError,
    PointMass,
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
]
