"""Label volumes: `septa labels` against VTK's SurfaceNets3D measured in the
same run (docs/performance.md, "Label volumes").

    python scripts/bench_labels.py SEPTA [--sizes 128,256] [--rounds 3] [--threads 1]

Needs numpy and pyvista (with VTK >= 9.3) in the running Python. For each
size it writes the blob volume of `make_label_blobs.py` to a temporary
folder, then alternates, `--rounds` times: VTK's
`pyvista.ImageData.contour_labels()` (in this process) and the whole
`septa labels VOLUME --format ply` process (reading the .npy, computing, and
writing network.ply). Both are timed in wall seconds and CPU seconds (user +
system: `time.process_time()` for VTK, the children's rusage for Septa); a
shared machine's load inflates wall time, so the CPU ratio is the steadier
figure. Prints the medians and the ratios Septa / SurfaceNets.
"""
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_label_blobs import blobs  # noqa: E402


def arg(name, default):
    a = sys.argv
    return a[a.index(name) + 1] if name in a else default


def surface_nets(labels):
    import pyvista as pv

    img = pv.ImageData(dimensions=labels.shape)
    img.point_data["labels"] = labels.ravel(order="F")
    w, c = time.perf_counter(), time.process_time()
    mesh = img.contour_labels()
    return time.perf_counter() - w, time.process_time() - c, mesh.n_cells


def septa(exe, path, out, threads):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    w = time.perf_counter()
    r = subprocess.run([exe, "labels", path, "-o", out, "--format", "ply", "--threads", threads, "--json"],
                       capture_output=True, text=True)
    wall = time.perf_counter() - w
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if r.returncode != 0:
        sys.exit(f"septa failed: {r.stderr.strip()[-400:]}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, json.loads(r.stdout.strip().splitlines()[-1])


def main():
    if len(sys.argv) < 2 or sys.argv[1].startswith("--"):
        sys.exit(__doc__)
    exe = sys.argv[1]
    sizes = [int(s) for s in arg("--sizes", "128,256").split(",")]
    rounds = int(arg("--rounds", "3"))
    threads = arg("--threads", "1")
    print(f"{'size':>5} {'SN wall':>8} {'SN cpu':>7} {'septa wall':>10} {'septa cpu':>9} "
          f"{'wall x':>7} {'cpu x':>6}  septa polygons / SN triangles")
    with tempfile.TemporaryDirectory() as d:
        for n in sizes:
            labels = blobs(n)
            path = os.path.join(d, f"blobs{n}.npy")
            np.save(path, labels)
            sn_w, sn_c, se_w, se_c = [], [], [], []
            for _ in range(rounds):
                w, c, tris = surface_nets(labels)
                sn_w.append(w)
                sn_c.append(c)
                w, c, summary = septa(exe, path, os.path.join(d, "out"), threads)
                se_w.append(w)
                se_c.append(c)
            m = [statistics.median(x) for x in (sn_w, sn_c, se_w, se_c)]
            print(f"{n:>5} {m[0]:8.3f} {m[1]:7.3f} {m[2]:10.3f} {m[3]:9.3f} {m[2] / m[0]:7.2f} {m[3] / m[1]:6.2f}"
                  f"  {summary['faces']} / {tris}")


if __name__ == "__main__":
    main()
