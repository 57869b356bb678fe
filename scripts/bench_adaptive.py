#!/usr/bin/env python3
"""Side by side on the 2024 adaptive-grid paper's figures (shared/data/adaptive): its program
(grid refinement, then the Du et al. extraction program on the grid it writes) against
`septa ia|mi|regions SCENE --adaptive --tolerance D`, at the same tolerance, one process each,
alternating run by run. Prints per figure and tool: grid tets and vertices, wall seconds (refine +
extract), patches / chains / cells, and the measured error: the largest distance from an output
vertex to the true surfaces.

Usage:
  bench_adaptive.py --anchor ISOSURFACING --risn RISN_BUILD_DIR [--septa SEPTA] [--data DIR]
                    [--figures 10d,11b,...] [--rounds N] [--markdown]

The programs are built in a temporary folder from their public repositories (see
shared/data/adaptive/README.md); Septa's `--adaptive` may be absent (then only the anchor's side
is measured and Septa's columns say so).

The error: each output vertex is projected by Newton steps onto the zero set of the function
(IA, CSG: each function; MI: the difference of the two largest at the vertex) and the smallest
such distance is its error; the table gives the largest over the vertices. Functions are
evaluated here with numpy from the same files (sphere, plane, cylinder, torus with `squared`,
the closed forms and Hermite RBFs), so both tools are measured by one yardstick.
"""
import argparse, json, os, statistics, subprocess, sys, tempfile, time

import numpy as np

# id: (folder, start grid, function file, mode, tolerance, tree)
FIGURES = {
    "1a": ("Figure1", "../mesh/cube6.msh", "10-wikiBall.json", "IA", 5e-4, None),
    "1b": ("Figure1", "../mesh/cube6.msh", "10-wikiBall.json", "CSG", 5e-4, "10-wikiBall-tree.json"),
    "10d": ("Figure10", "grid_1.json", "2-cylSphere.json", "IA", 0.01, None),
    "11b": ("Figure11", "grid_1.json", "3-cylinder.json", "IA", 0.005, None),
    "13b": ("Figure13", "grid_1.json", "figure13.json", "MI", 0.001, None),
    "14b": ("Figure14", "grid_1.json", "figure14.json", "CSG", 0.001, "figure14_tree.json"),
    "15": ("Figure15", "grid_1.json", "figure15.json", "IA", 0.005, None),
    "18": ("Figure18", "grid_1.json", "config.json", "IA", 0.005, None),
    "20a": ("Figure20", "grid_1.json", "csg_examples_1.json", "CSG", 0.01, "csg_examples_1_tree.json"),
    "21a": ("Figure21", "grid_1.json", "csg_examples_3.json", "CSG", 0.03, "csg_examples_3_tree.json"),
    "22a": ("Figure22", "grid_1.json", "config.json", "IA", 0.008, None),
}


# ---------------------------------------------------------------- functions (numpy, positive inside)

def _unit(v):
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


WAVES = [(15.343274134071653, -9.21125890435288, -18.2340614919869, 1.0),
         (4.801594243303487, 7.985828093490334, -10.314294288432725, 1.0),
         (6.54696301939958, -18.46419127184428, -1.2648908198491549, -1.0)]


