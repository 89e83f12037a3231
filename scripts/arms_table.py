#!/usr/bin/env python3
"""Every arm of example-robot-data through osrl: load, eq. 7, and learning (issue 28).

    python3 scripts/arms_table.py --osrl BIN --robots DIR --runs OUT [--minutes 30] [--seed 0]
        [--no-train] [--only NAME ...] > table.md

DIR is the `robots` folder of the installed PyPI package `example-robot-data` (e.g.
`VENV/lib/python3.X/site-packages/cmeel.prefix/share/example-robot-data/robots`, after `pip
install example-robot-data==6.0.0`; the committed fixtures folder
`crates/dynamics/tests/fixtures/example-robot-data` holds the arms that need no subfolder there).

For each robot with an arm chain (ARMS below; legged robots, drones and hands without an arm are
listed in NOT_ARMS and only checked to be refused: step 1 alone, a third table):
1. `osrl robot --robot F [--tip T] --json`: DOF and tip (or the refusal's message);
2. `osrl simulate --robot F [--tip T] --json`: eq. 7 (`N = I`, true model) on the profile's default
   figure-8, 12 s;
3. where 2 ran: `osrl train --robot F [--tip T] --minutes M --seed S --json --out OUT/NAME.model`,
   its last stdout line kept as OUT/NAME.train.json (a run already there is reused, not repeated).
Prints the Markdown table on stdout; each command's stdout/stderr is kept in OUT.
"""

import argparse
import json
import os
import subprocess
import sys

# (name, path under the package's robots folder, extra osrl options, note)
ARMS = [
    ("panda", "panda_description/urdf/panda.urdf", [], ""),
    ("panda_collision", "panda_description/urdf/panda_collision.urdf", [], "variant of panda"),
    ("ur3", "ur_description/urdf/ur3_robot.urdf", [], ""),
    ("ur3_joint_limited", "ur_description/urdf/ur3_joint_limited_robot.urdf", [], "variant"),
    ("ur3_gripper", "ur_description/urdf/ur3_gripper.urdf", [], "variant"),
    ("ur3_empty", "ur_description/urdf/ur3.urdf", [], "empty file"),
    ("ur5", "ur_description/urdf/ur5_robot.urdf", [], ""),
    ("ur5_joint_limited", "ur_description/urdf/ur5_joint_limited_robot.urdf", [], "variant"),
    ("ur5_gripper", "ur_description/urdf/ur5_gripper.urdf", [], "variant"),
    ("ur10", "ur_description/urdf/ur10_robot.urdf", [], ""),
    ("ur10_joint_limited", "ur_description/urdf/ur10_joint_limited_robot.urdf", [], "variant"),
    ("kinova_jaco2", "kinova_description/robots/kinova.urdf", [], ""),
    ("xarm7", "xarm_description/urdf/xarm7.urdf", [], ""),
    ("z1", "z1_description/urdf/z1.urdf", [], ""),
    ("so100", "so_arm_description/urdf/so100.urdf", [], ""),
    ("so101", "so_arm_description/urdf/so101.urdf", [], ""),
    ("talos_left_arm", "talos_data/robots/talos_left_arm.urdf", [], ""),
    ("talos_full_v2", "talos_data/robots/talos_full_v2.urdf", ["--tip", "wrist_right_ft_tool_link"], "right arm"),
    ("tiago", "tiago_description/robots/tiago.urdf", [], ""),
    ("tiago_no_hand", "tiago_description/robots/tiago_no_hand.urdf", [], "variant"),
    ("tiago_dual", "tiago_description/robots/tiago_dual.urdf", ["--tip", "arm_right_tool_link"], "right arm"),
    ("tiago_pro", "tiago_pro_description/robots/tiago_pro.urdf", ["--tip", "arm_right_tool_link"], "right arm"),
    ("baxter", "baxter_description/urdf/baxter.urdf", ["--tip", "right_gripper"], "right arm"),
    ("pr2", "pr2_description/urdf/pr2.urdf", ["--tip", "r_gripper_tool_frame"], "right arm"),
    ("anymal_kinova", "anymal_b_simple_description/robots/anymal-kinova.urdf", [], "arm on a quadruped, base fixed"),
    ("b1_z1", "b1_description/urdf/b1-z1.urdf", ["--tip", "gripperStator"], "arm on a quadruped, base fixed"),
    ("centauro", "centauro_description/urdf/centauro.urdf", ["--tip", "ball2_tip"], "arm 2"),
    ("borinot_flying_arm_2", "borinot_description/urdf/borinot_flying_arm_2.urdf", [], "arm on a drone, base fixed"),
    ("hextilt_flying_arm_5", "hextilt_description/urdf/hextilt_flying_arm_5.urdf", [], "arm on a drone, base fixed"),
    ("twodofs", "asr_twodof_description/urdf/TwoDofs.urdf", [], ""),
    ("double_pendulum", "double_pendulum_description/urdf/double_pendulum.urdf", [], ""),
    ("double_pendulum_continuous", "double_pendulum_description/urdf/double_pendulum_continuous.urdf", [], ""),
    ("double_pendulum_simple", "double_pendulum_description/urdf/double_pendulum_simple.urdf", [], ""),
    ("finger_edu", "finger_edu_description/robots/finger_edu.urdf", [], ""),
    ("romeo", "romeo_description/urdf/romeo.urdf", ["--tip", "r_gripper"], "right arm, base fixed"),
    ("icub", "icub_description/robots/icub.urdf", ["--tip", "r_hand"], "right arm, base fixed"),
    ("g1", "g1_description/urdf/g1_29dof_rev_1_0.urdf", ["--tip", "right_rubber_hand"], "right arm, base fixed"),
    ("alex", "alex_description/urdf/alex_nub_hands.urdf", ["--tip", "RightGripperYawLink"], "right arm"),
    ("human", "human_description/robots/human.urdf", ["--tip", "right_hand"], "right arm, base fixed"),
    ("simple_humanoid", "simple_humanoid_description/urdf/simple_humanoid.urdf", ["--tip", "r_wrist"], "right arm, base fixed"),
]

