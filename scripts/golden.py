#!/usr/bin/env python3
"""Golden hashes of septa's outputs across the library's paths: a restructuring
(files moved, nothing meant to change) must leave every written file
byte-identical. Runs each case with `SEPTA`, hashes every file it writes
(JSON files, and .npz arrays by name, without their timings and machine
facts: keys naming seconds, times, threads, memory or `exact_fallbacks`) and prints them, or compares them
with an earlier run.

    python3 scripts/golden.py SEPTA DATA > before.json          # hashes of one build
    python3 scripts/golden.py SEPTA DATA --compare before.json  # exit 1 on any difference

DATA is the shared data folder (isn/*.npz, meshes/, topocut/*.plane).
Cases: IA and MI on the reference's sphere sets (dense, sparse, streamed),
a degenerate one (shifted spheres), built-in regions scenes, a label volume,
and cuts (TopoCut plane sets). scripts/cut_golden.py covers all 57 cuts.
"""
import hashlib
import json
import os
import re
import subprocess
import sys
import tempfile

VOLATILE = re.compile(r"second|time|_ms$|elapsed|thread|memory|peak|rss|exact_fallbacks|^version$")


def clean(x):
    if isinstance(x, dict):
        return {k: clean(v) for k, v in x.items() if not VOLATILE.search(k)}
    if isinstance(x, list):
        return [clean(v) for v in x]
    return x


def npz_bytes(path):
    """An .npz's arrays by name (the zip's entry dates vary run to run); a
    JSON text array is cleaned like a JSON file."""
    import numpy as np
    out = b""
    with np.load(path, allow_pickle=False) as z:
        for k in sorted(z.files):
            if VOLATILE.search(k):
                continue
            a = z[k]
            if a.dtype.kind == "U" and a.ndim == 0:
                try:
                    a = np.array(json.dumps(clean(json.loads(str(a))), sort_keys=True))
                except ValueError:
                    pass
            out += k.encode() + str(a.dtype).encode() + str(a.shape).encode() + a.tobytes()
    return out


def cases(data):
    isn = os.path.join(data, "isn")
    c = {}
    for name in ("ia4_R20", "ia18_R20", "nested8_R20", "shifted4_ia_eps1e-7_R20_s0"):
        npz = os.path.join(isn, name + ".npz")
        c[f"ia.{name}"] = ["ia", npz, "--format", "all"]
    for name in ("mi4_R20", "mi18_R20", "shifted4_mi_eps1e-7_R2_s0"):
        c[f"mi.{name}"] = ["mi", os.path.join(isn, name + ".npz"), "--format", "all"]
    spheres = json.dumps([
        {"type": "sphere", "center": [0.1 * i - 0.2, 0.05 * i, -0.1 * i], "radius": 0.3 + 0.05 * i} for i in range(5)
    ])
    c["ia.spec.sparse"] = ["ia", "@spheres", "--grid", "24", "--format", "all"]
    c["ia.spec.dense"] = ["ia", "@spheres", "--grid", "24", "--dense", "--format", "all"]
    c["ia.spec.stream"] = ["ia", "@spheres", "--grid", "24", "--stream", "@out/stream.ply", "--block", "8"]
    c["mi.spec.sparse"] = ["mi", "@spheres", "--grid", "24", "--format", "all"]
    c["mi.spec.stream"] = ["mi", "@spheres", "--grid", "24", "--stream", "@out/stream.ply", "--block", "8"]
    for scene in ("cad-part", "saucer-square", "sphere-with-hole"):
        c[f"regions.{scene}"] = ["regions", f"builtin:{scene}"]
    c["labels.blobs"] = ["labels", "@labels"]
    for mesh, s in (("cube", "A10"), ("bunny", "R20"), ("plate_genus9", "A10")):
        c[f"cut.{mesh}.{s}"] = ["cut", os.path.join(data, "meshes", mesh + ".obj"), "--planes",
                                os.path.join(data, "topocut", f"{mesh}.{s}.plane"), "--threads", "1"]
    return c, spheres


def run_case(septa, args, spheres, tmp):
    out = os.path.join(tmp, "out")
    os.makedirs(out)
    spec = os.path.join(tmp, "spheres.json")
    open(spec, "w").write(spheres)
    labels = os.path.join(tmp, "labels.npy")
    if "@labels" in args:
        import numpy as np
        g = np.indices((20, 20, 20)).astype(float)
        v = np.zeros((20, 20, 20), np.int64)
        v[((g - 7) ** 2).sum(0) < 30] = 1
        v[((g - 12) ** 2).sum(0) < 20] = 2
        v[(g[0] > 14)] = 3
        np.save(labels, v)
    args = [a.replace("@spheres", spec).replace("@labels", labels).replace("@out", out) for a in args]
    if args[0] != "cut" or "-o" not in args:
        args = args + ["-o", out]
    r = subprocess.run([septa] + args + ["-q"], capture_output=True, text=True)
    h = {"exit": r.returncode}
    for dirpath, _, files in os.walk(out):
        for f in sorted(files):
            p = os.path.join(dirpath, f)
            rel = os.path.relpath(p, out)
            if f in ("manifest.json", ".septa.lock"):
                continue
            data = open(p, "rb").read()
            if f.endswith(".json"):
                try:
                    data = json.dumps(clean(json.loads(data)), sort_keys=True).encode()
                except ValueError:
                    pass
            if f.endswith(".npz"):
                data = npz_bytes(p)
            h[rel] = hashlib.md5(data).hexdigest()
    return h


def main():
    a = sys.argv[1:]
    if len(a) < 2:
        print(__doc__)
        return 2
    septa, data = os.path.abspath(a[0]), a[1]
    compare = a[a.index("--compare") + 1] if "--compare" in a else None
    cs, spheres = cases(data)
    result = {}
    for name, args in cs.items():
        with tempfile.TemporaryDirectory() as tmp:
            result[name] = run_case(septa, args, spheres, tmp)
        print(name, file=sys.stderr, end=" ", flush=True)
    print(file=sys.stderr)
    if compare is None:
        print(json.dumps(result, indent=1, sort_keys=True))
        return 0
    before = json.load(open(compare))
    bad = [k for k in sorted(set(before) | set(result)) if before.get(k) != result.get(k)]
    for k in bad:
        print(f"DIFFERENT: {k}: {before.get(k)} != {result.get(k)}")
    files = sum(len(v) - 1 for v in result.values())
    print(f"golden: {len(result) - len(bad)}/{len(result)} cases identical ({files} files)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
