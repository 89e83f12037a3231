"""What a robot gives a learner, and what a learner may ask of it (ROBOT_PROTOCOL.md).

The protocol mirrors the Rust trait ``osrl_dynamics::Robot`` (crates/dynamics/src/sim.rs):
commands in, measurements out, and nothing else — a learner never reads the simulator's model.
Any Python object with these attributes and methods is a robot for osrl (``MujocoRobot`` is one;
a real robot's driver can be another).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol, Tuple, runtime_checkable

import numpy as np

__all__ = ["Measurement", "RobotProtocol"]


@dataclass(frozen=True)
class Measurement:
    """What a learner can measure on a robot at one instant (all arrays float64, owned).

    Task-space quantities are the task point's position on the robot's task axes.
    """

    t: float
    """Time since reset (s)."""
    q: np.ndarray
    """Joint positions (rad), shape ``(dof,)``."""
    qd: np.ndarray
    """Joint velocities (rad/s), shape ``(dof,)``."""
    x: np.ndarray
    """Task-space position (m), shape ``(task_dim,)``."""
    xd: np.ndarray
    """Task-space velocity (m/s), shape ``(task_dim,)``."""
    xdd: np.ndarray
    """Task-space acceleration (m/s²), shape ``(task_dim,)``: the instantaneous acceleration at
    this state under the command ``u`` still applied, without gravity (``J q̈ + J̇ q̇``)."""
    u: np.ndarray
    """The command being applied (N·m), after clipping to the torque limits, shape ``(dof,)``."""


@runtime_checkable
class RobotProtocol(Protocol):
    """A robot as a learner sees it (see ROBOT_PROTOCOL.md for the contract of each member)."""

    @property
    def dof(self) -> int:
        """Number of joints."""
        ...

    @property
    def task_dim(self) -> int:
        """Task-space dimension."""
        ...

    @property
    def control_period(self) -> float:
        """Control period (s): ``step`` holds a command this long."""
        ...

    @property
    def torque_limits(self) -> np.ndarray:
        """Torque limits per joint (N·m, inf for none), shape ``(dof,)``."""
        ...

    @property
    def joint_limits(self) -> Tuple[np.ndarray, np.ndarray]:
        """``(q_min, q_max)`` (rad, ∓inf for none), each of shape ``(dof,)``."""
        ...

    def measurement(self) -> Measurement:
        """The latest measurement."""
        ...

    def reset(self, q: np.ndarray | None = None, qd: np.ndarray | None = None) -> Measurement:
        """Puts the robot at ``(q, q̇)`` (defaults: its start posture, at rest) with zero command
        and time 0; returns the measurement there."""
        ...

    def step(self, u: np.ndarray) -> Measurement:
        """Applies ``u`` (N·m, clipped to the torque limits) for one control period; returns
        the new measurement. A wrong length or a non-finite ``u`` raises ``ValueError`` and
        changes nothing."""
        ...
