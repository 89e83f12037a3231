#!/usr/bin/env python3
"""Checks an `osrl reproduce` report folder: results.json has E1..E8 (and E9 where it ran), config, seeds and
wall_seconds; every number outside `config` is finite (serde_json writes NaN/inf as null, so no null is allowed);
no experiment reports a failed run; index.html inlines every figure; the PNGs exist."""
import json, math, pathlib, sys

out = pathlib.Path(sys.argv[1])
r = json.loads((out / "results.json").read_text())
errors = []

# Measured "never" outcomes: the first minute at which a target was met, null if it never was.
NULLABLE = ("minutes_to_1mm", "minutes_to_nmse_0_05", "minutes_to_2x_nominal",
            "minutes_to_1mm_stable", "minutes_to_2x_nominal_stable")
# E8's timelines: null marks an evaluation that diverged (drawn as a gap).
TIMELINE = ("adapting_mm", "frozen_mm", "eq7_stale_mm")

# E8's rows name the numbers that are null because their evaluation diverged (error > 0.2 m).
E8_DIVERGED = set()
for robot, rows in r.get("E8", {}).items():
    for change, row in rows.items():
        for name in row.get("diverged", []):
            E8_DIVERGED.add(f"E8.{robot}.{change}.{name}")

def walk(v, path):
    if v is None and path in E8_DIVERGED:
        return
    if v is None and path.rsplit(".", 1)[-1] in NULLABLE:
        return
    if v is None and ".timeline." in path and path.rsplit(".", 1)[-1].split("[")[0] in TIMELINE:
        return
    if v is None:
        errors.append(f"{path}: null (a NaN/inf or a missing number)")
    elif isinstance(v, float) and not math.isfinite(v):
        errors.append(f"{path}: {v}")
    elif isinstance(v, dict):
        if v.get("status") == "failed":
            errors.append(f"{path}: failed: {v.get('errors')}")
        for k, x in v.items():
            walk(x, f"{path}.{k}")
    elif isinstance(v, list):
        for i, x in enumerate(v):
            walk(x, f"{path}[{i}]")

for key in [f"E{i}" for i in range(1, 9)] + ["config", "seeds", "wall_seconds"]:
    if key not in r:
        errors.append(f"missing {key}")
    elif key.startswith("E") and not r[key]:
        errors.append(f"{key} is empty")
# `config` holds settings, where null means "unset" (an Option); everything else is measured.
for key, v in r.items():
    if key != "config":
        walk(v, key)
for robot in ["planar3", "sarcos7"]:
    for key in ["E3", "E4", "E5", "E6", "E7", "E8"]:
        if robot not in r.get(key, {}):
            errors.append(f"{key} has no {robot}")
    e3 = r.get("E3", {}).get(robot, {})
    t = e3.get("tracking_rms_mm", {})
    if "mean" not in t and t.get("status") != "diverged":
        errors.append(f"E3.{robot}: no tracking error")
    # The learning-safety record of every training run (issue 25).
    safety = e3.get("safety", [])
    if len(safety) != e3.get("runs", -1):
        errors.append(f"E3.{robot}: {len(safety)} safety rows for {e3.get('runs')} runs")
    for i, row in enumerate(safety):
        for k in ["aborted_episodes", "braked_episodes", "clipped_on_policy", "max_command_step",
                  "max_torque_rate", "max_command_step_analytical", "step_curve"]:
            if k not in row:
                errors.append(f"E3.{robot}.safety[{i}]: no {k}")
    # E8 (issue 26): every change, its timeline of three lines, the recovery times.
    e8 = r.get("E8", {}).get(robot, {})
    for change in ["payload", "mass_x1.3", "friction_x2"]:
        row = e8.get(change)
        if row is None:
            errors.append(f"E8.{robot}: no {change}")
            continue
        for k in ["nominal_tracking_rms_mm", "frozen_tracking_rms_mm", "eq7_stale_tracking_rms_mm",
                  "adapted_tracking_rms_mm", "minutes_to_1mm", "minutes_to_2x_nominal",
                  "minutes_to_1mm_stable", "minutes_to_2x_nominal_stable", "aborted_episodes", "max_command_step", "diverged", "timeline"]:
            if k not in row:
                errors.append(f"E8.{robot}.{change}: no {k}")
        tl = row.get("timeline", {})
        n = len(tl.get("sim_minutes", []))
        if n < 4 or any(len(tl.get(k, [])) != n for k in TIMELINE):
            errors.append(f"E8.{robot}.{change}: timeline of {n} points, lines of other lengths")
    if "after_removal" not in e8.get("payload", {}):
        errors.append(f"E8.{robot}.payload: no after_removal")
# E9 (issue 27): when the sizes ask for it, every E9 robot has seeds, held-out paths of every
# kind, and per path and seed both controllers' tracking, nMSE and support share, and the bound.
e9_sizes = r.get("config", {}).get("sizes", {}).get("e9", {})
for robot in ["planar3", "sarcos7"]:
    want = e9_sizes.get(f"{robot}_seeds", 0)
    if not want:
        continue
    row = r.get("E9", {}).get(robot)
    if row is None:
        errors.append(f"E9 has no {robot}")
        continue
    if row.get("failed"):
        errors.append(f"E9.{robot}: failed runs {row['failed']}")
    if len(row.get("seeds", [])) != want:
        errors.append(f"E9.{robot}: seeds {row.get('seeds')} for {want} asked")
    paths = row.get("paths", [])
    if len(paths) != 3 * e9_sizes.get("paths_per_kind", 0):
        errors.append(f"E9.{robot}: {len(paths)} held-out paths")
    for kind in ["figure-8", "circle", "min-jerk"]:
        if not any(p["label"].startswith(kind) for p in paths):
            errors.append(f"E9.{robot}: no held-out {kind}")
    for i, p in enumerate(paths):
        for side in ["figure8_only", "family"]:
            pts = p.get(side, [])
            if len(pts) != want:
                errors.append(f"E9.{robot}.paths[{i}].{side}: {len(pts)} seeds")
            for x in pts:
                for k in ["tracking_rms_mm", "command_nmse", "support_share"]:
                    if k not in x:
                        errors.append(f"E9.{robot}.paths[{i}].{side}: no {k}")
                if not 0.0 <= x.get("support_share", -1) <= 1.0:
                    errors.append(f"E9.{robot}.paths[{i}].{side}: support_share out of [0, 1]")
        if len(p.get("family_within_bounds", [])) != want:
            errors.append(f"E9.{robot}.paths[{i}]: no bound per seed")
html = (out / "index.html").read_text()
svgs = sorted(out.glob("E*/**/*.svg"))
if html.count("<svg") < 10 or html.count("<figcaption>") != html.count("<svg"):
    errors.append(f"index.html: {html.count('<svg')} inline SVGs, {html.count('<figcaption>')} captions")
for s in svgs:
    if not s.with_suffix(".png").exists():
        errors.append(f"{s} has no PNG")
if errors:
    print("report check failed:\n  " + "\n  ".join(errors[:40]))
    sys.exit(1)
n_div = json.dumps(r).count('"diverged": true')
e9_robots = ", ".join(sorted(r.get("E9", {})))
print(f"report check: E1..E8 present{f', E9 for {e9_robots}' if e9_robots else ''}, all numbers finite, {html.count('<svg')} figures inline, "
      f"{len(svgs)} SVG+PNG pairs, {n_div} diverged evaluations reported, wall {r['wall_seconds']:.0f} s")
