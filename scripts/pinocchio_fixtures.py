#!/usr/bin/env python3
"""Regenerate the Pinocchio cross-check fixtures of crates/dynamics/tests/pinocchio.rs and
crates/dynamics/tests/published.rs.

Three sets (Pinocchio = PyPI package `pin`, NOT `pinocchio`):
- builtin: each built-in robot's URDF from `osrl robot --robot R --urdf` (written next to the
  fixture as R.urdf);
- mixed: arms with revolute and prismatic joints from the dynamics crate's `export_urdf` example;
- published: the arms of the PyPI package `example-robot-data` (6.0.0), from the ORIGINAL files
  (copied unchanged to fixtures/example-robot-data/), reduced in Pinocchio with
  `buildReducedModel` to the degrees of freedom listed in ARMS below: every other movable joint is
  locked at 0 clamped into its limits, a mimic joint at multiplier * leader + offset. The lists
  are written here by hand from osrl's documented rules (crates/dynamics/src/urdf/mod.rs); the
  Rust test checks that the loader arrives at the same tip, degrees of freedom and locks.

At 100 seeded random states each: M (CRBA), g, RNEA, ABA, the tip's position, its Jacobian and
J̇q̇. Published fixtures keep 13 significant digits (the test's tolerance is 1e-9).

Usage:  pip install pin example-robot-data numpy && cargo build --release &&
        python3 scripts/pinocchio_fixtures.py [builtin|mixed|published|all] [OSRL_BINARY]
"""
import json
import pathlib
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin  # provided by the `pin` wheel

ROOT = pathlib.Path(__file__).resolve().parent.parent
OUT = ROOT / "crates" / "dynamics" / "tests" / "fixtures"
ERD_OUT = OUT / "example-robot-data"
ROBOTS = ["planar3", "sarcos7"]
MIXED = [("mixed7_3", 7, 3), ("mixed4_8", 4, 8)]
N_STATES = 100


def joints(prefix, names):
    return [prefix.format(n) for n in names]


UR = ["shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint", "wrist_2_joint", "wrist_3_joint"]
SO = ["shoulder_pan", "shoulder_lift", "elbow_flex", "wrist_flex", "wrist_roll"]
# name, file under example-robot-data's robots/, tip option (None: the default rule), the tip the
# rule must choose, the degrees of freedom in chain order.
ARMS = [
    ("panda", "panda_description/urdf/panda.urdf", None, "panda_hand_tcp", joints("panda_joint{}", range(1, 8))),
    ("ur3", "ur_description/urdf/ur3_robot.urdf", None, "ee_link", UR),
    ("ur5", "ur_description/urdf/ur5_robot.urdf", None, "ee_link", UR),
    ("ur10", "ur_description/urdf/ur10_robot.urdf", None, "ee_link", UR),
    ("jaco2", "kinova_description/robots/kinova.urdf", None, "j2s6s200_end_effector", joints("j2s6s200_joint_{}", range(1, 7))),
    ("xarm7", "xarm_description/urdf/xarm7.urdf", None, "link_eef", joints("joint{}", range(1, 8))),
    ("z1", "z1_description/urdf/z1.urdf", None, "link06", joints("joint{}", range(1, 7))),
    ("so100", "so_arm_description/urdf/so100.urdf", None, "gripper", SO),
    ("so101", "so_arm_description/urdf/so101.urdf", None, "gripper_frame_link", SO),
    ("talos_left_arm", "talos_data/robots/talos_left_arm.urdf", None, "wrist_left_ft_tool_link", joints("arm_left_{}_joint", range(2, 8))),
    ("tiago", "tiago_description/robots/tiago.urdf", None, "hand_tool_link", ["torso_lift_joint"] + joints("arm_{}_joint", range(1, 8))),
    ("baxter", "baxter_description/urdf/baxter.urdf", "right_gripper", "right_gripper", joints("right_{}", ["s0", "s1", "e0", "e1", "w0", "w1", "w2"])),
    ("twodofs", "asr_twodof_description/urdf/TwoDofs.urdf", None, "Link2", ["J1", "J2"]),
]


def sig(x):
    """13 significant digits, as a float."""
    return float(f"{x:.13g}")


