"""Per-step cost of training through ``osrl.train`` on a Python robot (MuJoCo), against the
same training on osrl's own simulator. A benchmark, not a test.

    cargo build --release -p osrl-cli
    python examples/python/bench_train_step.py [--robot planar3] [--minutes 2] [--rounds 3]

Per control step, in interleaved rounds (the best round of each):
Times are CPU seconds of this process (``time.process_time``) and of the CLI child
(``getrusage``), not wall time: on a machine shared with other jobs the wall time of each part
moves by 2× between rounds while its CPU time does not. Both training figures include the
set-up (model, trajectory, IK of the home posture: well under 1 % of a minute's training).
- ``mujoco``: ``osrl.train(MujocoRobot.builtin(robot), minutes=M)``: the Rust trainer, the
  Rust → Python call of ``robot.step`` and reading its ``Measurement``, MuJoCo's steps and
  measurement;
- ``rust``: ``osrl train --robot R --minutes M`` (target/release/osrl): the same trainer and
  learner on osrl's simulator;
- ``mj_step``: ``MujocoRobot.step`` alone, called from a Python loop with the command sequence
  of a PD hold computed in the loop (MuJoCo's share and Python's cost of the adapter; the PD
  command with ``Robot.gravity`` adds about 2 µs);
- ``mj_raw``: MuJoCo's own work in ``step`` (``mj_step`` per substep and the ``mj_forward`` of
  the measurement), called bare from Python with a constant control: ``mj_step − mj_raw`` is
  the adapter's Python (argument checks, the saved state, the Jacobians, the ``Measurement``).
``mujoco − rust − mj_step`` is then the binding's share (plus osrl's own simulator step, a few
µs, which ``rust`` contains and ``mujoco`` does not).
"""

import argparse
import resource
import subprocess
import time
from pathlib import Path

import mujoco
import numpy as np

import osrl
from osrl.mujoco import MujocoRobot

REPO = Path(__file__).resolve().parents[2]


def children_cpu() -> float:
    """CPU seconds (user + system) of the finished child processes."""
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--robot", default="planar3")
    ap.add_argument("--minutes", type=float, default=2.0)
    ap.add_argument("--rounds", type=int, default=3)
    a = ap.parse_args()
    cli = REPO / "target" / "release" / "osrl"
    if not cli.is_file():
        raise SystemExit(f"{cli} not found: cargo build --release -p osrl-cli")
    sim = MujocoRobot.builtin(a.robot)
    steps = int(round(a.minutes * 60 / sim.control_period))
    r = osrl.Robot.builtin(a.robot)
    best = {"mujoco": np.inf, "rust": np.inf, "mj_step": np.inf, "mj_raw": np.inf}
    for _ in range(a.rounds):
        t0 = time.process_time()
        osrl.train(sim, "figure8", minutes=a.minutes, seed=0)
        best["mujoco"] = min(best["mujoco"], (time.process_time() - t0) / steps)
        c0 = children_cpu()
        subprocess.run([str(cli), "train", "--robot", a.robot, "--minutes", str(a.minutes),
                        "--out", "/tmp/bench_train_step.model"], check=True, capture_output=True)
        best["rust"] = min(best["rust"], (children_cpu() - c0) / steps)
        meas = sim.reset()
        q0 = meas.q.copy()
        t0 = time.process_time()
        for _ in range(steps):
            meas = sim.step(r.gravity(meas.q) + 50.0 * (q0 - meas.q) - 5.0 * meas.qd)
        best["mj_step"] = min(best["mj_step"], (time.process_time() - t0) / steps)
        m, d = sim.model, sim.data
        sim.reset()
        d.ctrl[:] = r.gravity(sim.measurement().q)
        t0 = time.process_time()
        for _ in range(steps):
            for _ in range(sim.substeps):
                mujoco.mj_step(m, d)
            mujoco.mj_forward(m, d)
        best["mj_raw"] = min(best["mj_raw"], (time.process_time() - t0) / steps)
    us = {k: 1e6 * v for k, v in best.items()}
    print(f"{a.robot}, {a.minutes} simulated minutes ({steps} control steps), "
          f"best of {a.rounds} rounds:")
    for k, v in us.items():
        print(f"  {k:8s} {v:7.1f} µs CPU per control step")
    print(f"  adapter's Python (mj_step − mj_raw): {us['mj_step'] - us['mj_raw']:.1f} µs")
    binding = us["mujoco"] - us["rust"] - us["mj_step"]
    print(f"  binding share (mujoco − rust − mj_step): {binding:.1f} µs")


if __name__ == "__main__":
    main()
