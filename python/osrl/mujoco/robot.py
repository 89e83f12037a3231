"""``MujocoRobot``: a MuJoCo model with one torque motor per joint, as the robot of
ROBOT_PROTOCOL.md.

One step holds the command for the control period (``substeps`` MuJoCo steps). Measurements
come from MuJoCo's state alone: ``q``, ``q̇`` are ``qpos``, ``qvel``; ``x``, ``ẋ`` are the task
point's position and ``J q̇`` on the task axes; ``ẍ = J q̈ + J̇ q̇`` with ``q̈`` MuJoCo's own
acceleration at the new state under the command still applied (``mj_forward`` after the steps,
constraint forces included) and ``J̇`` from ``mj_jacDot``: the instantaneous acceleration, as
osrl's simulator measures it, not a finite difference over the period.
"""

from __future__ import annotations

from typing import Optional, Sequence, Tuple, Union

import mujoco
import numpy as np

from ..protocol import Measurement
from .model import load_model

__all__ = ["MujocoRobot"]

_OBJ = mujoco.mjtObj


def _checked(what: str, v, n: int) -> np.ndarray:
    """``v`` as a new float64 vector of length ``n`` with finite entries, else ``ValueError``."""
    a = np.array(v, dtype=np.float64, copy=True) if not isinstance(v, np.ndarray) else v
    if a.dtype != np.float64:
        raise ValueError(f"{what}: expected float64 values, got dtype {a.dtype}")
    if a.shape != (n,):
        raise ValueError(f"{what}: expected shape ({n},), got {a.shape}")
    bad = np.flatnonzero(~np.isfinite(a))
    if bad.size:
        raise ValueError(f"{what}[{bad[0]}] is not finite ({a[bad[0]]}); nothing was changed")
    return a.copy()


def _motor_gains(m: "mujoco.MjModel") -> Tuple[np.ndarray, np.ndarray]:
    """Per joint (dof order): the actuator driving it and the torque per unit of control.
    Raises ``ValueError`` unless every joint is a hinge or slide with exactly one motor."""
    if not (m.nq == m.nv == m.njnt) or np.any((m.jnt_type != mujoco.mjtJoint.mjJNT_HINGE)
                                            & (m.jnt_type != mujoco.mjtJoint.mjJNT_SLIDE)):
        raise ValueError("MujocoRobot needs a chain of hinge or slide joints (nq = nv = njnt)")
    act = np.full(m.nv, -1)
    gain = np.zeros(m.nv)
    for a in range(m.nu):
        motor = (m.actuator_trntype[a] == mujoco.mjtTrn.mjTRN_JOINT
                 and m.actuator_dyntype[a] == mujoco.mjtDyn.mjDYN_NONE
                 and m.actuator_gaintype[a] == mujoco.mjtGain.mjGAIN_FIXED
                 and m.actuator_biastype[a] == mujoco.mjtBias.mjBIAS_NONE)
        if not motor:
            raise ValueError(f"actuator {a} is not a motor on a joint (MJCF <motor joint=...>)")
        dof = m.jnt_dofadr[m.actuator_trnid[a, 0]]
        if act[dof] >= 0:
            raise ValueError(f"joint {dof} has two motors")
        act[dof], gain[dof] = a, m.actuator_gear[a, 0] * m.actuator_gainprm[a, 0]
    if np.any(act < 0) or np.any(gain == 0):
        raise ValueError("every joint needs one motor with a non-zero gear")
    return act, gain


def _torque_limits(m: "mujoco.MjModel", act: np.ndarray, gain: np.ndarray) -> np.ndarray:
    """The largest torque each joint's motor can apply (inf: unlimited); symmetric ranges only."""
    lim = np.full(m.nv, np.inf)
    for dof, a in enumerate(act):
        if m.actuator_ctrllimited[a]:
            lo, hi = m.actuator_ctrlrange[a]
            if lo != -hi:
                raise ValueError(f"actuator {a}: ctrlrange [{lo}, {hi}] is not symmetric")
            lim[dof] = abs(hi * gain[dof])
        if m.actuator_forcelimited[a]:
            lo, hi = m.actuator_forcerange[a]
            lim[dof] = min(lim[dof], -lo, hi)
    return lim


