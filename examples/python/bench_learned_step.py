"""Per-step cost of a Python-driven control step of the learned controller on sarcos7
(issue 29: ≤ 20 µs). A benchmark, not a test.

    cargo run --release -- train --robot sarcos7 --minutes 5 --out /tmp/sarcos7.model
    python examples/python/bench_learned_step.py /tmp/sarcos7.model [--steps 20000]

Times, per control step, best of 5 repeats:
- ``command``: ``LearnedController.command(measurement, x_d, xd_d, xdd_d)`` on recorded states
  (reading the measurement and target, the Rust command, the new numpy array);
- ``rust``: the Rust ``LearnedController::command`` alone (crates/py/examples/learned_timing.rs,
  run through cargo when the repository is here), so ``command − rust`` is Python's overhead;
- ``loop``: the same inside a MuJoCo closed loop (``MujocoRobot.builtin("sarcos7")``), and the
  loop with a PD command instead (the simulator's and the loop's own share).
"""

import argparse
import json
import subprocess
import time
from pathlib import Path

import numpy as np

import osrl
from osrl.mujoco import MujocoRobot


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("model")
    ap.add_argument("--steps", type=int, default=20000)
    a = ap.parse_args()
    c = osrl.LearnedController.load(a.model)
    assert c.robot == "sarcos7", c.robot
    sim = MujocoRobot.builtin("sarcos7", control_period=c.control_period)
    m = c.task_dim
    goal = [np.array(sim.reset(c.home).x), np.zeros(m), np.zeros(m)]

    # Recorded states of a closed loop (the controller holding home).
    states, meas = [], sim.reset(c.home)
    for _ in range(min(a.steps, 2000)):
        states.append(meas)
        meas = sim.step(c.command(meas, *goal))
    reps = a.steps // len(states)

    def best(f) -> float:
        ts = []
        for _ in range(5):
            t0 = time.perf_counter()
            f()
            ts.append(time.perf_counter() - t0)
        return min(ts)

    def commands():
        for _ in range(reps):
            for s in states:
                c.command(s, *goal)

    per = best(commands) / (reps * len(states)) * 1e6

    def loop(ctrl):
        def run():
            meas = sim.reset(c.home)
            for _ in range(len(states)):
                meas = sim.step(ctrl(meas))
        return run

    learned = best(loop(lambda s: c.command(s, *goal))) / len(states) * 1e6
    robot = osrl.Robot.builtin("sarcos7")
    pd = best(loop(lambda s: robot.gravity(s.q) - 2.0 * s.qd)) / len(states) * 1e6
    rust = None
    try:
        out = subprocess.run(["cargo", "run", "--release", "-q", "-p", "osrl-py", "--example",
                              "learned_timing", "--", a.model, str(a.steps)],
                             cwd=Path(__file__).resolve().parents[2], capture_output=True,
                             text=True, check=True).stdout
        rust = json.loads(out.strip().splitlines()[-1])["command_us"]
    except (OSError, subprocess.CalledProcessError, ValueError, KeyError, IndexError):
        pass
    if rust is not None:
        print(f"Rust command alone {rust:.2f} µs: Python's overhead {per - rust:.2f} µs/step")
    print(f"sarcos7, {c.n_local_models} local models: command {per:.2f} µs/step; "
          f"MuJoCo loop with the learned controller {learned:.1f} µs/step, "
          f"with gravity compensation + damping {pd:.1f} µs/step")


if __name__ == "__main__":
    main()
