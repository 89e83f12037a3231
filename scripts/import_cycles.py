#!/usr/bin/env python3
"""Import circles between the files of a Rust crate.

Builds the graph of file-level module dependencies of a crate from its source and reports every
circle (a strongly connected component of more than one file), with the lines that make each
edge; exits with status 1 when there is one, 0 when there is none, 2 on bad usage.

Usage:
  python3 scripts/import_cycles.py crates/lwpr/src [crates/learn/src ...] [--edges]

How the graph is built (no compiler needed, so a few constructs are approximations):
- The module tree: from `lib.rs` (else `main.rs`) through `mod name;` declarations, with the
  usual file rules (`name.rs` or `name/mod.rs`, next to a mod-rs file or in the folder named
  after a non-mod-rs file) and `#[path = "..."]` attributes. Files not reached are ignored.
- Each file's paths, with comments, strings and character literals removed first: every `use`
  tree (braces, `self`, renames) and every path starting with `crate`, `self` or `super`
  elsewhere in the code, plus paths that start with a module declared in the file. Inline
  modules (`mod tests { ... }`) belong to their file, but `super` inside them counts from the
  inline module.
- A path names the deepest module file it walks through; when its next segment is an item that
  module re-exports (`pub use a::X`, `pub(crate) use a::{X, Y}`, `pub use a::*`), the edge goes to
  the module the item comes from, so `use crate::Lwpr` in a crate whose `lib.rs` re-exports
  `model::Lwpr` depends on `model.rs`, not on `lib.rs`.
- `mod x;` itself is not an edge (declaring a child is structure, not use), nor is a path into
  the file itself. An external crate's path (`std::`, `nalgebra::`) is not an edge.
"""

import os
import re
import sys

ITEM_RE = re.compile(
    r"\b(?:fn|struct|enum|union|trait|type|const|static|mod)\s+([A-Za-z_]\w*)"
    r"|\bmacro_rules!\s*([A-Za-z_]\w*)"
)
MOD_DECL_RE = re.compile(
    r"((?:#\s*\[[^\]]*\]\s*)*)(?:pub(?:\s*\([^)]*\))?\s+)?mod\s+([A-Za-z_]\w*)\s*([;{])"
)
PATH_ATTR_RE = re.compile(r'#\s*\[\s*path\s*=\s*"([^"]*)"\s*\]')
USE_RE = re.compile(r"\b((?:pub(?:\s*\([^)]*\))?\s+)?)use\s+([^;]+);")
PATH_RE = re.compile(r"(?<![\w$:])((?:crate|self|super|[A-Za-z_]\w*)(?:\s*::\s*[A-Za-z_]\w*)+)")


def strip_code(src):
    """The source with comments, string and char literals blanked (newlines kept, so that line
    numbers stay right)."""
    out = []
    i, n = 0, len(src)

    def blank(s):
        return "".join(c if c == "\n" else " " for c in s)

    while i < n:
        c = src[i]
        if src.startswith("//", i):
            j = src.find("\n", i)
            j = n if j < 0 else j
            out.append(blank(src[i:j]))
            i = j
        elif src.startswith("/*", i):
            depth, j = 1, i + 2
            while j < n and depth:
                if src.startswith("/*", j):
                    depth, j = depth + 1, j + 2
                elif src.startswith("*/", j):
                    depth, j = depth - 1, j + 2
                else:
                    j += 1
            out.append(blank(src[i:j]))
            i = j
        elif c == "r" and re.match(r'r#*"', src[i:i + 300]) and (i == 0 or not (src[i - 1].isalnum() or src[i - 1] == "_")):
            m = re.match(r'r(#*)"', src[i:])
            end = src.find('"' + m.group(1), i + len(m.group(0)))
            j = n if end < 0 else end + 1 + len(m.group(1))
            out.append(blank(src[i:j]))
            i = j
        elif c == '"':
            j = i + 1
            while j < n and src[j] != '"':
                j += 2 if src[j] == "\\" else 1
            out.append(blank(src[i:j + 1]))
            i = j + 1
        elif c == "'":
            # A char literal ('a', '\n', '\u{..}') or a lifetime ('a): only the former is blanked.
            m = re.match(r"'(?:\\.[^']*|[^\\'])'", src[i:i + 12])
            if m:
                out.append(blank(m.group(0)))
                i += len(m.group(0))
            else:
                out.append(c)
                i += 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def parse_use_tree(text):
    """`a::{b, c::{self, D}, f::*}` -> [['a','b'], ['a','c'], ['a','c','D'], ['a','f','*']]
    (renames already removed, see `use_paths`)."""
    paths = []

    def parse(s, prefix):
        if s.startswith("::"):
            s = s[2:]
        if "{" not in s:
            full = prefix + [p for p in s.split("::") if p]
            if full and full[-1] == "self":
                full = full[:-1]
            if full:
                paths.append(full)
            return
        k = s.index("{")
        head = [p for p in s[:k].split("::") if p]
        inner = s[k + 1:s.rindex("}")]
        depth, start = 0, 0
        for j, ch in enumerate(inner):
            if ch == "{":
                depth += 1
            elif ch == "}":
                depth -= 1
            elif ch == "," and depth == 0:
                if inner[start:j]:
                    parse(inner[start:j], prefix + head)
                start = j + 1
        if inner[start:]:
            parse(inner[start:], prefix + head)

    parse(re.sub(r"\s+", "", text), [])
    return paths


