#!/usr/bin/env python3
"""Du et al. 2022, Figures 13-15 (grid benchmarks, Sec. 8.3): the paper plots these and prints no
numbers, except that its MI extraction keeps "a consistent slow-down of 2-3 times compared with
label-separation" and that cell grouping instead of ray shooting costs "often a few times more than
the rest of the entire pipeline". This prints Septa's numbers for the same sweeps:

- Fig. 13 (IA) and Fig. 15 (MI): 4 functions at growing resolutions, then up to 18 functions at the
  highest resolution (`septa bench grid`: active tets, extraction and whole network against the
  label-separating extractor and, for IA, marching tetrahedra; exact against the float variant);
- Fig. 14: separate and nested spheres (data/specs/separate8.json, nested8.json), cells by ray
  shooting against cell grouping (`septa ia --cells raytrace|grouping`).

    python3 scripts/reproduce/du_figures13_15.py SEPTA [--res 20,40,60,80,100] [--functions 2,4,8,12,18]
        [--repeat 3] [--specs data/specs]
"""
import argparse
import os

from common import run_json, septa_path, table

HERE = os.path.dirname(os.path.abspath(__file__))


def bench(septa, mode, f, r, repeat):
    cmd = [septa, "bench", "grid", "--mode", mode, "--functions", str(f), "--resolution", str(r),
           "--repeat", str(repeat), "--json"]
    code, objs, err = run_json(cmd)
    if code != 0 or not objs:
        raise SystemExit(f"{' '.join(cmd)} failed: {err.strip()}")
    o = objs[-1]
    s, q = o["seconds"], o["ratios"]
    row = [mode.upper(), f, f"{r}^3", o["active_tets"], f"{s['extract']:.3f}", f"{s['label_separating']:.3f}",
           f"{q['extract_over_label_separating']:.2f}", f"{s['network']:.3f}", f"{q['exact_over_float']:.2f}"]
    row.append(f"{s['marching_tets']:.3f}" if mode == "ia" and "marching_tets" in s else "-")
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("septa")
    ap.add_argument("--res", default="20,40,60,80,100")
    ap.add_argument("--functions", default="2,4,8,12,18")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--specs", default=os.path.join(HERE, "..", "..", "data", "specs"))
    a = ap.parse_args()
    septa = septa_path(a.septa)
    res = [int(x) for x in a.res.split(",")]
    header = ["mode", "functions", "grid", "active tets", "extract s", "label-separating s", "ratio",
              "whole network s", "exact / float", "marching tets s"]
    for mode, fig in (("ia", "13"), ("mi", "15")):
        rows = [bench(septa, mode, 4, r, a.repeat) for r in res]
        rows += [bench(septa, mode, int(f), res[-1], a.repeat) for f in a.functions.split(",")]
        table(f"Du et al. Fig. {fig} ({mode.upper()}: 4 functions by resolution, then functions at {res[-1]}^3); "
              "paper: MI extraction 2-3x label-separation", header, rows)
    rows = []
    for name in ("separate8", "nested8"):
        spec = os.path.join(a.specs, name + ".json")
        t = {}
        for cells in ("raytrace", "grouping"):
            cmd = [septa, "ia", spec, "--grid", str(res[-1]), "--cells", cells, "--threads", "1", "--no-output",
                   "--json", "-q"]
            code, objs, err = run_json(cmd)
            if code != 0 or not objs:
                raise SystemExit(f"{' '.join(cmd)} failed: {err.strip()}")
            t[cells] = objs[-1]
        sr, sg = t["raytrace"]["seconds"]["total"], t["grouping"]["seconds"]["total"]
        same = all(t["raytrace"][k] == t["grouping"][k] for k in ("cells", "shells", "patches"))
        rows.append([name, f"{res[-1]}^3", t["raytrace"]["cells"], t["raytrace"]["shells"], f"{sr:.3f}", f"{sg:.3f}",
                     f"{sg / sr:.2f}", "yes" if same else "NO"])
    table("Du et al. Fig. 14 (IA, cells by ray shooting against cell grouping); paper: grouping often costs a few "
          "times the rest of the pipeline",
          ["spheres", "grid", "cells", "shells", "ray shooting s", "grouping s", "ratio", "same cells"], rows)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