class MujocoRobot:
    """A MuJoCo model as an osrl robot (``osrl.RobotProtocol``).

    ``model``: an ``MjModel``, or MJCF text (compiled by ``osrl.mujoco.load_model``), with one
    ``motor`` per hinge joint; ``site`` or ``body``: the task point (a site, or a body's frame
    origin); ``task_axes``: the world axes of the task space; ``control_period``: seconds a
    command is held (a whole number of ``model.opt.timestep``; default one step); ``q_start``:
    the posture of ``reset()`` (default ``model.qpos0``). Raises ``ValueError`` on a model
    without that structure or bad arguments.
    """

    def __init__(self, model: Union["mujoco.MjModel", str], *, site: Optional[str] = None,
                 body: Optional[str] = None, task_axes: Sequence[int] = (0, 1, 2),
                 control_period: Optional[float] = None, q_start=None):
        m = load_model(model) if isinstance(model, str) else model
        if (site is None) == (body is None):
            raise ValueError("give the task point as exactly one of site= and body=")
        kind, name = (_OBJ.mjOBJ_SITE, site) if site is not None else (_OBJ.mjOBJ_BODY, body)
        self._point = mujoco.mj_name2id(m, kind, name)
        if self._point < 0:
            raise ValueError(f"the model has no {'site' if site is not None else 'body'} {name!r}")
        self._is_site = site is not None
        axes = [int(a) for a in task_axes]
        if not axes or len(set(axes)) != len(axes) or any(a not in (0, 1, 2) for a in axes):
            raise ValueError(f"task_axes {list(task_axes)}: distinct values among 0, 1, 2")
        self._axes = np.array(axes)
        period = m.opt.timestep if control_period is None else float(control_period)
        substeps = int(round(period / m.opt.timestep))
        if not (np.isfinite(period) and substeps >= 1
                and abs(substeps * m.opt.timestep - period) <= 1e-9 * period):
            raise ValueError(f"control_period {period} s is not a whole number of MuJoCo steps "
                             f"({m.opt.timestep} s)")
        self._act, self._gain = _motor_gains(m)
        self._tau_max = _torque_limits(m, self._act, self._gain)
        lo = np.where(m.jnt_limited, m.jnt_range[:, 0], -np.inf)
        hi = np.where(m.jnt_limited, m.jnt_range[:, 1], np.inf)
        self._limits = (lo[m.dof_jntid].copy(), hi[m.dof_jntid].copy())
        self.model, self.data = m, mujoco.MjData(m)
        self._period, self._substeps = period, substeps
        q0 = m.qpos0 if q_start is None else q_start
        self._q_start = _checked("q_start", q0, m.nq)
        self._jac = np.zeros((3, m.nv))
        self._jacdot = np.zeros((3, m.nv))
        self._u = np.zeros(m.nv)
        self._meas = self.reset()

    @classmethod
    def builtin(cls, name: str, *, control_period: float = 0.002, timestep: float = 0.001,
                joint_limits: bool = True) -> "MujocoRobot":
        """A built-in osrl robot simulated by MuJoCo: the model of ``builtin_mjcf(name)``
        (RK4 steps of ``timestep``), the task point ``ee_link``, osrl's task axes and start
        posture. osrl's own simulator defaults to the same period and step. Its ``osrl_name``
        is ``name`` (``osrl.train`` evaluates on osrl's model of that name)."""
        from .. import Robot
        from .mjcf import builtin_mjcf

        r = Robot.builtin(name)
        xml = builtin_mjcf(name, timestep=timestep, joint_limits=joint_limits)
        robot = cls(load_model(xml), site="ee_link", task_axes=r.task_axes,
                    control_period=control_period, q_start=r.q_start)
        robot.osrl_name = name
        return robot

    @property
    def dof(self) -> int:
        return int(self.model.nv)

    @property
    def task_dim(self) -> int:
        return len(self._axes)

    @property
    def control_period(self) -> float:
        return self._period

    @property
    def substeps(self) -> int:
        """MuJoCo steps per control period."""
        return self._substeps

    @property
    def torque_limits(self) -> np.ndarray:
        return self._tau_max.copy()

    @property
    def joint_limits(self) -> Tuple[np.ndarray, np.ndarray]:
        return self._limits[0].copy(), self._limits[1].copy()

    def measurement(self) -> Measurement:
        return self._meas

    def reset(self, q=None, qd=None) -> Measurement:
        """Puts the robot at ``(q, q̇)`` (default ``q_start``, at rest), command 0, time 0."""
        n = self.dof
        q = self._q_start if q is None else _checked("q", q, n)
        qd = np.zeros(n) if qd is None else _checked("qd", qd, n)
        mujoco.mj_resetData(self.model, self.data)
        self.data.qpos[:], self.data.qvel[:] = q, qd
        self._u = np.zeros(n)
        self.data.ctrl[:] = 0.0
        mujoco.mj_forward(self.model, self.data)
        self._meas = self._measure()
        return self._meas

    def step(self, u) -> Measurement:
        """Applies ``u`` (N·m, clipped to ``torque_limits``) for one control period. A bad ``u``
        raises ``ValueError``, and a step MuJoCo cannot take (a non-finite state, MuJoCo's
        bad-acceleration warning) ``RuntimeError``; either leaves the robot as it was."""
        u = np.clip(_checked("u", u, self.dof), -self._tau_max, self._tau_max)
        d = self.data
        saved = (d.time, d.qpos.copy(), d.qvel.copy(), d.ctrl.copy(), d.qacc_warmstart.copy())
        warnings = d.warning[mujoco.mjtWarning.mjWARN_BADQACC].number
        d.ctrl[self._act] = u / self._gain
        for _ in range(self._substeps):
            mujoco.mj_step(self.model, d)
        if (d.warning[mujoco.mjtWarning.mjWARN_BADQACC].number != warnings
                or not (np.all(np.isfinite(d.qpos)) and np.all(np.isfinite(d.qvel)))):
            d.time, d.qpos[:], d.qvel[:], d.ctrl[:], d.qacc_warmstart[:] = saved
            mujoco.mj_forward(self.model, d)
            raise RuntimeError(f"MuJoCo could not step at t = {d.time:.4f} s (the state diverged); "
                               "the robot is as it was before the step")
        self._u = u
        mujoco.mj_forward(self.model, d)
        self._meas = self._measure()
        return self._meas

    def _measure(self) -> Measurement:
        """The measurement of MuJoCo's current state (after ``mj_forward``)."""
        m, d = self.model, self.data
        if self._is_site:
            point = d.site_xpos[self._point]
            body = m.site_bodyid[self._point]
            mujoco.mj_jacSite(m, d, self._jac, None, self._point)
        else:
            point, body = d.xpos[self._point], self._point
            mujoco.mj_jacBody(m, d, self._jac, None, self._point)
        mujoco.mj_jacDot(m, d, self._jacdot, None, point.reshape(3, 1), body)
        ax = self._axes
        qd = d.qvel.copy()
        return Measurement(
            t=float(d.time),
            q=d.qpos.copy(),
            qd=qd,
            x=point[ax].copy(),
            xd=(self._jac @ qd)[ax],
            xdd=(self._jac @ d.qacc + self._jacdot @ qd)[ax],
            u=self._u.copy(),
        )

    def __repr__(self) -> str:
        return (f"MujocoRobot(dof={self.dof}, task_axes={self._axes.tolist()}, "
                f"control_period={self._period}, substeps={self._substeps})")