def use_paths(text):
    """The paths of one `use` tree, renames (`X as Y`) reduced to `X`."""
    return parse_use_tree(re.sub(r"\s+as\s+[A-Za-z_]\w*", "", text))


class Module:
    def __init__(self, path, file, is_mod_rs):
        self.path = path  # tuple of segments from the crate root
        self.file = file
        self.is_mod_rs = is_mod_rs
        self.children = {}  # name -> Module (file modules only)
        self.code = ""
        self.items = set()
        self.reexports = {}  # name -> full path (list), for pub/pub(crate) use
        self.globs = []  # full paths of glob re-exports
        self.inline = []  # (start, end, name) spans of inline modules


def line_of(code, pos):
    return code.count("\n", 0, pos) + 1


def find_block_end(code, brace):
    depth = 0
    for j in range(brace, len(code)):
        if code[j] == "{":
            depth += 1
        elif code[j] == "}":
            depth -= 1
            if depth == 0:
                return j
    return len(code)


def load_tree(src_dir):
    root_file = None
    for name in ("lib.rs", "main.rs"):
        if os.path.isfile(os.path.join(src_dir, name)):
            root_file = os.path.join(src_dir, name)
            break
    if root_file is None:
        raise SystemExit(f"{src_dir}: no lib.rs or main.rs")
    modules = {}

    def visit(path, file, is_mod_rs):
        m = Module(path, file, is_mod_rs)
        modules[path] = m
        with open(file, encoding="utf-8") as f:
            orig = f.read()
        m.code = strip_code(orig)  # the same length: positions match `orig`
        for mt in ITEM_RE.finditer(m.code):
            m.items.add(mt.group(1) or mt.group(2))
        base = os.path.dirname(file)
        child_dir = base if is_mod_rs else os.path.join(base, os.path.splitext(os.path.basename(file))[0])
        for md in MOD_DECL_RE.finditer(m.code):
            # Attributes from the original text (`strip_code` blanked their strings).
            attrs, name, kind = orig[md.start(1):md.end(1)], md.group(2), md.group(3)
            if kind == "{":
                brace = md.end() - 1
                m.inline.append((brace, find_block_end(m.code, brace), name))
                continue
            if any(s < md.start() < e for s, e, _ in m.inline):
                continue  # a file module inside an inline module: not followed
            pa = PATH_ATTR_RE.search(attrs)
            if pa:
                pf = os.path.normpath(os.path.join(base, pa.group(1)))
                cand = [(pf, os.path.basename(pf) == "mod.rs")]
            else:
                cand = [
                    (os.path.join(child_dir, name + ".rs"), False),
                    (os.path.join(child_dir, name, "mod.rs"), True),
                ]
            for cf, cmr in cand:
                if os.path.isfile(cf):
                    m.children[name] = visit(path + (name,), cf, cmr)
                    break
        return m

    visit((), root_file, True)
    return modules


def inline_depth(m, pos):
    """Names of the inline modules enclosing `pos` (outermost first)."""
    return [name for s, e, name in sorted(m.inline) if s < pos < e]


def raw_paths(m):
    """(position, [segments], is_reexport) for every path in the file."""
    out = []
    use_spans = []
    for u in USE_RE.finditer(m.code):
        use_spans.append((u.start(), u.end()))
        vis = u.group(1).strip()
        for p in use_paths(u.group(2)):
            out.append((u.start(), p, bool(vis)))
    for pm in PATH_RE.finditer(m.code):
        if any(s <= pm.start() < e for s, e in use_spans):
            continue
        segs = [s for s in re.split(r"\s*::\s*", pm.group(1)) if s]
        out.append((pm.start(), segs, False))
    return out


