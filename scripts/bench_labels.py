"""Label volumes: `septa.label_surfaces` against VTK's SurfaceNets3D
(`pyvista.ImageData.contour_labels`), both in this one Python process
(docs/performance.md, "Label volumes").

    python scripts/bench_labels.py [--sizes 128,256] [--rounds 3] [--volumes blobs,ball]

Needs numpy, pyvista (VTK >= 9.3) and septa in the running Python. For each
volume and size, alternates `--rounds` times the two calls on the same
array, in two settings:

- `plain`: no smoothing on either side: `label_surfaces(v)` and
  `contour_labels(boundary_style="all", smoothing=False)` (every pair of
  labels gets its boundary, as Septa's surfaces do);
- `plain-nc`: the same with Septa's exact check of the written doubles
  off (`certify=False`), which SurfaceNets3D has no counterpart of;
- `smoothed`: both smoothing as each offers it: `label_surfaces(v,
  sigma=1)` (Gaussian pre-smoothing of each label's indicator, the surfaces
  then exact) and `contour_labels(boundary_style="all")` (VTK's default
  constrained smoothing of the dual mesh, 16 iterations).

Volumes with several labels meeting: `blobs` (4 overlapping balls,
`make_label_blobs.py`) and `ball` (12 labels partitioning a ball: the
Voronoi cells of 12 fixed seeds, so labels meet along curves and at
corners). SurfaceNets3D's count is of its cells: quads without smoothing,
triangles with it. Timed as CPU seconds of this process (`time.process_time()`:
every thread, both libraries) and wall seconds; medians. The load average
before and after each row is printed: a shared machine inflates wall time,
the CPU ratio is the steadier figure. Nothing here is asserted.
"""
import os
import statistics
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_label_blobs import blobs  # noqa: E402


def arg(name, default):
    a = sys.argv
    return a[a.index(name) + 1] if name in a else default


def ball(n):
    """12 labels partitioning a ball of radius 0.45 n (Voronoi cells of
    fixed seeds), 0 outside."""
    rng = np.random.default_rng(12)
    seeds = rng.uniform(0.25, 0.75, size=(12, 3))
    x = (np.arange(n) + 0.5) / n
    X, Y, Z = np.meshgrid(x, x, x, indexing="ij")
    best = np.full((n, n, n), np.inf)
    lab = np.zeros((n, n, n), dtype=np.int32)
    for i, s in enumerate(seeds):
        d = (X - s[0]) ** 2 + (Y - s[1]) ** 2 + (Z - s[2]) ** 2
        closer = d < best
        best[closer] = d[closer]
        lab[closer] = i + 1
    lab[(X - 0.5) ** 2 + (Y - 0.5) ** 2 + (Z - 0.5) ** 2 > 0.45**2] = 0
    return lab


def timed(f):
    w, c = time.perf_counter(), time.process_time()
    out = f()
    return time.perf_counter() - w, time.process_time() - c, out


def surface_nets(labels, smoothing):
    import pyvista as pv

    img = pv.ImageData(dimensions=labels.shape)
    img.point_data["labels"] = labels.ravel(order="F")
    return timed(lambda: img.contour_labels(boundary_style="all", smoothing=smoothing).n_cells)


def septa_labels(labels, sigma, certify):
    import septa

    return timed(lambda: len(septa.label_surfaces(labels, sigma=sigma, certify=certify).triangles))


def main():
    sizes = [int(s) for s in arg("--sizes", "128,256").split(",")]
    rounds = int(arg("--rounds", "3"))
    volumes = arg("--volumes", "blobs,ball").split(",")
    print(f"{'volume':>7} {'size':>5} {'setting':>8} {'SN cpu':>7} {'septa cpu':>9} {'cpu x':>6} "
          f"{'SN wall':>8} {'septa wall':>10} {'wall x':>7}  septa / SN triangles  load before -> after")
    for kind in volumes:
        for n in sizes:
            labels = (blobs(n) if kind == "blobs" else ball(n)).astype(np.int32)
            for setting, smooth, sigma, certify in (("plain", False, 0.0, True), ("plain-nc", False, 0.0, False),
                                                    ("smoothed", True, 1.0, True)):
                load0 = os.getloadavg()[0]
                sn_w, sn_c, se_w, se_c = [], [], [], []
                for _ in range(rounds):
                    w, c, tris = surface_nets(labels, smooth)
                    sn_w.append(w)
                    sn_c.append(c)
                    w, c, ours = septa_labels(labels, sigma, certify)
                    se_w.append(w)
                    se_c.append(c)
                m = [statistics.median(x) for x in (sn_c, se_c, sn_w, se_w)]
                print(f"{kind:>7} {n:>5} {setting:>8} {m[0]:7.3f} {m[1]:9.3f} {m[1] / m[0]:6.2f} {m[2]:8.3f} "
                      f"{m[3]:10.3f} {m[3] / m[2]:7.2f}  {ours} / {tris}  {load0:.2f} -> {os.getloadavg()[0]:.2f}",
                      flush=True)


if __name__ == "__main__":
    main()
