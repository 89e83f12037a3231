"""Compiling an MJCF of ``mjcf_from_urdf`` with its exact inertials."""

from __future__ import annotations

import mujoco
import numpy as np

from .inertia import quat_from_matrix
from .mjcf import INERTIAL_PREFIX

__all__ = ["load_model"]


def _principal(inertia: np.ndarray):
    """Principal moments and the rotation whose columns are the principal axes (det +1)."""
    moments, axes = np.linalg.eigh(inertia)
    if np.linalg.det(axes) < 0:
        axes[:, 2] = -axes[:, 2]
    return moments, axes


def load_model(xml: str) -> "mujoco.MjModel":
    """Compiles MJCF text and writes the exact inertials its ``osrl_inertial:`` numerics hold
    into the compiled model (bodies that MuJoCo's compiler would refuse; see
    ``osrl.mujoco.mjcf``). MuJoCo's runtime does not require a body to be physically
    consistent, only the whole mass matrix to be positive definite, which holds for a model
    osrl accepts. Derived constants are recomputed (``mj_setConst``).

    Raises ``ValueError`` when MuJoCo refuses the MJCF or a numeric names no body.
    """
    try:
        m = mujoco.MjModel.from_xml_string(xml)
    except Exception as e:  # mujoco raises its own ValueError subclasses, message included
        raise ValueError(f"MuJoCo refused the model: {e}") from None
    patched = False
    for k in range(m.nnumeric):
        name = mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_NUMERIC, k)
        if not name or not name.startswith(INERTIAL_PREFIX):
            continue
        body = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, name[len(INERTIAL_PREFIX):])
        if body < 0:
            raise ValueError(f"numeric {name!r} names no body")
        adr, size = m.numeric_adr[k], m.numeric_size[k]
        if size != 10:
            raise ValueError(f"numeric {name!r} has {size} values, expected 10")
        mass, cx, cy, cz, ixx, iyy, izz, ixy, ixz, iyz = m.numeric_data[adr:adr + 10]
        inertia = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])
        moments, axes = _principal(inertia)
        m.body_mass[body] = mass
        m.body_ipos[body] = (cx, cy, cz)
        m.body_iquat[body] = quat_from_matrix(axes)
        m.body_inertia[body] = moments
        # The inertial frame is no longer the body frame (MuJoCo's shortcut for that case).
        m.body_sameframe[body] = 0
        if m.body_simple[body]:
            raise ValueError(f"body {name!r}: MuJoCo treats it as simple; cannot patch")
        patched = True
    if patched:
        mujoco.mj_setConst(m, mujoco.MjData(m))
    return m
