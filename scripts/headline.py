#!/usr/bin/env python3
"""Prints the README's headline tables (markdown) from an `osrl reproduce` report's results.json,
so the numbers the README quotes are the ones of a run: `python3 scripts/headline.py report/`."""
import json, pathlib, sys


def num(v, fmt="{:.3g}"):
    """A number, or the status of what replaced it."""
    if isinstance(v, (int, float)):
        return fmt.format(v)
    if isinstance(v, dict):
        return v.get("status", "–")
    return "–"


def mean(v, fmt):
    """The mean of a `{mean, min, max}` summary (or the status that replaced it)."""
    return num(v.get("mean", v) if isinstance(v, dict) else v, fmt)


def main():
    out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "report")
    r = json.loads((out / "results.json").read_text())
    print(f"Full run: {r['wall_seconds'] / 60:.1f} min wall, seeds {r['seeds']}.\n")
    print("| robot | minutes | tracking RMS per seed (mm) | command nMSE per seed | cost ratio (mean) "
          "| local models (mean) | real-time factor (min–max) | largest on-policy command step (N·m) "
          "| eq. 7 tracking (mm) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for robot, e in r["E3"].items():
        if "per_seed" not in e:
            print(f"| {robot} | {num(e)} |")
            continue
        seeds = e["per_seed"]
        track = " / ".join(num(s.get("tracking_rms_mm"), "{:.2f}") if s.get("evaluated") else "diverged" for s in seeds)
        nmse = " / ".join(num(s.get("command_nmse"), "{:.3f}") if s.get("evaluated") else "diverged" for s in seeds)
        rt = e["realtime_factor"]
        print(f"| {robot} | {mean(e['sim_training_minutes'], '{:.0f}')} | {track} | {nmse} "
              f"| {mean(e['command_cost_ratio'], '{:.3f}')} | {mean(e['n_local_models'], '{:.0f}')} "
              f"| {rt['min']:.1f}–{rt['max']:.1f} | {num(e['max_command_step']['max'], '{:.1f}')} "
              f"| {num(e.get('analytical_eq7_tracking_rms_mm'), '{:.3f}')} |")
    print("\nE6 ablation (final evaluation of seed 0, the seed every variant has; cost ratio and local models: mean over seeds):\n")
    print("| robot | variant | tracking RMS (mm) | command nMSE | cost ratio | local models |")
    print("|---|---|---|---|---|---|")
    for robot, rows in r["E6"].items():
        for key, row in rows.items():
            if "tracking_rms_mm" not in row:
                print(f"| {robot} | {key} | {num(row)} | | | |")
                continue
            s0 = row["per_seed"][0]
            first = [("diverged, " if s0.get("diverged") else "") + num(s0.get(k), f)
                     if s0.get("evaluated") else "not evaluated"
                     for k, f in [("tracking_rms_mm", "{:.3f}"), ("command_nmse", "{:.4f}")]]
            cells = first + [mean(row[k], f) for k, f in [("command_cost_ratio", "{:.3f}"), ("n_local_models", "{:.0f}")]]
            print(f"| {robot} | {key} | " + " | ".join(cells) + " |")
    print("\nE7 model errors (tracking RMS, mm):\n")
    print("| robot | model error | eq. 7 with the wrong model | learned (trained on the true robot) |")
    print("|---|---|---|---|")
    for robot, rows in r["E7"].items():
        for key, row in rows.items():
            print(f"| {robot} | {key} | {num(row.get('analytical_eq7_tracking_rms_mm'), '{:.3f}')} "
                  f"| {mean(row.get('learned_tracking_rms_mm'), '{:.3f}')} |")


if __name__ == "__main__":
    main()
