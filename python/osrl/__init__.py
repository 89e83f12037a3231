"""osrl from Python: LWPR and robot dynamics on numpy arrays, and a MuJoCo adapter.

- ``osrl.Lwpr``: incremental Locally Weighted Projection Regression (the Rust crate ``lwpr``);
- ``osrl.Robot``: rigid-body dynamics of a built-in robot or a URDF (the crate ``osrl-dynamics``);
- ``osrl.LearnedController``, ``osrl.Learner``, ``osrl.train``: the learned operational space
  controller (the crate ``osrl-learn``), stepped from Python and trained on a Python robot;
- ``osrl.Trajectory``: the task-space path ``osrl.train`` follows, sampled in time;
- ``osrl.Measurement`` and ``osrl.RobotProtocol``: what a robot gives a learner (ROBOT_PROTOCOL.md);
- ``osrl.mujoco``: a MuJoCo model as such a robot, and the MuJoCo model of a built-in robot
  (imported on use: it needs the ``mujoco`` package).

See python/README.md.
"""

from ._osrl import (
    MAX_BATCH_VALUES,
    MAX_NORMALISED,
    LearnedController,
    Learner,
    Lwpr,
    NoSupportError,
    Robot,
    Trajectory,
    __version__,
    train,
)
from .protocol import Measurement, RobotProtocol

__all__ = [
    "LearnedController",
    "Learner",
    "Lwpr",
    "MAX_BATCH_VALUES",
    "MAX_NORMALISED",
    "Measurement",
    "NoSupportError",
    "Robot",
    "RobotProtocol",
    "Trajectory",
    "__version__",
    "train",
]
