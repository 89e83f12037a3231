#!/usr/bin/env python3
"""The README's performance tables, generated from the JSON of `osrl bench references --json`.

    python3 scripts/bench_tables.py docs/bench/references-DATE.json          # rewrite
    python3 scripts/bench_tables.py docs/bench/references-DATE.json --check  # fail if stale

crates/lwpr/README.md gets `osrl bench references --markdown --from JSON` (date, CPU model,
load, every table) between its `<!-- bench-references:begin/end -->` markers; the root README
gets a one-line summary of the ratios between the same markers. Nothing else is touched.
"""
import json
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
BEGIN, END = "<!-- bench-references:begin -->", "<!-- bench-references:end -->"


def splice(text: str, body: str, where: str) -> str:
    """`text` with everything between the markers replaced by `body`."""
    if text.count(BEGIN) != 1 or text.count(END) != 1 or text.index(BEGIN) > text.index(END):
        sys.exit(f"{where}: needs exactly one {BEGIN} ... {END} pair, in that order")
    head, rest = text.split(BEGIN)
    _, tail = rest.split(END)
    return f"{head}{BEGIN}\n{body.strip()}\n{END}{tail}"


def ratio(x) -> str:
    return f"{x:.1f}×" if isinstance(x, (int, float)) else "?"


def summary(out: dict, source: str) -> str:
    """One line: C / crate ratios per LWPR data set, Pinocchio / crate per dynamics call."""
    m = out.get("machine", {})
    parts = []
    for key, v in out.get("lwpr", {}).items():
        if "skipped" in v:
            parts.append(f"{key} skipped ({v['skipped']})")
            continue
        parts.append(
            f"{key} ({v.get('seeds', '?')} seeds × {v.get('epochs', '?')} epochs) update "
            f"{ratio(v.get('ratio_update_us_c_o2'))} / predict "
            f"{ratio(v.get('ratio_predict_us_c_o2'))} the C library at -O2 "
            f"({ratio(v.get('ratio_update_us_c_o3_native'))} / "
            f"{ratio(v.get('ratio_predict_us_c_o3_native'))} at -O3 native)"
        )
        if "ratio_update_us_batch_c_o2" in v:
            parts[-1] += (
                f" or, timed as whole loops, {ratio(v.get('ratio_update_us_batch_c_o2'))} / "
                f"{ratio(v.get('ratio_predict_us_batch_c_o2'))} "
                f"({ratio(v.get('ratio_update_us_batch_c_o3_native'))} / "
                f"{ratio(v.get('ratio_predict_us_batch_c_o3_native'))})"
            )
    lwpr = "; ".join(parts) if parts else "not measured"
    d = out.get("dynamics")
    if d is None:
        dyn = "not measured"
    elif "skipped" in d:
        dyn = f"skipped ({d['skipped']})"
    else:
        r = d.get("ratio", {})
        names = [("fk_jacobian_ns", "FK + Jacobian"), ("rnea_ns", "RNEA"), ("crba_ns", "CRBA"), ("aba_ns", "ABA")]
        dyn = ", ".join(f"{label} {ratio(r.get('sarcos7/' + k))}" for k, label in names)
        dyn = f"sarcos7 {dyn} Pinocchio's C++ library (its time / the crate's)"
    return (
        f"**Speed against the references** (`osrl bench references --json`, saved as `{source}`; "
        f"{m.get('date', '?')}, {m.get('cpu', '?')}, {m.get('cores', '?')} cores, load average "
        f"{m.get('loadavg', '?')} at the start; ratios measured in one run, C/Pinocchio and the crate "
        f"interleaved): LWPR (C time / crate time) {lwpr}. Dynamics: {dyn}. Tables: "
        f"`crates/lwpr/README.md`, \"Against the reference library\". Issue 31's targets: LWPR ≥ 5× "
        f"(-O2) and ≥ 3× (-O3 native) on the crosses, SARCOS update ≥ 20×; dynamics ≥ 1.5×."
    )


def main() -> None:
    args = [a for a in sys.argv[1:] if a != "--check"]
    if len(args) != 1:
        sys.exit(__doc__)
    src = pathlib.Path(args[0])
    try:
        out = json.loads(src.read_text())
    except (OSError, ValueError) as e:
        sys.exit(f"{src}: not the JSON of osrl bench references ({e})")
    if not isinstance(out, dict) or "machine" not in out:
        sys.exit(f"{src}: not the JSON of osrl bench references (no 'machine' key)")
    rel = src.resolve().relative_to(ROOT) if src.resolve().is_relative_to(ROOT) else src
    tables = subprocess.run(
        ["cargo", "run", "--release", "-q", "--", "bench", "references", "--markdown", "--from", str(src)],
        cwd=ROOT, check=True, capture_output=True, text=True,
    ).stdout
    stale = []
    for path, body in [(ROOT / "crates/lwpr/README.md", tables), (ROOT / "README.md", summary(out, str(rel)))]:
        old = path.read_text()
        new = splice(old, body, str(path))
        if new != old:
            stale.append(str(path.relative_to(ROOT)))
            if "--check" not in sys.argv:
                path.write_text(new)
    if "--check" in sys.argv and stale:
        sys.exit(f"stale performance tables in {', '.join(stale)}: run python3 scripts/bench_tables.py {src}")
    print(("rewrote " + ", ".join(stale)) if stale and "--check" not in sys.argv else "tables up to date")


if __name__ == "__main__":
    main()