# Robots without an arm chain (legs, rotors, fingers): only `osrl robot` runs, which should refuse them.
NOT_ARMS = [
    ("a1", "a1_description/urdf/a1.urdf"),
    ("alexander_lower_body", "alexander_description/urdf/alexander_v1.lowerBodyOnly.urdf"),
    ("allegro_left_hand", "allegro_hand_description/urdf/allegro_left_hand.urdf"),
    ("allegro_right_hand", "allegro_hand_description/urdf/allegro_right_hand.urdf"),
    ("anymal_b", "anymal_b_simple_description/robots/anymal.urdf"),
    ("anymal_c", "anymal_c_simple_description/urdf/anymal.urdf"),
    ("b1", "b1_description/urdf/b1.urdf"),
    ("bolt", "bolt_description/robots/bolt.urdf"),
    ("go1", "go1_description/urdf/go1.urdf"),
    ("go2", "go2_description/urdf/go2.urdf"),
    ("hector", "hector_description/robots/quadrotor_base.urdf"),
    ("hyq", "hyq_description/robots/hyq_no_sensors.urdf"),
    ("iris", "iris_description/robots/iris.urdf"),
    ("iris_simple", "iris_description/robots/iris_simple.urdf"),
    ("laikago", "laikago_description/urdf/laikago.urdf"),
    ("quadruped", "quadruped_description/urdf/quadruped.urdf"),
    ("solo", "solo_description/robots/solo.urdf"),
    ("solo12", "solo_description/robots/solo12.urdf"),
]


def run(cmd, out_prefix):
    """Runs cmd, keeps stdout/stderr next to out_prefix; returns (rc, last stdout line, stderr)."""
    p = subprocess.run(cmd, capture_output=True, text=True)
    with open(out_prefix + ".out", "w") as f:
        f.write(p.stdout)
    with open(out_prefix + ".err", "w") as f:
        f.write(p.stderr)
    lines = [l for l in p.stdout.splitlines() if l.strip()]
    return p.returncode, (lines[-1] if lines else ""), p.stderr.strip()


def error_text(stderr, robots):
    """The refusal's message, one line, without the robots folder's path."""
    lines = [l for l in stderr.splitlines() if l.startswith("error")] or stderr.splitlines()[-1:]
    return " ".join(lines).replace(robots.rstrip("/") + "/", "").replace("|", "/")


def measure(args, name, rel, opts):
    f = os.path.join(args.robots, rel)
    base = os.path.join(args.runs, name)
    row = {"name": name, "file": rel, "opts": opts}
    rc, last, err = run([args.osrl, "robot", "--robot", f, "--json", *opts], base + ".robot")
    if rc != 0:
        row["refused"] = error_text(err, args.robots)
        return row
    info = json.loads(last)
    row["dof"] = info["dof"]
    row["tip"] = info["profile"].get("tip")
    rc, last, err = run([args.osrl, "simulate", "--robot", f, "--json", *opts], base + ".eq7")
    if rc != 0:
        row["refused"] = error_text(err, args.robots)
        return row
    row["eq7"] = json.loads(last)
    train_json = base + ".train.json"
    if not args.no_train and not os.path.exists(train_json):
        cmd = [args.osrl, "train", "--robot", f, *opts, "--minutes", str(args.minutes),
               "--seed", str(args.seed), "--json", "--out", base + ".model"]
        rc, last, err = run(cmd, base + ".train")
        if rc == 0:
            with open(train_json, "w") as out:
                out.write(last + "\n")
        else:
            row["train_error"] = error_text(err, args.robots)
    elif not os.path.exists(train_json) and os.path.exists(base + ".train.err"):
        with open(base + ".train.err") as fh:
            err = fh.read()
        if "rror" in err:
            row["train_error"] = error_text(err, args.robots)
    if os.path.exists(train_json):
        with open(train_json) as fh:
            row["train"] = json.loads(fh.read())
    return row