def rounded(v):
    return [sig(x) for x in np.ravel(v)] if np.ndim(v) == 1 else [[sig(x) for x in row] for row in v]


def to_pin_q(model, angles):
    """Joint positions (one per degree of freedom) to Pinocchio's configuration vector."""
    q = pin.neutral(model)
    for j in range(1, model.njoints):
        jm = model.joints[j]
        a = angles[jm.idx_v]
        if jm.nq == 2:
            q[jm.idx_q : jm.idx_q + 2] = [np.cos(a), np.sin(a)]
        else:
            q[jm.idx_q] = a
    return q


def evaluate(model, fid, rng, full_precision):
    data = model.createData()
    states = []
    for _ in range(N_STATES):
        angles = np.empty(model.nv)
        for j in range(1, model.njoints):
            jm = model.joints[j]
            if jm.nq == 2:
                angles[jm.idx_v] = rng.uniform(-np.pi, np.pi)
            else:
                lo, hi = model.lowerPositionLimit[jm.idx_q], model.upperPositionLimit[jm.idx_q]
                angles[jm.idx_v] = rng.uniform(lo, hi)
        q = to_pin_q(model, angles)
        qd = rng.uniform(-2.0, 2.0, model.nv)
        qdd = rng.uniform(-5.0, 5.0, model.nv)
        u = rng.uniform(-10.0, 10.0, model.nv)
        m = pin.crba(model, data, q).copy()
        m = np.triu(m) + np.triu(m, 1).T
        g = pin.computeGeneralizedGravity(model, data, q).copy()
        tau = pin.rnea(model, data, q, qd, qdd).copy()
        qdd_aba = pin.aba(model, data, q, qd, u).copy()
        pin.forwardKinematics(model, data, q, qd, np.zeros(model.nv))
        pin.updateFramePlacements(model, data)
        x = data.oMf[fid].translation.copy()
        jdot_qd = pin.getFrameClassicalAcceleration(model, data, fid, pin.LOCAL_WORLD_ALIGNED).linear.copy()
        jac = pin.computeFrameJacobian(model, data, q, fid, pin.LOCAL_WORLD_ALIGNED)[:3, :].copy()
        values = {
            "q": angles, "qd": qd, "qdd": qdd, "u": u, "M": m, "g": g, "rnea": tau, "aba": qdd_aba,
            "x": x, "J": jac, "jdot_qd": jdot_qd,
        }
        conv = (lambda v: np.asarray(v).tolist()) if full_precision else rounded
        states.append({k: conv(v) for k, v in values.items()})
    return states


def builtin(osrl: str, robot: str, seed: int) -> dict:
    urdf = subprocess.run([osrl, "robot", "--robot", robot, "--urdf"], check=True, capture_output=True, text=True).stdout
    (OUT / f"{robot}.urdf").write_text(urdf)
    model = pin.buildModelFromXML(urdf)
    assert model.nq == model.nv, "only revolute joints expected"
    states = evaluate(model, model.getFrameId("ee_link"), np.random.default_rng(seed), True)
    return {"robot": robot, "pinocchio": pin.__version__, "seed": seed, "states": states}


def mixed(name: str, n: int, seed: int) -> dict:
    cmd = ["cargo", "run", "--release", "-q", "-p", "osrl-dynamics", "--example", "export_urdf", "--", "mixed", str(n), str(seed)]
    urdf = subprocess.run(cmd, check=True, capture_output=True, text=True, cwd=ROOT).stdout
    (OUT / f"{name}.urdf").write_text(urdf)
    model = pin.buildModelFromXML(urdf)
    assert model.nq == model.nv
    states = evaluate(model, model.getFrameId("ee_link"), np.random.default_rng(100 + seed), True)
    return {"robot": name, "pinocchio": pin.__version__, "seed": 100 + seed, "states": states}


