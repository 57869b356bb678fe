#!/usr/bin/env python3
"""Writes a small, hand-derived surface network in the job output format.

Until the grid pipeline writes real outputs, the viewer, `septa view` and the
Python loaders are tested on this fixture: the implicit arrangement (IA) of the
two planes f0 = x - 1/2 and f1 = y - 1/2 in the unit box. Its topology is known
by hand: 4 patches (each plane is split in two by the other),
1 chain (the line x = y = 1/2), 2 corners (where the chain meets the box),
4 cells (the quadrants), each cell bounded by one shell of two half-patches.

Output contract (the network writer produces the same): ``network.json`` with
points, polygon faces (CCW seen from the positive side of their function),
face_patch, face_cells ([c_pos, c_neg]), patches ({label, faces}), chains,
corners, shells (half-patch ids 2p / 2p+1 = positive / negative side of p),
cells ({shells, label}), counts and seconds; and a binary ``network.ply`` with
a per-face ``patch`` property.

Standard library only, so it runs before any virtual environment exists.

    python3 scripts/make_fixture.py OUTDIR [--n 4]
"""
import argparse
import json
import os
import struct
import sys


def two_planes(n=4):
    """Returns the network dict of planes x=1/2 and y=1/2 in [0,1]^3, each
    patch split into n x n quads (n even so the chain lies on grid lines)."""
    if n < 2 or n % 2:
        raise ValueError("n must be an even number >= 2")
    points, index = [], {}

    def pid(x, y, z):
        # Exact key: coordinates are multiples of 1/n, keyed by integers.
        key = (round(x * n), round(y * n), round(z * n))
        if key not in index:
            index[key] = len(points)
            points.append([key[0] / n, key[1] / n, key[2] / n])
        return index[key]

    faces, face_patch, face_cells = [], [], []
    h = n // 2
    # Cells are the quadrants: id = 2*(x > 1/2) + (y > 1/2); sign vectors
    # [f0 > 0, f1 > 0] as labels (IA), patch labels [f, f], as the writer does.
    cell_of = lambda sx, sy: 2 * sx + sy  # noqa: E731
    # Patch 0: x = 1/2, y < 1/2; patch 1: x = 1/2, y > 1/2;
    # patch 2: y = 1/2, x < 1/2; patch 3: y = 1/2, x > 1/2.
    for p in range(4):
        for a in range(n):
            for b in range(h):
                side = p % 2  # 0: lower half of the other coordinate
                u0, u1 = (b + side * h), (b + side * h + 1)
                z0, z1 = a, a + 1
                if p < 2:
                    # Plane x = 1/2, normal +x. Polygon in (y, z) CCW seen
                    # from +x: (y, z) order (y0,z0) (y1,z0) (y1,z1) (y0,z1).
                    f = [pid(h / n, u / n, z / n) for u, z in ((u0, z0), (u1, z0), (u1, z1), (u0, z1))]
                    sy = side
                    c_pos, c_neg = cell_of(1, sy), cell_of(0, sy)
                else:
                    # Plane y = 1/2, normal +y. CCW seen from +y in (z, x).
                    f = [pid(u / n, h / n, z / n) for u, z in ((u0, z0), (u0, z1), (u1, z1), (u1, z0))]
                    sx = side
                    c_pos, c_neg = cell_of(sx, 1), cell_of(sx, 0)
                faces.append(f)
                face_patch.append(p)
                face_cells.append([c_pos, c_neg])
    patches = [{"label": [p // 2, p // 2], "faces": face_patch.count(p)} for p in range(4)]
    chain = [pid(h / n, h / n, k / n) for k in range(n + 1)]
    corners = [chain[0], chain[-1]]
    # Shell of each cell: the half-patches facing it. Cell (sx, sy) sees
    # patch (0 + sy) from side sx (positive side if sx = 1) and patch
    # (2 + sx) from side sy.
    shells, cells = [], []
    for sx in (0, 1):
        for sy in (0, 1):
            hp_a = 2 * (0 + sy) + (0 if sx else 1)
            hp_b = 2 * (2 + sx) + (0 if sy else 1)
            shells.append(sorted([hp_a, hp_b]))
            cells.append({"shells": [len(shells) - 1], "label": [bool(sx), bool(sy)]})
    edges = set()
    for f in faces:
        for i in range(len(f)):
            a, b = f[i], f[(i + 1) % len(f)]
            edges.add((min(a, b), max(a, b)))
    counts = {
        "vertices": len(points),
        "faces": len(faces),
        "edges": len(edges),
        "patches": len(patches),
        "chains": 1,
        "corners": len(corners),
        "shells": len(shells),
        "cells": len(cells),
        "components": 1,
    }
    return {
        "mode": "ia",
        "points": points,
        "faces": faces,
        "face_patch": face_patch,
        "face_cells": face_cells,
        "patches": patches,
        "chains": [chain],
        "corners": corners,
        "shells": shells,
        "cells": cells,
        "counts": counts,
        "seconds": {"total": 0.0},
    }


def write_ply(path, net):
    """Binary little-endian PLY in Septa's layout: each polygon as a fan of
    triangles with its polygon id, patch, label pair and cell pair (the
    names of crates/septa/src/io/writers/result_mesh.rs, written independently)."""
    pts, faces = net["points"], net["faces"]
    ntri = sum(len(f) - 2 for f in faces)
    header = (
        "ply\nformat binary_little_endian 1.0\ncomment septa surface network, polygons as triangle fans\n"
        f"element vertex {len(pts)}\nproperty double x\nproperty double y\nproperty double z\n"
        f"element face {ntri}\nproperty list uchar int vertex_indices\nproperty int face\nproperty int patch\n"
        "property int labels_0\nproperty int labels_1\nproperty int cells_0\nproperty int cells_1\nend_header\n"
    )
    out = bytearray(header.encode("ascii"))
    for p in pts:
        out += struct.pack("<3d", *p)
    labels = net.get("face_label", [[-1, -1]] * len(faces))
    cells = net.get("face_cells", [[-1, -1]] * len(faces))
    for i, (f, patch, label, cell) in enumerate(zip(faces, net["face_patch"], labels, cells)):
        for j in range(1, len(f) - 1):
            out += struct.pack("<B3i", 3, f[0], f[j], f[j + 1])
            out += struct.pack("<6i", i, patch, label[0], label[1], cell[0], cell[1])
    atomic_write(path, bytes(out))


def atomic_write(path, data):
    """Temporary file in the same folder, then rename: never half-written."""
    tmp = path + ".tmp"
    with open(tmp, "wb") as fh:
        fh.write(data)
    os.replace(tmp, path)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("outdir")
    ap.add_argument("--n", type=int, default=4, help="quads per patch side (even)")
    args = ap.parse_args(argv)
    os.makedirs(args.outdir, exist_ok=True)
    net = two_planes(args.n)
    atomic_write(os.path.join(args.outdir, "network.json"), json.dumps(net, separators=(",", ":")).encode())
    write_ply(os.path.join(args.outdir, "network.ply"), net)
    print(f"wrote {args.outdir}/network.json and network.ply: {json.dumps(net['counts'])}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