def load_functions(path):
    """A list of callables p (n x 3) -> values (n), for the anchor's function file."""
    d = json.load(open(path))
    if isinstance(d, dict):
        d = d["input"]
    base = os.path.dirname(path)
    out = []
    for f in d:
        t = f["type"]
        sq = f.get("squared", False)
        if t == "sphere":
            c, r = np.array(f["center"], float), f["radius"]
            out.append((lambda p, c=c, r=r, sq=sq: r * r - ((p - c) ** 2).sum(1) if sq
                        else r - np.linalg.norm(p - c, axis=1)))
        elif t == "plane":
            q, n = np.array(f["point"], float), _unit(f["normal"])
            out.append(lambda p, q=q, n=n: (p - q) @ n)
        elif t == "cylinder":
            q, a, r = np.array(f["axis_point"], float), _unit(f["axis_vector"]), f["radius"]

            def cyl(p, q=q, a=a, r=r, sq=sq):
                v = p - q
                w = v - np.outer(v @ a, a)
                d2 = (w ** 2).sum(1)
                return r * r - d2 if sq else r - np.sqrt(d2)
            out.append(cyl)
        elif t == "torus":
            c, a = np.array(f["center"], float), _unit(f["axis_vector"])
            R, r = f["major_radius"], f["minor_radius"]

            def tor(p, c=c, a=a, R=R, r=r, sq=sq):
                v = p - c
                h = v @ a
                rho = np.linalg.norm(v - np.outer(h, a), axis=1)
                d2 = (rho - R) ** 2 + h ** 2
                return r * r - d2 if sq else r - np.sqrt(d2)
            out.append(tor)
        elif t == "Gaussian":
            out.append(lambda p: (lambda x, y, z: 3.4641 - 2.3094 * (x + y + z) + 2 * np.exp(
                -21.3333 * (x * x + y * y + z * z - x * y - y * z - z * x)))(*p.T))
        elif t == "smile":
            out.append(lambda p: (lambda u, v, w: (1 + v - u * u - v * v) ** 4 + (u * u + v * v + w * w) ** 4 - 1)(
                *(2 * (p - 0.51)).T))
        elif t == "cyclide":
            out.append(lambda p: (lambda u, v, w: 7984 + 2400 * u - 20800 * u * u - 19200 * v * v + 19200 * w * w
                                  + 10000 * (u * u + v * v + w * w) ** 2)(*(3 * (p - 0.5)).T))
        elif t == "wave":
            out.append(lambda p: 2 - 4 * p[:, 2] + sum(s * np.sin(a + b * p[:, 0] + c * p[:, 1])
                                                       for a, b, c, s in WAVES) / 3)
        elif t == "teardrop":
            out.append(lambda p: (lambda u, v, w: 0.5 * u ** 5 + 0.5 * u ** 4 - v * v - w * w)(*(2 * (p - 0.5)).T))
        elif t == "rbf":
            txt = open(os.path.join(base, f["points"])).read().split()
            ctr = np.array(txt[1:], float).reshape(-1, 3)
            lines = [l for l in open(os.path.join(base, f["rbf_coeffs"])).read().splitlines() if l.strip()]
            co = np.array(lines[0].split(), float)
            poly = np.array(lines[1].split(), float)
            n = len(ctr)
            a, b = co[:n], co[n:].reshape(3, n).T

            def rbf(p, ctr=ctr, a=a, b=b, poly=poly):
                out = np.empty(len(p))
                for k in range(0, len(p), 256):
                    d = p[k:k + 256, None, :] - ctr[None]
                    r = np.linalg.norm(d, axis=2)
                    out[k:k + 256] = (a * r ** 3).sum(1) + 3 * (r * (d * b[None]).sum(2)).sum(1)
                return out + poly[0] + p @ poly[1:]
            out.append(rbf)
        else:
            raise ValueError(f"{path}: function type {t} not supported here")
    return out


def newton_distance(g, p, steps=6, h=1e-7):
    """Distance from each row of p to the zero set of g by Newton steps along the
    (central-difference) gradient: the length of the path, a close estimate near the set."""
    q = p.copy()
    for _ in range(steps):
        v = g(q)
        grad = np.stack([(g(q + h * e) - g(q - h * e)) / (2 * h) for e in np.eye(3)], 1)
        n2 = np.maximum((grad ** 2).sum(1), 1e-300)
        q = q - (v / n2)[:, None] * grad
    return np.linalg.norm(q - p, axis=1)


def measured_error(funcs, mode, pts):
    if len(pts) == 0:
        return float("nan")
    pts = np.asarray(pts, float)
    if mode == "MI":
        vals = np.stack([f(pts) for f in funcs], 1)
        top = np.argsort(-vals, axis=1)[:, :2]
        best = np.empty(len(pts))
        for i, j in {tuple(x) for x in top.tolist()}:
            sel = (top[:, 0] == i) & (top[:, 1] == j)
            best[sel] = newton_distance(lambda q: funcs[i](q) - funcs[j](q), pts[sel])
        return float(best.max())
    d = np.stack([newton_distance(f, pts) for f in funcs], 1)
    return float(d.min(1).max())


