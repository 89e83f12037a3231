"""MuJoCo as a robot for osrl: ``MujocoRobot`` (the robot protocol of ROBOT_PROTOCOL.md over a
MuJoCo model with torque actuators) and the MuJoCo model of an osrl robot (``mjcf_from_urdf``,
``builtin_mjcf``, ``load_model``). Needs the ``mujoco`` package (``pip install osrl[mujoco]``)."""

from .mjcf import INERTIAL_PREFIX, builtin_mjcf, mjcf_from_urdf
from .model import load_model
from .robot import MujocoRobot

__all__ = ["INERTIAL_PREFIX", "MujocoRobot", "builtin_mjcf", "load_model", "mjcf_from_urdf"]
