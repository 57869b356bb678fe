#!/usr/bin/env python3
"""Checks that the library's modules import one way (no cycles).

Reads every `.rs` file of crates/septa/src (test modules after `#[cfg(test)]`
excluded), finds the `crate::...` and `super::...` paths it names, and builds
a graph between *units*: a top-level module (`complex`, `grid`, `scene`, ...),
except that `network` counts per sub-folder (`network::block`,
`network::topology`, `network::sparse`, `network::stream`, and the files of
`network/` itself) and `io` per file (its readers sit below the scene, its
writers above everything they write). Fails, naming the cycle, if two units
import each other directly or through others, or if network's folders
import against their order block < topology < sparse < stream.

    python3 scripts/check_layers.py          # prints the unit graph, exit 1 on a cycle
"""
import os
import re
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "crates", "septa", "src")
NETWORK_ORDER = ["network::block", "network::topology", "network::sparse", "network::stream"]
# Sub-folders and files of network/ (items of network/mod.rs belong to `network`).
NETWORK_FILES = ["block", "topology", "sparse", "stream", "dense", "field"]


def module_path(path):
    """`crates/septa/src/network/block/worker.rs` -> ['network', 'block', 'worker']."""
    rel = os.path.relpath(path, ROOT)[:-3].split(os.sep)
    if rel[-1] in ("mod", "lib"):
        rel = rel[:-1]
    return rel


def io_reexports():
    """Item -> file of io's flat re-exports (`pub use file::{a, b};` in io/mod.rs)."""
    text = open(os.path.join(ROOT, "io", "mod.rs"), encoding="utf-8").read()
    items = {}
    for m in re.finditer(r"pub use (\w+)::(\{[^}]*\}|\w+);", text):
        for item in re.findall(r"\w+", m.group(2)):
            items[item] = m.group(1)
    return items


IO_ITEMS = io_reexports()


def unit(parts):
    """The unit a module path belongs to."""
    if not parts:
        return None
    if parts[0] == "network" and len(parts) > 1 and parts[1] in NETWORK_FILES:
        return "network::" + parts[1]
    if parts[0] == "io" and len(parts) > 1:
        # A flat re-export (`crate::io::read_mesh`) counts as the file defining it.
        file = IO_ITEMS.get(parts[1], parts[1])
        if not file[:1].islower():
            return parts[0]
        # The triangle-mesh readers (one per format, sharing `IndexedMesh`) are one unit.
        return "io::mesh" if file.startswith("mesh_") else "io::" + file
    return parts[0]


def resolve(mod, path):
    """Resolves `super::a::b` / `crate::a::b` named in module `mod`."""
    segs = path.split("::")
    if segs[0] == "crate":
        return segs[1:]
    if segs[0] in ("super", "self"):
        base = list(mod)
        while segs and segs[0] in ("super", "self"):
            if segs[0] == "super":
                base = base[:-1]
            segs = segs[1:]
        return base + segs
    return None


def main():
    edges = {}
    for dirpath, _, files in os.walk(ROOT):
        for f in files:
            if not f.endswith(".rs"):
                continue
            path = os.path.join(dirpath, f)
            mod = module_path(path)
            if f not in ("mod.rs", "lib.rs"):
                pass
            text = open(path, encoding="utf-8").read().split("#[cfg(test)]")[0]
            # Strip comments (doc links name other modules without importing them).
            text = "\n".join(line.split("//")[0] for line in text.splitlines())
            src = unit(mod)
            for m in re.finditer(r"\b((?:crate|super|self)(?:::[A-Za-z_][A-Za-z0-9_]*)+)", text):
                target = resolve(mod if f not in ("mod.rs", "lib.rs") else mod + ["_"], m.group(1))
                if not target:
                    continue
                dst = unit(target)
                if dst and src and dst != src:
                    edges.setdefault(src, set()).add(dst)
    # Tarjan's strongly connected components.
    index, low, stack, on, sccs = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges.get(v, ()):
            if w not in index:
                visit(w)
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
            sccs.append(comp)

    nodes = set(edges) | {w for ws in edges.values() for w in ws}
    sys.setrecursionlimit(10000)
    for v in sorted(nodes):
        if v not in index:
            visit(v)
    bad = [sorted(c) for c in sccs if len(c) > 1]
    for v in sorted(edges):
        print(f"{v} -> {', '.join(sorted(edges[v]))}")
    ok = True
    for c in bad:
        print(f"CYCLE: {' <-> '.join(c)}")
        ok = False
    for i, a in enumerate(NETWORK_ORDER):
        for b in NETWORK_ORDER[:i]:
            if a in edges.get(b, ()):
                print(f"ORDER: {b} imports {a} (network folders import down: {' < '.join(NETWORK_ORDER)})")
                ok = False
    print("layers: ok" if ok else "layers: FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
