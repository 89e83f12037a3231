#!/usr/bin/env python3
"""Time Pinocchio's RNEA, CRBA, ABA and frame Jacobian through its Python API on the URDFs that
`osrl robot --urdf` exports (committed in crates/dynamics/tests/fixtures), at the same states as
crates/dynamics/benches/dynamics.rs. Prints one JSON object (ns per call; the Python call overhead,
measured with a no-op call, is reported separately and also subtracted).

Usage: pip install pin && python3 scripts/bench_pinocchio.py
"""
import json
import pathlib
import timeit

import numpy as np
import pinocchio as pin

FIX = pathlib.Path(__file__).resolve().parent.parent / "crates" / "dynamics" / "tests" / "fixtures"


def per_call_ns(fn, number=20000, repeat=7):
    return min(timeit.repeat(fn, number=number, repeat=repeat)) / number * 1e9


def main():
    out = {"pinocchio": pin.__version__}
    noop = per_call_ns(lambda: None)
    out["python_call_overhead_ns"] = noop
    for robot in ["sarcos7", "planar3"]:
        model = pin.buildModelFromXML((FIX / f"{robot}.urdf").read_text())
        data = model.createData()
        n = model.nv
        q = np.array([0.1 * i + 0.2 for i in range(n)])
        qd = np.array([0.3 - 0.05 * i for i in range(n)])
        qdd = np.array([0.5 + 0.1 * i for i in range(n)])
        fid = model.getFrameId("ee_link")
        calls = {
            "fk_jacobian": lambda: pin.computeFrameJacobian(model, data, q, fid, pin.LOCAL_WORLD_ALIGNED),
            "rnea": lambda: pin.rnea(model, data, q, qd, qdd),
            "crba": lambda: pin.crba(model, data, q),
            "aba": lambda: pin.aba(model, data, q, qd, qdd),
        }
        for name, fn in calls.items():
            t = per_call_ns(fn)
            out[f"{robot}/{name}_ns"] = t
            out[f"{robot}/{name}_minus_overhead_ns"] = t - noop
    print(json.dumps(out))


if __name__ == "__main__":
    main()