# ---------------------------------------------------------------- the two tools

def timed(cmd, cwd):
    t0 = time.perf_counter()
    r = subprocess.run(cmd, cwd=cwd, stdout=subprocess.DEVNULL if "--json" not in cmd else subprocess.PIPE,
                       stderr=subprocess.PIPE, text=True, timeout=3600)
    return time.perf_counter() - t0, r


def run_anchor(args, fig, d):
    folder, start, funcs, mode, tol, tree = FIGURES[fig]
    src = os.path.join(args.data, folder)
    cmd = [args.anchor, os.path.join(src, start), os.path.join(src, funcs), "-t", str(tol)]
    if mode != "IA":
        cmd += ["-o", mode]
    if tree:
        cmd += ["--tree", os.path.join(src, tree)]
    t_refine, r = timed(cmd, d)
    if r.returncode != 0:
        return {"error": f"refinement exited {r.returncode}: {r.stderr[-200:]}"}
    stats = json.load(open(os.path.join(d, "stats.json")))
    verts, tets = json.load(open(os.path.join(d, "mesh.json")))
    row = {"tets": int(stats["total tet number: "]), "vertices": len(verts), "refine_s": t_refine}
    # Extraction: the full arrangement (IA, also for CSG rows, as the paper's counts) or MI.
    exe = "material_interface" if mode == "MI" else "impl_arrangement"
    cfg = {"gridResolution": 1, "gridBbox": [[0, 0, 0], [1, 1, 1]], "tetMeshFile": "mesh.json",
           "funcFile": "function_value.json", "outputDir": "risn", "useLookup": True,
           "useSecondaryLookup": True, "useTopoRayShooting": True}
    os.makedirs(os.path.join(d, "risn"), exist_ok=True)
    json.dump(cfg, open(os.path.join(d, "risn.json"), "w"))
    t_ex, r = timed([os.path.join(args.risn, exe), "risn.json"], d)
    row["extract_s"] = t_ex
    if r.returncode != 0:
        row["error"] = f"extraction exited {r.returncode}"
        return row
    st = json.load(open(os.path.join(d, "risn", "stats.json")))
    row["counts"] = (st.get("num_patches"), st.get("num_chains"), st.get("num_cells"))
    mesh = json.load(open(os.path.join(d, "risn", "mesh.json")))
    row["points"] = mesh.get("points") or mesh.get("vertices") or []
    return row


def run_septa(args, fig, d, scene):
    folder, start, funcs, mode, tol, tree = FIGURES[fig]
    cmd = [args.septa, {"IA": "ia", "MI": "mi", "CSG": "regions"}[mode], scene, "--adaptive",
           "--tolerance", str(tol), "--threads", "1", "--json", "--format", "obj", "-o", os.path.join(d, "out")]
    t, r = timed(cmd, d)
    if r.returncode != 0:
        msg = r.stderr.strip().splitlines()[-1] if r.stderr.strip() else f"exit {r.returncode}"
        return {"error": "septa: " + msg[:160]}
    info = json.loads(r.stdout) if r.stdout.strip() else {}

    def find(o, keys):
        if isinstance(o, dict):
            for k, v in o.items():
                if k in keys and isinstance(v, (int, float)):
                    return v
                x = find(v, keys)
                if x is not None:
                    return x
        return None
    pts = []
    for name in os.listdir(os.path.join(d, "out")):
        if name.endswith(".obj"):
            pts += [list(map(float, l.split()[1:4])) for l in open(os.path.join(d, "out", name)) if l.startswith("v ")]
    return {"tets": find(info, {"tets", "grid_tets"}), "vertices": find(info, {"grid_vertices"}),
            "refine_s": t, "extract_s": 0.0,
            "counts": (find(info, {"patches"}), find(info, {"chains"}), find(info, {"cells", "regions"})),
            "points": pts}


