#!/usr/bin/env python3
"""Golden hashes of `septa cut`'s outputs on the 57 TopoCut reference cases: a change meant only
for speed must leave every file byte-identical. For each (mesh, plane set) it runs
`SEPTA cut MESH --planes SET -o TMP --threads 1 [EXTRA...]` and hashes cells.vtu, cells.obj and
cut.json without its timings (`seconds`) and `exact_fallbacks` (a process-wide counter).

    python scripts/cut_golden.py SEPTA > before.json          # hashes of one build
    python scripts/cut_golden.py SEPTA --compare before.json  # exit 1 on any difference
    [--cases cube.A10,knight.R20] [--extra "--format all"]

The reference data (meshes and plane files) is read from ../shared/data next to the repository,
(searched up to two levels higher for a worktree), or from $SEPTA_SHARED_DATA.
"""
import glob, hashlib, json, os, subprocess, sys, tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SHARED = os.environ.get("SEPTA_SHARED_DATA") or next(
    (p for p in (os.path.join(HERE, *[".."] * n, "shared", "data") for n in (2, 3, 4)) if os.path.isdir(p)),
    os.path.join(HERE, "..", "..", "shared", "data"))


def hashes(septa, mesh, planes, extra):
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "o")
        r = subprocess.run([septa, "cut", mesh, "--planes", planes, "-o", out, "--threads", "1", "-q"] + extra,
                           capture_output=True, text=True)
        h = {"exit": r.returncode}
        for name in sorted(os.listdir(out)) if os.path.isdir(out) else []:
            p = os.path.join(out, name)
            if not os.path.isfile(p) or name in ("manifest.json", ".septa.lock"):
                continue
            data = open(p, "rb").read()
            if name == "cut.json":
                j = json.loads(data)
                j.pop("seconds", None)
                j.pop("exact_fallbacks", None)
                data = json.dumps(j, sort_keys=True).encode()
            h[name] = hashlib.md5(data).hexdigest()
        return h


def main():
    a = sys.argv[1:]
    septa = a[0]
    compare = a[a.index("--compare") + 1] if "--compare" in a else None
    extra = a[a.index("--extra") + 1].split() if "--extra" in a else []
    cases = sorted(os.path.basename(p)[:-6] for p in glob.glob(os.path.join(SHARED, "topocut", "*.plane")))
    if "--cases" in a:
        cases = a[a.index("--cases") + 1].split(",")
    result = {}
    for c in cases:
        mesh, s = c.rsplit(".", 1)
        result[c] = hashes(septa, os.path.join(SHARED, "meshes", mesh + ".obj"),
                           os.path.join(SHARED, "topocut", c + ".plane"), extra)
        print(c, file=sys.stderr, end=" ", flush=True)
    print(file=sys.stderr)
    if compare is None:
        print(json.dumps(result, indent=1, sort_keys=True))
        return 0
    before = json.load(open(compare))
    diff = [c for c in result if before.get(c) != result[c]]
    for c in diff:
        print(f"{c}: {before.get(c)} -> {result[c]}")
    print(f"{len(result) - len(diff)} of {len(result)} cases byte-identical")
    return 1 if diff else 0


if __name__ == "__main__":
    sys.exit(main())