def resolve_start(modules, m, pos, segs):
    """The module the path starts in and the remaining segments, or None for an external path."""
    here = m.path + tuple(inline_depth(m, pos))
    first = segs[0]
    if first == "crate":
        cur, rest = (), segs[1:]
    elif first in ("self", "super"):
        cur, rest = here, segs
        while rest and rest[0] in ("self", "super"):
            if rest[0] == "super":
                cur = cur[:-1]
            rest = rest[1:]
    elif here + (first,) in modules:
        cur, rest = here, segs
    else:
        return None
    return cur, rest


def file_module(modules, path):
    """The file module holding a (possibly inline) module path."""
    while path not in modules:
        path = path[:-1]
    return modules[path]


def target(modules, start, rest, seen=None):
    """The file module a path `start` + `rest` depends on."""
    seen = seen or set()
    cur = start
    rest = list(rest)
    while rest and cur + (rest[0],) in modules:
        cur = cur + (rest[0],)
        rest.pop(0)
    fm = file_module(modules, cur)
    if not rest or rest[0] == "*" or rest[0] in fm.items:
        return fm
    name = rest[0]
    key = (fm.path, name)
    if key in seen:
        return fm
    seen.add(key)
    if name in fm.reexports:
        src = fm.reexports[name]
        r = resolve_start(modules, fm, 0, src)
        if r is not None:
            return target(modules, r[0], r[1] + rest[1:], seen)
    for g in fm.globs:
        r = resolve_start(modules, fm, 0, g)
        if r is None:
            continue
        t = target(modules, r[0], r[1][:-1], seen)
        if name in t.items or name in t.reexports:
            return target(modules, t.path, [name] + rest[1:], seen)
    return fm


def build_graph(src_dir):
    modules = load_tree(src_dir)
    for m in modules.values():
        for pos, segs, reexp in raw_paths(m):
            if reexp and segs:
                if segs[-1] == "*":
                    m.globs.append(segs)
                else:
                    m.reexports[segs[-1]] = segs
    edges = {}  # (from file, to file) -> [line numbers]
    for m in modules.values():
        for pos, segs, _ in raw_paths(m):
            r = resolve_start(modules, m, pos, segs)
            if r is None:
                continue
            t = target(modules, r[0], r[1])
            if t.file != m.file:
                edges.setdefault((m.file, t.file), []).append(line_of(m.code, pos))
    return modules, edges


def sccs(nodes, adj):
    """Tarjan's strongly connected components."""
    index, low, on, stack, out = {}, {}, set(), [], []
    counter = [0]

    def strong(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in adj.get(v, ()):
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            out.append(comp)

    sys.setrecursionlimit(10000)
    for v in sorted(nodes):
        if v not in index:
            strong(v)
    return out


def shortest_cycle(comp, adj):
    """A shortest circle through the component's first file (breadth-first search)."""
    comp = set(comp)
    start = min(comp)
    prev, frontier = {start: None}, [start]
    while frontier:
        nxt = []
        for v in frontier:
            for w in sorted(adj.get(v, ())):
                if w not in comp:
                    continue
                if w == start:
                    path = [v]
                    while prev[path[-1]] is not None:
                        path.append(prev[path[-1]])
                    return list(reversed(path)) + [start]
                if w not in prev:
                    prev[w] = v
                    nxt.append(w)
        frontier = nxt
    return [start]


def check(src_dir, show_edges=False):
    modules, edges = build_graph(src_dir)
    rel = lambda f: os.path.relpath(f, src_dir)
    adj = {}
    for a, b in edges:
        adj.setdefault(a, set()).add(b)
    files = {m.file for m in modules.values()}
    comps = [c for c in sccs(files, adj) if len(c) > 1]
    print(f"{src_dir}: {len(files)} files, {len(edges)} file-level dependencies, "
          f"{len(comps)} import circle{'s' if len(comps) != 1 else ''}")
    if show_edges:
        for (a, b), lines in sorted(edges.items()):
            print(f"  {rel(a)} -> {rel(b)} (line {', '.join(map(str, lines[:3]))})")
    for c in comps:
        cyc = shortest_cycle(c, adj)
        print(f"  circle of {len(c)} files: {', '.join(sorted(rel(f) for f in c))}")
        for a, b in zip(cyc, cyc[1:]):
            lines = edges[(a, b)]
            print(f"    {rel(a)}:{lines[0]} -> {rel(b)}")
    return len(comps)


def main(argv):
    args = [a for a in argv if not a.startswith("--")]
    if not args or any(a not in ("--edges",) for a in argv if a.startswith("--")):
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    bad = 0
    for d in args:
        if not os.path.isdir(d):
            print(f"{d}: not a folder", file=sys.stderr)
            return 2
        bad += check(d, "--edges" in argv)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
