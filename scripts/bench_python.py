#!/usr/bin/env python3
"""Python overhead: septa.arrangement on a 64^3 grid with 8 spheres versus
`septa ia --no-output --json` on the same job, measured in the same run
(median of N runs each; wall time of the process for the command line,
wall time of the call for Python; sampling excluded on both sides where the
command line reports it).

    .venv/bin/python scripts/bench_python.py [--resolution 64] [--runs 5] [--threads 1]
"""
import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import septa
from septa import shapes

ROOT = Path(__file__).resolve().parents[1]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--resolution", type=int, default=64)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--threads", type=int, default=1)
    a = ap.parse_args()
    rng = np.random.default_rng(1)
    spec = [{"type": "sphere", "center": (0.25 + 0.5 * rng.random(3)).tolist(), "radius": float(0.15 + 0.1 * rng.random())} for _ in range(8)]
    tmp = Path(tempfile.mkdtemp())
    (tmp / "f.json").write_text(json.dumps(spec))
    exe = ROOT / "target" / "release" / "septa"
    cmd = [str(exe), "ia", str(tmp / "f.json"), "--grid", str(a.resolution), "--bounds", "0", "0", "0", "1", "1", "1",
           "--threads", str(a.threads), "--no-output", "--json", "-o", str(tmp / "o")]
    g = septa.grid.box(a.resolution)
    vals = shapes.sample([shapes.sphere(s["center"], s["radius"]) for s in spec], g)
    cli_network, py_wall, cli_summary = [], [], None
    for _ in range(a.runs):
        out = json.loads(subprocess.run(cmd, capture_output=True, text=True, check=True).stdout)
        sec = out["seconds"]
        # The network stages alone (the command line also reads/samples and writes).
        cli_network.append(sum(v for k, v in sec.items() if k not in ("total", "read", "write", "sample", "input")))
        cli_summary = out
        t = time.perf_counter()
        net = septa.arrangement(g, vals, threads=a.threads)
        py_wall.append(time.perf_counter() - t)
    c, p = statistics.median(cli_network), statistics.median(py_wall)
    same = all(net.summary()[k] == cli_summary[k] for k in ("vertices", "faces", "patches", "chains", "cells"))
    print(f"grid {a.resolution}^3, 8 spheres, threads {a.threads}, median of {a.runs}")
    print(f"command line network stages: {c:.3f} s   (stages: {sorted(cli_summary['seconds'])})")
    print(f"python septa.arrangement:    {p:.3f} s   (call wall time incl. numpy conversion)")
    print(f"ratio python / command line: {p / c:.3f}   same counts: {same}")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