def fmt_train(t):
    if t is None:
        return "—"
    div = ", diverged" if t.get("diverged") else ""
    curve = [p for p in t.get("learning_curve", []) if not p.get("diverged")]
    best = min(curve, key=lambda p: p["tracking_rms_mm"], default=None)
    best = f"; best {best['tracking_rms_mm']:.3g} mm at minute {best['sim_minutes']:.0f}" if best else ""
    unsettled = f", {t['unsettled_starts']} unsettled starts" if t.get("unsettled_starts") else ""
    stage = f"; highest stage {t['max_stage']}" if t.get("max_stage") is not None else ""
    return (f"{t['tracking_rms_mm']:.3g} mm, nMSE {t['command_nmse']:.3g}{div} "
            f"({t['episodes']} episodes, {t['aborted_episodes']} aborted, "
            f"{t['braked_episodes']} braked ({t.get('braked_on_step', 0)} on a jump), "
            f"{t['clipped_on_policy']} clipped{unsettled}; max step {t['max_command_step']:.2f} N·m vs "
            f"analytical {t['max_command_step_analytical']:.2f}; "
            f"rejected {100 * t.get('rejected_share', 0):.3g} %{best}{stage})")


def check_not_arm(args, name, rel):
    """`osrl robot` on a robot without an arm: the refusal's message, or what it loaded as."""
    f = os.path.join(args.robots, rel)
    rc, last, err = run([args.osrl, "robot", "--robot", f, "--json"], os.path.join(args.runs, name + ".robot"))
    if rc != 0:
        return {"name": name, "file": rel, "refused": error_text(err, args.robots)}
    info = json.loads(last)
    return {"name": name, "file": rel,
            "loaded": f"loads (not refused): {info['dof']} DOF, tip `{info['profile'].get('tip')}`"}


def not_arms_table(rows):
    out = ["| robot (file) | `osrl robot` |", "|---|---|"]
    for r in rows:
        out.append(f"| {r['name']} (`{os.path.basename(r['file'])}`) | {r.get('refused') or r['loaded']} |")
    return "\n".join(out)


def table(rows):
    """Two Markdown tables: the robots that load and track (eq. 7, learned), the refused ones."""
    out = ["| robot (file, options) | DOF | tip | eq. 7 RMS (mm) | learned |",
           "|---|---|---|---|---|"]
    refused = ["| robot (file, options) | the error |", "|---|---|"]
    for r in rows:
        opts = " " + " ".join(r["opts"]) if r["opts"] else ""
        label = f"{r['name']} (`{os.path.basename(r['file'])}`{opts})"
        if "refused" in r:
            refused.append(f"| {label} | {r['refused']} |")
            continue
        eq7 = r["eq7"]["tracking_rms_mm"]
        learned = r.get("train_error") and "train failed: " + r["train_error"] or fmt_train(r.get("train"))
        out.append(f"| {label} | {r['dof']} | `{r['tip']}` | {eq7:.4f} | {learned} |")
    return "\n".join(out) + "\n\nRefused:\n\n" + "\n".join(refused)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--osrl", required=True)
    ap.add_argument("--robots", required=True)
    ap.add_argument("--runs", required=True)
    ap.add_argument("--minutes", type=float, default=30)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--no-train", action="store_true")
    ap.add_argument("--only", nargs="*")
    args = ap.parse_args()
    os.makedirs(args.runs, exist_ok=True)
    rows = []
    for name, rel, opts, _note in ARMS:
        if args.only and name not in args.only:
            continue
        print(f"{name} ...", file=sys.stderr, flush=True)
        rows.append(measure(args, name, rel, opts))
    others = []
    for name, rel in NOT_ARMS:
        if args.only and name not in args.only:
            continue
        print(f"{name} (not an arm) ...", file=sys.stderr, flush=True)
        others.append(check_not_arm(args, name, rel))
    print(table(rows))
    if others:
        print("\nNot arms (only `osrl robot`, which should refuse them):\n")
        print(not_arms_table(others))


if __name__ == "__main__":
    main()
