"""Rigid-body inertials as 4×4 pseudo-inertia matrices, and the rotations of URDF and MuJoCo.

A body's pseudo-inertia about a frame is ``J = Σ m_k [r_k; 1][r_k; 1]ᵀ``: ``[[Σ, h], [hᵀ, m]]``
with ``m`` the mass, ``h = m c`` the first moment and ``Σ = ½ tr(I) 1 − I`` the second moment
(``I`` the rotational inertia about the frame's origin). It moves to a parent frame as
``T J Tᵀ`` (``T`` the homogeneous transform), adds by ``+``, and a body is physically
consistent exactly when it is positive definite.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Inertial", "rpy_matrix", "quat_from_matrix", "mujoco_accepts"]


def rpy_matrix(r: float, p: float, y: float) -> np.ndarray:
    """URDF's fixed-axis roll-pitch-yaw: ``Rz(y) Ry(p) Rx(r)``."""
    cr, sr, cp, sp, cy, sy = np.cos(r), np.sin(r), np.cos(p), np.sin(p), np.cos(y), np.sin(y)
    rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    return rz @ ry @ rx


def quat_from_matrix(rot: np.ndarray) -> np.ndarray:
    """The unit quaternion ``(w, x, y, z)`` of a rotation matrix (MuJoCo's order), w ≥ 0."""
    m = np.asarray(rot, dtype=float)
    t = np.trace(m)
    # The largest of 1 + t, 1 + m00 − m11 − m22, ... gives the best-conditioned formula.
    k = int(np.argmax([t, m[0, 0], m[1, 1], m[2, 2]]))
    if k == 0:
        s = 2.0 * np.sqrt(1.0 + t)
        q = [0.25 * s, (m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s]
    else:
        i, j, l = (k - 1, k % 3, (k + 1) % 3)
        s = 2.0 * np.sqrt(1.0 + m[i, i] - m[j, j] - m[l, l])
        q = [0.0] * 4
        q[0] = (m[l, j] - m[j, l]) / s
        q[1 + i] = 0.25 * s
        q[1 + j] = (m[j, i] + m[i, j]) / s
        q[1 + l] = (m[l, i] + m[i, l]) / s
    q = np.array(q)
    q /= np.linalg.norm(q)
    return q if q[0] >= 0 else -q


@dataclass(frozen=True)
class Inertial:
    """A body's mass properties as its pseudo-inertia ``j`` (4×4) about its own frame."""

    j: np.ndarray

    @staticmethod
    def zero() -> "Inertial":
        return Inertial(np.zeros((4, 4)))

    @staticmethod
    def from_com(mass: float, com, inertia_com) -> "Inertial":
        """From the mass (kg), the centre of mass (m) and the inertia about it (kg·m²)."""
        c = np.asarray(com, dtype=float)
        i_c = np.asarray(inertia_com, dtype=float)
        sigma = 0.5 * np.trace(i_c) * np.eye(3) - i_c + mass * np.outer(c, c)
        j = np.zeros((4, 4))
        j[:3, :3], j[:3, 3], j[3, :3], j[3, 3] = sigma, mass * c, mass * c, mass
        return Inertial(j)

    @property
    def mass(self) -> float:
        return float(self.j[3, 3])

    @property
    def com(self) -> np.ndarray:
        """Centre of mass (the frame origin for a massless body)."""
        return self.j[:3, 3] / self.mass if self.mass > 0 else np.zeros(3)

    @property
    def inertia_com(self) -> np.ndarray:
        """Rotational inertia about the centre of mass (about the origin when massless)."""
        c = self.com
        sigma = self.j[:3, :3] - self.mass * np.outer(c, c)
        return np.trace(sigma) * np.eye(3) - sigma

    def transformed(self, rot: np.ndarray, pos: np.ndarray) -> "Inertial":
        """The same body seen from a frame in which this one sits at ``(rot, pos)``."""
        t = np.eye(4)
        t[:3, :3], t[:3, 3] = rot, pos
        return Inertial(t @ self.j @ t.T)

    def __add__(self, other: "Inertial") -> "Inertial":
        return Inertial(self.j + other.j)


def mujoco_accepts(inertial: Inertial) -> bool:
    """Whether MuJoCo's compiler takes this inertial as it is: a positive mass, positive
    principal moments about the centre of mass, and the triangle inequality between them
    (with a relative margin of 1e-9 over MuJoCo's own)."""
    if not inertial.mass > 1e-12:
        return False
    moments = np.linalg.eigvalsh(inertial.inertia_com)
    scale = max(float(moments.max()), 1e-300)
    a, b, c = moments
    return bool(moments.min() > 1e-9 * scale and a + b >= c * (1 + 1e-9))
