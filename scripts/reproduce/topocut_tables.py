#!/usr/bin/env python3
"""TopoCut (Fang et al. 2022), Tables 3 and 4, on the meshes and plane sets of a data folder:
Table 3's average smallest cell volume per cut type beside Septa's (`septa cut`, cut.json's
min_cell_volume, each mesh scaled as the paper's dataset is: to the unit box, so volumes scale by
the cube of the bounding box's largest side), and Table 4's per-model counts (cut-vertices, -edges,
-faces, cells, seconds) beside Septa's for the models both have.

    python3 scripts/reproduce/topocut_tables.py SEPTA DATA [--sets A10,R20] [--meshes bunny,cube]

DATA holds meshes/*.obj and topocut/MESH.SET.plane (the project's shared data folder). The
paper's Table 4 cuts with its own 15 and 10 random planes, which it does not publish: the counts
differ with the planes; the columns show the same statistics on this folder's planes.
"""
import argparse
import glob
import json
import os
import subprocess
import tempfile

from common import septa_path, table

# Table 3: cut type -> (average min volume, average max volume) over the paper's dataset.
PAPER3 = {"A5": (3.9e-4, 4.6e-2), "A10": (1.3e-5, 6.7e-3), "A20": (8.5e-7, 9.8e-4), "A50": (2.6e-8, 1.2e-4),
          "R10": (3.9e-5, 0.19), "R20": (2.3e-6, 0.10), "R30": (1.8e-7, 0.065), "R100": (8.7e-9, 0.013)}
# Table 4 rows for models in the shared data (its armadillo: 21k vertices, 43k triangles): model -> 15 planes (V, E, F, C, s), 10 planes (V, E, F, C, s).
PAPER4 = {"armadillo43k": ((26094, 73565, 47648, 60, 0.531), (25616, 72602, 47142, 41, 0.438))}


def bbox_side(obj):
    lo, hi = [float("inf")] * 3, [float("-inf")] * 3
    for line in open(obj):
        if line.startswith("v "):
            p = [float(x) for x in line.split()[1:4]]
            lo = [min(a, b) for a, b in zip(lo, p)]
            hi = [max(a, b) for a, b in zip(hi, p)]
    return max(h - l for h, l in zip(hi, lo))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("septa")
    ap.add_argument("data")
    ap.add_argument("--sets", default="")
    ap.add_argument("--meshes", default="")
    a = ap.parse_args()
    septa = septa_path(a.septa)
    planes = sorted(glob.glob(os.path.join(a.data, "topocut", "*.plane")))
    if not planes:
        raise SystemExit(f"no plane files in {os.path.join(a.data, 'topocut')}")
    sets = set(a.sets.split(",")) - {""}
    meshes = set(a.meshes.split(",")) - {""}
    by_set, rows4, failed = {}, [], 0
    for p in planes:
        mesh, s = os.path.basename(p)[: -len(".plane")].rsplit(".", 1)
        if (sets and s not in sets) or (meshes and mesh not in meshes):
            continue
        obj = os.path.join(a.data, "meshes", mesh + ".obj")
        with tempfile.TemporaryDirectory() as tmp:
            r = subprocess.run([septa, "cut", obj, "--planes", p, "-o", tmp + "/o", "--threads", "1", "-q",
                                "--no-mesh-output"], capture_output=True, text=True)
            if r.returncode != 0:
                print(f"{mesh} {s}: septa cut failed: {r.stderr.strip()}")
                failed += 1
                continue
            j = json.load(open(tmp + "/o/cut.json"))
        side = bbox_side(obj)
        by_set.setdefault(s, []).append(j["min_cell_volume"] / side ** 3)
        secs = j.get("seconds", {})
        total = secs.get("total") if isinstance(secs, dict) else secs
        row = [mesh, s, j["planes"], j["cut_vertices"], j["cut_edges"], j["cut_faces"], j["cut_cells"],
               f"{total:.3f}" if isinstance(total, float) else "-"]
        if mesh in PAPER4:
            a15, a10 = PAPER4[mesh]
            row += [f"15 planes: {a15}; 10 planes: {a10}"]
        else:
            row += ["-"]
        rows4.append(row)
    rows3 = [[s, f"{PAPER3[s][0]:.1e}" if s in PAPER3 else "-", f"{sum(v) / len(v):.1e}", len(v)]
             for s, v in sorted(by_set.items())]
    table("TopoCut Table 3: average smallest cell volume (mesh scaled to a unit bounding box)",
          ["cut type", "paper (its ~10K-mesh dataset)", "Septa (this folder)", "meshes"], rows3)
    table("TopoCut Table 4: statistics per model (paper: its own random planes; Septa: this folder's)",
          ["model", "set", "planes", "cut-vertices", "cut-edges", "cut-faces", "cells", "Septa s",
           "paper (V, E, F, C, s)"], rows4)
    return 1 if failed else 0


if __name__ == "__main__":
    raise SystemExit(main())
