"""Is there a physically consistent robot with exactly the dynamics of osrl's sarcos7?
(ROBOT_PROTOCOL.md, "sarcos7 in MuJoCo".)

A revolute chain's dynamics do not change when mass distributed along joint j's axis moves
between link j and its parent (for joint 0, the world): in link j's frame, its pseudo-inertia
is ``B [[α, η], [η, μ]] Bᵀ`` with ``B = [[z, 0], [0, 1]]`` (second moment α, first moment η
along the axis z, mass μ). This maximises the smallest eigenvalue of every link's pseudo-
inertia over those 3 parameters per joint; a positive optimum would be a physical equivalent.

    pip install cvxpy && python tools/sarcos7_regrouping.py [ROBOT]
"""

import sys
import xml.etree.ElementTree as ET

import cvxpy as cp
import numpy as np

import osrl
from osrl.mujoco.inertia import Inertial, rpy_matrix


def chain(urdf: str):
    """Per moving joint: the child's pseudo-inertia, the joint's transform and axis."""
    root = ET.fromstring(urdf)
    links = {l.get("name"): l for l in root.findall("link")}
    out = []
    for j in root.findall("joint"):
        if j.get("type") == "fixed":
            continue
        i = links[j.find("child").get("link")].find("inertial")
        m = float(i.find("mass").get("value"))
        c = [float(v) for v in i.find("origin").get("xyz").split()]
        a = {k: float(v) for k, v in i.find("inertia").attrib.items()}
        ic = np.array([[a["ixx"], a["ixy"], a["ixz"]], [a["ixy"], a["iyy"], a["iyz"]],
                       [a["ixz"], a["iyz"], a["izz"]]])
        o = j.find("origin")
        t = np.eye(4)
        t[:3, :3] = rpy_matrix(*(float(v) for v in o.get("rpy").split()))
        t[:3, 3] = [float(v) for v in o.get("xyz").split()]
        z = np.array([float(v) for v in j.find("axis").get("xyz").split()])
        out.append((Inertial.from_com(m, c, ic).j, t, z / np.linalg.norm(z)))
    return out


def main():
    name = sys.argv[1] if len(sys.argv) > 1 else "sarcos7"
    links = chain(osrl.Robot.builtin(name).to_urdf())
    n = len(links)
    theta, t = cp.Variable((n, 3)), cp.Variable()

    def on_axis(k):
        b = np.zeros((4, 2))
        b[:3, 0], b[3, 1] = links[k][2], 1.0
        return b @ cp.bmat([[theta[k, 0], theta[k, 1]], [theta[k, 1], theta[k, 2]]]) @ b.T

    cons = []
    for k, (j0, _, _) in enumerate(links):
        j = j0 + on_axis(k)
        if k + 1 < n:
            tk = links[k + 1][1]
            j = j - tk @ on_axis(k + 1) @ tk.T
        cons.append((j + j.T) / 2 >> t * np.eye(4))
    for k, (j0, _, _) in enumerate(links):
        print(f"link {k}: smallest pseudo-inertia eigenvalue {np.linalg.eigvalsh(j0).min():.4g}")
    cp.Problem(cp.Maximize(t), cons + [t <= 1, cp.abs(theta) <= 1e4]).solve()
    print(f"{name}: best smallest eigenvalue after regrouping {t.value:.4g} kg·m² "
          f"({'physical equivalent exists' if t.value > 0 else 'no physical equivalent'})")


if __name__ == "__main__":
    main()
