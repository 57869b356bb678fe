#!/usr/bin/env python3
"""Septa's cut against TopoCut and an older Septa build, side by side: each round runs
NEW, TopoCut and BASE (`-` for NEW again) on every (mesh, A10|R20) case, recording wall
(perf_counter) and CPU (user + sys of the child from `os.wait4`, microsecond resolution)
seconds, and prints medians and ratios. The command lines are those of
../shared/tools/sxs_cut.py; TopoCut is built outside the repository from its public sources
(docs/performance.md).

Both programs run on one thread: Septa with `--threads 1`, TopoCut with OMP_NUM_THREADS=1
(`--topocut-threads N` to change it). TopoCut parallelises parts of its run with OpenMP;
with two threads its waiting threads spin, so its CPU time then counts spinning (about a
fifth more on the small meshes) and a ratio of CPU times flatters Septa.

    python scripts/bench_cut.py NEW_SEPTA TOPOCUT_BINARY BASE_SEPTA|- ROUNDS [mesh,mesh,...]
        [--topocut-threads N]
"""
import os, statistics, subprocess, sys, tempfile, time

SHARED = os.environ.get("SEPTA_SHARED_DATA",
                        os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "data"))
MESHES = ["cube", "staircase", "knight", "plate_genus9", "bunny", "fertility", "rocker_arm",
          "bumpy_cube", "armadillo43k", "armadillo", "nefertiti"]


def timed(cmd, env=None):
    """Wall and CPU seconds (user + sys of the child alone) and the exit code."""
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
    _, status, ru = os.wait4(p.pid, 0)
    w = time.perf_counter() - t0
    p.returncode = os.waitstatus_to_exitcode(status)
    return w, ru.ru_utime + ru.ru_stime, p.returncode


args = [a for a in sys.argv[1:]]
topo_threads = "1"
if "--topocut-threads" in args:
    i = args.index("--topocut-threads")
    topo_threads = args[i + 1]
    del args[i:i + 2]
new, topo, base = args[0:3]
rounds = int(args[3])
meshes = args[4].split(",") if len(args) > 4 else MESHES
topo_env = dict(os.environ, OMP_NUM_THREADS=topo_threads)
print(f"TopoCut threads: {topo_threads}; Septa --threads 1")
print(f"{'case':20} {'topo wall':>9} {'topo cpu':>8} {'new wall':>8} {'new cpu':>7} {'base wall':>9} "
      f"{'base cpu':>8} {'x wall':>6} {'x cpu':>6} {'base x wall':>11} {'base x cpu':>10}", flush=True)
rw, rc, bw, bc = [], [], [], []
with tempfile.TemporaryDirectory() as d:
    for m in meshes:
        for s in ["A10", "R20"]:
            mesh = f"{SHARED}/meshes/{m}.obj"
            planes = f"{SHARED}/topocut/{m}.{s}.plane"
            res = {"n": [], "t": [], "b": []}
            for _ in range(rounds):
                for tag, cmd, env in [
                    ("n", [new, "cut", mesh, "--planes", planes, "-o", d + "/s", "--threads", "1", "--json"], None),
                    ("t", [topo, "cut", "-i", mesh, "-p", planes, "-o", d + "/t.vtk", "--is-triangulate", "0"], topo_env),
                    ("b", [new if base == "-" else base, "cut", mesh, "--planes", planes, "-o", d + "/b",
                           "--threads", "1", "--json"], None)]:
                    w, c, code = timed(cmd, env)
                    assert code == 0, (tag, m, s)
                    res[tag].append((w, c))
            med = {k: (statistics.median(w for w, _ in v), statistics.median(c for _, c in v)) for k, v in res.items()}
            xw, xc = med["t"][0] / med["n"][0], med["t"][1] / med["n"][1]
            yw, yc = med["t"][0] / med["b"][0], med["t"][1] / med["b"][1]
            rw.append(xw); rc.append(xc); bw.append(yw); bc.append(yc)
            print(f"{m + ' ' + s:20} {med['t'][0]:9.3f} {med['t'][1]:8.3f} {med['n'][0]:8.3f} {med['n'][1]:7.3f} "
                  f"{med['b'][0]:9.3f} {med['b'][1]:8.3f} {xw:6.2f} {xc:6.2f} {yw:11.2f} {yc:10.2f}", flush=True)
summary = lambda r: f"min x{min(r):.2f} median x{statistics.median(r):.2f}"
print(f"new: wall {summary(rw)}, cpu {summary(rc)}   base: wall {summary(bw)}, cpu {summary(bc)}")
