#!/usr/bin/env python3
"""tests/layers.py: the include graph against the layer rule (`make layers`; every build runs it).

The rule (README, "The map"): src/LAYER/*.c with its headers in include/LAYER/; a file
includes its own layer and the layers below it, never above, never a sibling:

    main.c -> {cmd, viewer, bench} -> cli -> term -> render -> scene -> base

and term reaches render only through the framebuffer's header (fb.h). The Makefile gives
each layer only the include paths the rule allows; this script checks the same rule from
the sources (so a header included through another path is caught too), and that no two
modules include each other round a circle (a module is X.c with its X.h).

    tests/layers.py            check; print the counts; exit 1 on any violation or circle
    tests/layers.py --report   also print files per layer and lines per file
Ends with a line "N passed, N failed" (two checks: the rule, the circles)."""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ORDER = ["base", "scene", "render", "term", "cli"]  # bottom to top; the three tops below
TOPS = ["cmd", "viewer", "bench"]
# term may include these render headers only
TERM_RENDER_OK = {"fb.h"}


def below(layer):
    """the layers a file of `layer` may include (its own too)"""
    if layer == "main":
        return set(ORDER + TOPS)
    if layer in TOPS:
        return set(ORDER) | {layer}
    return set(ORDER[: ORDER.index(layer) + 1])


def files():
    out = []
    for top in ("src", "include"):
        for d, _, names in os.walk(os.path.join(ROOT, top)):
            for n in sorted(names):
                if n.endswith((".c", ".h")):
                    out.append(os.path.join(d, n))
    return sorted(out)


def layer_of(path):
    rel = os.path.relpath(path, ROOT).split(os.sep)
    if rel == ["src", "main.c"]:
        return "main"
    return rel[1] if len(rel) >= 3 else None


def main():
    report = "--report" in sys.argv
    paths = files()
    header_at = {}  # header name -> its layer
    problems = []
    for p in paths:
        lay = layer_of(p)
        if lay is None:
            problems.append(f"{os.path.relpath(p, ROOT)}: not in a layer folder")
            continue
        if p.endswith(".h"):
            n = os.path.basename(p)
            if n in header_at:
                problems.append(f"two headers named {n} ({header_at[n]}, {lay})")
            header_at[n] = lay
    inc_re = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
    edges = {}  # module -> set of modules
    n_includes = 0
    for p in paths:
        lay = layer_of(p)
        mod = os.path.splitext(os.path.basename(p))[0]
        text = open(p, encoding="utf-8", errors="replace").read()
        for inc in inc_re.findall(text):
            n_includes += 1
            name = os.path.basename(inc)
            to = header_at.get(name)
            if to is None:
                problems.append(f"{os.path.relpath(p, ROOT)}: includes {inc}, which is no header of ours")
                continue
            if to not in below(lay):
                problems.append(f"{os.path.relpath(p, ROOT)} ({lay}) includes {name} ({to}): against the rule")
            elif lay == "term" and to == "render" and name not in TERM_RENDER_OK:
                problems.append(f"{os.path.relpath(p, ROOT)} (term) includes {name} (render): term reaches render only through fb.h")
            tmod = os.path.splitext(name)[0]
            if tmod != mod:
                edges.setdefault(mod, set()).add(tmod)
    # circles: strongly connected components of more than one module (Tarjan)
    index, low, on, stack, comps, counter = {}, {}, set(), [], [], [0]

    def strong(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges.get(v, ()):
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
            if len(comp) > 1:
                comps.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in sorted(set(edges) | {w for s in edges.values() for w in s}):
        if v not in index:
            strong(v)
    for p in problems:
        print("layers: " + p)
    for c in comps:
        print("layers: circle: " + " <-> ".join(c))
    per = {}
    for p in paths:
        per.setdefault(layer_of(p), []).append(p)
    print(f"layers: {len(paths)} files, {n_includes} includes of our headers, "
          f"{len(problems)} against the rule, {len(comps)} circles")
    if report:
        for lay in ["main"] + ORDER + TOPS:
            fs = per.get(lay, [])
            nc = sum(1 for f in fs if f.endswith(".c"))
            nh = len(fs) - nc
            lines = [sum(1 for _ in open(f, encoding="utf-8", errors="replace")) for f in fs]
            if lines:
                print(f"  {lay:7} {nc:3} .c {nh:3} .h  {sum(lines):6} lines, "
                      f"largest {max(lines)} ({os.path.basename(fs[lines.index(max(lines))])})")
    failed = (len(problems) > 0) + (len(comps) > 0)
    print(f"{2 - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
