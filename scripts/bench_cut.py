#!/usr/bin/env python3
"""Septa's cut against TopoCut and an older Septa build, side by side: each round runs
NEW, TopoCut and BASE (`-` for NEW again) on every (mesh, A10|R20) case, recording wall
(perf_counter) and CPU (user+sys from /usr/bin/time) seconds, and prints medians and ratios.
The command lines are those of ../shared/tools/sxs_cut.py; TopoCut is built outside the
repository from its public sources (docs/performance.md).

    python scripts/bench_cut.py NEW_SEPTA TOPOCUT_BINARY BASE_SEPTA|- ROUNDS [mesh,mesh,...]
"""
import os, statistics, subprocess, sys, tempfile, time
SHARED = os.environ.get("SEPTA_SHARED_DATA",
                        os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "data"))
MESHES = ["cube", "staircase", "knight", "plate_genus9", "bunny", "fertility", "rocker_arm",
          "bumpy_cube", "armadillo43k", "armadillo", "nefertiti"]
def timed(cmd):
    t0 = time.perf_counter()
    r = subprocess.run(["/usr/bin/time", "-f", "%U %S %M"] + cmd, capture_output=True, text=True, timeout=900)
    w = time.perf_counter() - t0
    u, s, m = r.stderr.strip().splitlines()[-1].split()
    return w, float(u) + float(s), r.returncode
new, topo, base = sys.argv[1:4]
rounds = int(sys.argv[4]); meshes = sys.argv[5].split(",") if len(sys.argv) > 5 else MESHES
print(f"{'case':20} {'topo wall':>9} {'topo cpu':>8} {'new wall':>8} {'new cpu':>7} {'base wall':>9} {'base cpu':>8} {'x wall':>6} {'x cpu':>6} {'base x cpu':>10}", flush=True)
rw, rc, rb = [], [], []
with tempfile.TemporaryDirectory() as d:
    for m in meshes:
        for s in ["A10", "R20"]:
            mesh = f"{SHARED}/meshes/{m}.obj"; planes = f"{SHARED}/topocut/{m}.{s}.plane"
            res = {"n": [], "t": [], "b": []}
            for _ in range(rounds):
                for tag, cmd in [("n", [new, "cut", mesh, "--planes", planes, "-o", d + "/s", "--threads", "1", "--json"]),
                                 ("t", [topo, "cut", "-i", mesh, "-p", planes, "-o", d + "/t.vtk", "--is-triangulate", "0"]),
                                 ("b", [new if base == "-" else base, "cut", mesh, "--planes", planes, "-o", d + "/b", "--threads", "1", "--json"])]:
                    w, c, code = timed(cmd)
                    assert code == 0, (tag, m, s)
                    res[tag].append((w, c))
            med = {k: (statistics.median(w for w, _ in v), statistics.median(c for _, c in v)) for k, v in res.items()}
            xw = med["t"][0] / med["n"][0]; xc = med["t"][1] / max(med["n"][1], 0.005); xb = med["t"][1] / max(med["b"][1], 0.005)
            rw.append(xw); rc.append(xc); rb.append(xb)
            print(f"{m + ' ' + s:20} {med['t'][0]:9.3f} {med['t'][1]:8.2f} {med['n'][0]:8.3f} {med['n'][1]:7.2f} {med['b'][0]:9.3f} {med['b'][1]:8.2f} {xw:6.2f} {xc:6.2f} {xb:10.2f}", flush=True)
print(f"wall: min x{min(rw):.2f} median x{statistics.median(rw):.2f}   cpu: min x{min(rc):.2f} median x{statistics.median(rc):.2f}   base cpu: min x{min(rb):.2f} median x{statistics.median(rb):.2f}")
