#!/usr/bin/env python3
"""Compares two `osrl reproduce` results.json files number by number, ignoring the timing fields
(wall seconds, real-time factors, µs per command), and prints every difference: a changed value,
a key present in one file only, a changed type or list length. Exit status 1 if there is any.

    python3 scripts/compare_results.py A/results.json B/results.json   (or the two folders)
    python3 scripts/compare_results.py A B --ignore config.learner_defaults
(`--ignore P`, repeatable: leave out the subtree at path P, e.g. settings whose layout changed.)
"""
import json, math, pathlib, sys

# Keys whose values measure time on this machine, not the experiments' numbers.
TIMING = {"wall_seconds", "realtime_factor", "real_time_factor", "command_us_median", "command_us_p99"}


def load(p):
    p = pathlib.Path(p)
    return json.loads((p / "results.json" if p.is_dir() else p).read_text())


def same_number(a, b):
    return a == b or (isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b))


def compare(a, b, path, out, ignore=()):
    if path.lstrip(".") in ignore:
        return
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b)):
            if k in TIMING:
                continue
            if k not in b:
                out.append(f"{path}.{k}: only in the first")
            elif k not in a:
                out.append(f"{path}.{k}: only in the second")
            else:
                compare(a[k], b[k], f"{path}.{k}", out, ignore)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            out.append(f"{path}: {len(a)} entries vs {len(b)}")
        for i, (x, y) in enumerate(zip(a, b)):
            compare(x, y, f"{path}[{i}]", out, ignore)
    elif type(a) is not type(b) and not (isinstance(a, (int, float)) and isinstance(b, (int, float))
                                         and not isinstance(a, bool) and not isinstance(b, bool)):
        out.append(f"{path}: {a!r} vs {b!r} (types differ)")
    elif not same_number(a, b):
        out.append(f"{path}: {a!r} vs {b!r}")


def main():
    args, ignore = sys.argv[1:], []
    while "--ignore" in args:
        i = args.index("--ignore")
        ignore.append(args[i + 1])
        del args[i:i + 2]
    if len(args) != 2:
        sys.exit(__doc__)
    out = []
    compare(load(args[0]), load(args[1]), "", out, tuple(ignore))
    for line in out:
        print(line.lstrip("."))
    left_out = f", {ignore} left out" if ignore else ""
    print(f"{len(out)} differences (timing fields {sorted(TIMING)} ignored{left_out})")
    sys.exit(1 if out else 0)


if __name__ == "__main__":
    main()