def lock_values(path: pathlib.Path, dof: list) -> dict:
    """Every movable joint outside `dof`: 0 clamped into its limits; mimic joints follow."""
    root = ET.parse(path).getroot()
    values, mimics = {}, {}
    for j in root.findall("joint"):
        name, kind = j.get("name"), j.get("type")
        if kind == "fixed" or name in dof:
            continue
        if j.find("mimic") is not None:
            mimics[name] = j.find("mimic")
            continue
        lim = j.find("limit")
        v = 0.0
        if kind in ("revolute", "prismatic") and lim is not None:
            v = min(max(0.0, float(lim.get("lower", 0))), float(lim.get("upper", 0)))
        values[name] = v
    for name, m in mimics.items():
        values[name] = float(m.get("multiplier", 1)) * values[m.get("joint")] + float(m.get("offset", 0))
    return values


def pin_name(path: pathlib.Path, joint: str) -> str:
    """The joint's name in pin_xml: Pinocchio's buildReducedModel refuses a joint named like a
    link (SO-100's jaw joint and link are both 'gripper'), so such joints get a suffix there."""
    links = {l.get("name") for l in ET.parse(path).getroot().findall("link")}
    return joint + "__joint" if joint in links else joint


def pin_xml(path: pathlib.Path) -> str:
    """The file for Pinocchio: the original, with the renames of pin_name (physics unchanged)."""
    root = ET.parse(path).getroot()
    links = {l.get("name") for l in root.findall("link")}
    for j in root.findall("joint"):
        if j.get("name") in links:
            j.set("name", j.get("name") + "__joint")
        m = j.find("mimic")
        if m is not None and m.get("joint") in links:
            m.set("joint", m.get("joint") + "__joint")
    return ET.tostring(root, encoding="unicode")


def published(erd: pathlib.Path, name: str, rel: str, tip_option, tip: str, dof: list, seed: int) -> dict:
    src = erd / rel
    dst = ERD_OUT / pathlib.Path(rel).name
    shutil.copyfile(src, dst)
    full = pin.buildModelFromXML(pin_xml(src))
    locked = lock_values(src, dof)
    lock_ids = [full.getJointId(pin_name(src, n)) for n in locked]
    assert all(i < full.njoints for i in lock_ids), "a locked joint is not in Pinocchio's model"
    angles = np.zeros(full.nv)
    for i, v in zip(lock_ids, locked.values()):
        angles[full.joints[i].idx_v] = v
    model = pin.buildReducedModel(full, lock_ids, to_pin_q(full, angles))
    assert list(model.names)[1:] == dof, f"{name}: Pinocchio's joints {list(model.names)[1:]}"
    states = evaluate(model, model.getFrameId(tip), np.random.default_rng(seed), False)
    return {
        "robot": name, "file": dst.name, "source": f"example-robot-data 6.0.0, robots/{rel}",
        "tip_option": tip_option, "tip": tip, "dof": dof, "locked": locked,
        "pinocchio": pin.__version__, "seed": seed, "states": states,
    }


def main() -> None:
    which = sys.argv[1] if len(sys.argv) > 1 else "all"
    OUT.mkdir(parents=True, exist_ok=True)
    if which in ("builtin", "all"):
        osrl = sys.argv[2] if len(sys.argv) > 2 else str(ROOT / "target" / "release" / "osrl")
        for seed, robot in enumerate(ROBOTS):
            data = builtin(osrl, robot, seed)
            (OUT / f"{robot}.pinocchio.json").write_text(json.dumps(data, indent=0))
            print(f"{robot}: {len(data['states'])} states from Pinocchio {data['pinocchio']}")
    if which in ("mixed", "all"):
        for name, n, seed in MIXED:
            data = mixed(name, n, seed)
            (OUT / f"{name}.pinocchio.json").write_text(json.dumps(data, indent=0))
            print(f"{name}: {len(data['states'])} states")
    if which in ("published", "all"):
        import cmeel  # installed with example-robot-data

        erd = pathlib.Path(cmeel.__file__).parent.parent / "cmeel.prefix" / "share" / "example-robot-data" / "robots"
        ERD_OUT.mkdir(parents=True, exist_ok=True)
        for seed, (name, rel, tip_option, tip, dof) in enumerate(ARMS):
            data = published(erd, name, rel, tip_option, tip, dof, 1000 + seed)
            (ERD_OUT / f"{name}.pinocchio.json").write_text(json.dumps(data, separators=(",", ":")))
            print(f"{name}: {len(dof)} DOF, {len(data['locked'])} locked, {len(data['states'])} states")


if __name__ == "__main__":
    main()
