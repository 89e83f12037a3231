#!/usr/bin/env python3
"""Regenerate the Pinocchio cross-check fixtures of crates/dynamics/tests/pinocchio.rs.

For each built-in robot: export its URDF with `osrl robot --robot R --urdf`, load it into
Pinocchio (PyPI package `pin`, NOT `pinocchio`), and evaluate M (CRBA), g, RNEA, ABA, the
end-effector position, its Jacobian and J̇q̇ at 100 seeded random states. Writes
crates/dynamics/tests/fixtures/R.urdf and R.pinocchio.json.

Usage:  pip install pin && cargo build --release && python3 scripts/pinocchio_fixtures.py [OSRL_BINARY]
"""
import json
import pathlib
import subprocess
import sys

import numpy as np
import pinocchio as pin  # provided by the `pin` wheel

ROOT = pathlib.Path(__file__).resolve().parent.parent
OUT = ROOT / "crates" / "dynamics" / "tests" / "fixtures"
ROBOTS = ["planar3", "sarcos7"]
N_STATES = 100


def fixture(osrl: str, robot: str, seed: int) -> dict:
    urdf = subprocess.run([osrl, "robot", "--robot", robot, "--urdf"], check=True, capture_output=True, text=True).stdout
    (OUT / f"{robot}.urdf").write_text(urdf)
    model = pin.buildModelFromXML(urdf)
    data = model.createData()
    assert model.nq == model.nv, "only revolute joints expected"
    fid = model.getFrameId("ee_link")
    rng = np.random.default_rng(seed)
    lo, hi = model.lowerPositionLimit, model.upperPositionLimit
    states = []
    for _ in range(N_STATES):
        q = rng.uniform(lo, hi)
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
        states.append({
            "q": q.tolist(), "qd": qd.tolist(), "qdd": qdd.tolist(), "u": u.tolist(),
            "M": m.tolist(), "g": g.tolist(), "rnea": tau.tolist(), "aba": qdd_aba.tolist(),
            "x": x.tolist(), "J": jac.tolist(), "jdot_qd": jdot_qd.tolist(),
        })
    return {"robot": robot, "pinocchio": pin.__version__, "seed": seed, "states": states}


def main() -> None:
    osrl = sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "target" / "release" / "osrl")
    OUT.mkdir(parents=True, exist_ok=True)
    for seed, robot in enumerate(ROBOTS):
        data = fixture(osrl, robot, seed)
        (OUT / f"{robot}.pinocchio.json").write_text(json.dumps(data, indent=0))
        print(f"{robot}: {len(data['states'])} states from Pinocchio {data['pinocchio']}")


if __name__ == "__main__":
    main()