def scene_for(args, fig, d):
    """A Septa scene file for the figure: the same function file, start box and CSG tree."""
    folder, start, funcs, mode, tol, tree = FIGURES[fig]
    src = os.path.join(args.data, folder)
    if start.endswith(".msh"):
        grid = {"resolution": 1, "bounds": [[0, 0, 0], [1, 1, 1]], "split": 6}
    else:
        g = json.load(open(os.path.join(src, start)))
        n = g["resolution"][0] if isinstance(g["resolution"], list) else g["resolution"]
        grid = {"resolution": n, "bounds": [g["bbox_min"], g["bbox_max"]], "split": 6}
    sc = {"grid": grid, "mode": "mi" if mode == "MI" else "ia", "functions": os.path.join(src, funcs)}
    if tree:
        # The figures' trees are written for the paper's program's reading (in where negative).
        sc["solid"] = {"csg_tree": os.path.join(src, tree), "inside": "negative"}
    path = os.path.join(d, f"scene_{fig}.json")
    json.dump(sc, open(path, "w"))
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--anchor", required=True, help="the adaptive-grid program (isosurfacing)")
    ap.add_argument("--risn", required=True, help="build folder of the Du et al. extraction programs")
    ap.add_argument("--septa", default=None)
    ap.add_argument("--data", default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                   "..", "..", "shared", "data", "adaptive"))
    ap.add_argument("--figures", default=",".join(FIGURES))
    ap.add_argument("--rounds", type=int, default=1)
    ap.add_argument("--markdown", action="store_true")
    args = ap.parse_args()
    args.anchor, args.risn = os.path.abspath(args.anchor), os.path.abspath(args.risn)
    args.septa = os.path.abspath(args.septa) if args.septa else None
    if not os.path.isdir(args.data):
        args.data = "/work/shared/data/adaptive"
    rows = []
    for fig in args.figures.split(","):
        folder, start, funcs, mode, tol, tree = FIGURES[fig]
        fns = load_functions(os.path.join(args.data, folder, funcs))
        res = {"anchor": [], "septa": []}
        with tempfile.TemporaryDirectory() as top:
            scene = scene_for(args, fig, top)
            for k in range(args.rounds):
                for tool in (["anchor", "septa"] if k % 2 == 0 else ["septa", "anchor"]):
                    if tool == "septa" and not args.septa:
                        continue
                    d = os.path.join(top, f"{tool}{k}")
                    os.makedirs(d)
                    row = run_anchor(args, fig, d) if tool == "anchor" else run_septa(args, fig, d, scene)
                    res[tool].append(row)
        for tool in ("anchor", "septa"):
            runs = [r for r in res[tool] if "error" not in r]
            if not res[tool]:
                rows.append((fig, mode, tol, tool, "not run"))
                continue
            if not runs:
                rows.append((fig, mode, tol, tool, res[tool][0]["error"]))
                continue
            r = runs[0]
            wall = statistics.median(x["refine_s"] + x["extract_s"] for x in runs)
            err = measured_error(fns, "MI" if mode == "MI" else "IA", r.get("points", []))
            c = r.get("counts", (None,) * 3)
            rows.append((fig, mode, tol, tool, r.get("tets"), r.get("vertices"), round(wall, 3),
                         round(statistics.median(x["refine_s"] for x in runs), 3), "/".join(str(x) for x in c),
                         f"{err:.2e}"))
    head = ("figure", "mode", "tolerance", "tool", "tets", "vertices", "wall s", "refine s",
            "patches/chains/cells", "max error")
    if args.markdown:
        print("| " + " | ".join(head) + " |")
        print("|" + "---|" * len(head))
        for r in rows:
            print("| " + " | ".join(str(x) for x in r) + " |")
    else:
        for r in [head] + rows:
            print("  ".join(str(x) for x in r))


if __name__ == "__main__":
    main()
