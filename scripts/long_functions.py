#!/usr/bin/env python3
"""Lists Rust functions longer than a limit (default 60 lines, body included) under the given
directories; exits 1 if there is any. Usage: scripts/long_functions.py [--max N] DIR...

A function starts at a line whose code begins with `fn`/`pub fn`/`pub(crate) fn`/... and ends at
the matching closing brace (braces counted outside strings, chars and comments, roughly)."""
import re
import sys
from pathlib import Path

FN = re.compile(r"^\s*(pub(\([^)]*\))?\s+)?(const\s+|async\s+|unsafe\s+)*fn\s+(\w+)")


def strip(line: str) -> str:
    line = re.sub(r'"(\\.|[^"\\])*"', '""', line)
    line = re.sub(r"'(\\.|[^'\\])'", "''", line)
    return line.split("//", 1)[0]


def functions(path: Path):
    lines = path.read_text().splitlines()
    i = 0
    while i < len(lines):
        m = FN.match(lines[i])
        if not m:
            i += 1
            continue
        depth, started, j = 0, False, i
        while j < len(lines):
            code = strip(lines[j])
            if not started and ";" in code and "{" not in code:
                break  # a declaration without body
            depth += code.count("{") - code.count("}")
            started |= "{" in code
            if started and depth <= 0:
                break
            j += 1
        yield m.group(4), i + 1, j - i + 1
        i += 1


def main() -> int:
    args = sys.argv[1:]
    limit = 60
    if args[:1] == ["--max"]:
        limit, args = int(args[1]), args[2:]
    bad = []
    for d in args:
        for p in sorted(Path(d).rglob("*.rs")):
            for name, line, length in functions(p):
                if length > limit:
                    bad.append((length, f"{p}:{line} {name}"))
    for length, where in sorted(bad, reverse=True):
        print(f"{length:4d} {where}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
