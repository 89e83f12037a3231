"""Train a learned operational space controller against MuJoCo and plot its tracking.

    python examples/python/train_mujoco.py --robot planar3 --minutes 30 --seed 0 --out /tmp/p3
    python examples/python/train_mujoco.py --model /tmp/p3/model.osrl --out /tmp/p3  # plot only

MuJoCo simulates the robot (``osrl.mujoco.MujocoRobot.builtin``: the MJCF built from osrl's
URDF export, RK4 steps of 1 ms, a 2 ms control period); ``osrl.train`` runs the Rust trainer of
``osrl train`` on it, so the learner sees MuJoCo's measurements only. What it prints and writes
(``--out``, a folder):

- ``training.json``: the trainer's summary. Its learning curve is evaluated on osrl's own
  simulator of the same model (tracking RMS, command nMSE against eq. 7's ``u*``), and its
  safety figures (aborted and braked episodes, clipped commands, the largest on-policy command
  step and eq. 7's on the path) come from the MuJoCo training itself.
- ``model.osrl``: the learned controller (``osrl.LearnedController.load``).
- ``mujoco_eval.json`` and ``tracking.png``: the learned controller tracking the trajectory in
  MuJoCo, as osrl's evaluation does (from rest at home, ``--periods`` periods of the path,
  the tracking RMS over the periods after the first), and the wall time per control step of
  this Python loop (``command`` and ``step`` separately).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

import osrl
from osrl.mujoco import MujocoRobot


def args() -> argparse.Namespace:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--robot", default="planar3", help="built-in robot (planar3, sarcos7, ...)")
    ap.add_argument("--trajectory", default="figure8", choices=["figure8", "circle", "min_jerk"])
    ap.add_argument("--minutes", type=float, default=30.0, help="simulated minutes of training")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--out", type=Path, required=True, help="output folder (created)")
    ap.add_argument("--periods", type=int, default=2, help="periods of the MuJoCo evaluation")
    ap.add_argument("--model", type=Path, help="evaluate and plot this saved model, no training")
    a = ap.parse_args()
    if not (np.isfinite(a.minutes) and a.minutes >= 0) or a.periods < 2:
        ap.error("--minutes must be finite and ≥ 0, --periods ≥ 2")
    if a.out.exists() and not a.out.is_dir():
        ap.error(f"--out {a.out} exists and is not a folder")
    return a


def evaluate(ctrl: osrl.LearnedController, traj: osrl.Trajectory, periods: int) -> dict:
    """The controller tracking ``traj`` in MuJoCo from rest at home; the series and metrics."""
    sim = MujocoRobot.builtin(ctrl.robot, control_period=ctrl.control_period)
    meas = sim.reset(ctrl.home)
    per = int(round(traj.period / ctrl.control_period))
    x, x_d, u, t = [], [], [], []
    t_cmd = t_step = 0.0
    for _ in range(periods * per):
        target = traj.sample(meas.t)
        c0 = time.perf_counter()
        cmd = ctrl.command(meas, *target)
        c1 = time.perf_counter()
        x.append(meas.x), x_d.append(target[0]), u.append(cmd), t.append(meas.t)
        meas = sim.step(cmd)
        t_cmd, t_step = t_cmd + c1 - c0, t_step + time.perf_counter() - c1
    x, x_d, u, t = map(np.array, (x, x_d, u, t))
    err = np.linalg.norm(x - x_d, axis=1)
    window = err[per:]
    n = len(t)
    return {
        "robot": ctrl.robot, "periods": periods, "steps": n,
        "control_period_s": ctrl.control_period,
        "tracking_rms_mm": 1e3 * float(np.sqrt(np.mean(window ** 2))),
        "tracking_max_mm": 1e3 * float(window.max()),
        "largest_command_step_nm": float(np.abs(np.diff(u, axis=0)).max()),
        "clipped_commands": int(np.sum(np.any(np.abs(u) > sim.torque_limits, axis=1))),
        "command_us_per_step": 1e6 * t_cmd / n, "mujoco_step_us_per_step": 1e6 * t_step / n,
        "series": {"t": t, "x": x, "x_d": x_d, "err": err},
    }


def plot(path: Path, ev: dict, training: dict | None) -> None:
    """Path in the task plane, tracking error over time and (after training) the learning curve."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no plot (pip install matplotlib)", file=sys.stderr)
        return
    s = ev["series"]
    cols = 3 if training else 2
    fig, ax = plt.subplots(1, cols, figsize=(5 * cols, 4.2))
    ax[0].plot(s["x_d"][:, 0], s["x_d"][:, -1], "k--", lw=1, label="target")
    ax[0].plot(s["x"][:, 0], s["x"][:, -1], lw=1, label="MuJoCo, learned controller")
    ax[0].set(xlabel="task axis 1 (m)", ylabel="last task axis (m)", title=f"{ev['robot']} path")
    ax[0].axis("equal"), ax[0].legend(fontsize=8)
    ax[1].semilogy(s["t"], np.maximum(1e3 * s["err"], 1e-4), lw=1)
    ax[1].axvline(s["t"][len(s["t"]) // ev["periods"]], color="gray", lw=0.5)
    ax[1].set(xlabel="time (s)", ylabel="tracking error (mm)",
              title=f"RMS {ev['tracking_rms_mm']:.3f} mm after the first period")
    if training:
        curve = training["learning_curve"]
        m = [c[0] for c in curve]
        ax[2].semilogy(m, [c[1]["tracking_rms_mm"] for c in curve], "o-", ms=3,
                       label="tracking RMS (mm)")
        ax[2].semilogy(m, [c[1]["command_nmse"] for c in curve], "s-", ms=3, label="command nMSE")
        ax[2].set(xlabel="simulated training minutes (MuJoCo)",
                  title="evaluations on osrl's model")
        ax[2].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main() -> None:
    a = args()
    a.out.mkdir(parents=True, exist_ok=True)
    training = None
    if a.model:
        ctrl = osrl.LearnedController.load(a.model)
    else:
        sim = MujocoRobot.builtin(a.robot)
        print(f"training {a.robot} in MuJoCo along {a.trajectory}: {a.minutes} simulated minutes, "
              f"seed {a.seed} ...", flush=True)
        ctrl = osrl.train(sim, a.trajectory, minutes=a.minutes, seed=a.seed)
        ctrl.save(a.out / "model.osrl")
        training = ctrl.training
        (a.out / "training.json").write_text(json.dumps(training))
        t, e = training, training["learning_curve"][-1][1]
        print(f"trained: {t['sim_training_minutes']:.1f} simulated minutes in "
              f"{t['wall_seconds']:.0f} s wall, {t['n_local_models']} local models")
        print(f"  evaluation on osrl's {a.robot} (last): tracking RMS {e['tracking_rms_mm']:.3f} "
              f"mm (max {e['tracking_max_mm']:.3f}), command nMSE vs eq. 7 {e['command_nmse']:.4f}")
        print(f"  safety in MuJoCo: {t['episodes']} episodes, {t['aborted_episodes']} aborted, "
              f"{t['braked_episodes']} braked, {t['clipped_on_policy']} commands clipped; "
              f"largest on-policy command step {t['max_command_step']:.3f} N·m (eq. 7 on the "
              f"path: {e['max_command_step_analytical']:.3f} N·m)")
    traj = osrl.Trajectory(ctrl.robot, a.trajectory)
    ev = evaluate(ctrl, traj, a.periods)
    series = ev.pop("series")
    (a.out / "mujoco_eval.json").write_text(json.dumps(ev, indent=1))
    print(f"MuJoCo evaluation ({a.periods} periods of {traj.period:.2f} s from home): tracking RMS "
          f"{ev['tracking_rms_mm']:.3f} mm (max {ev['tracking_max_mm']:.3f}), largest command step "
          f"{ev['largest_command_step_nm']:.3f} N·m; Python loop per step: command "
          f"{ev['command_us_per_step']:.1f} µs, MuJoCo step + measurement "
          f"{ev['mujoco_step_us_per_step']:.1f} µs")
    ev["series"] = series
    plot(a.out / "tracking.png", ev, training)
    print(f"wrote {a.out}/: mujoco_eval.json, tracking.png"
          + (", training.json, model.osrl" if training else ""))


if __name__ == "__main__":
    main()
