#!/usr/bin/env python3
"""Du et al. 2022, Table 3: mean and standard deviation of the incremental construction of an IA
inside one tetrahedron for N = 1, 2, 3 random linear functions (no look-up tables), the paper's
algorithm and CGAL's exact clipping beside Septa (`septa bench tet --no-lookup`), and Septa with
its look-up tables.

    python3 scripts/reproduce/du_table3_per_tet.py SEPTA [--count 100000]

The paper ran 100 instances on its machine (Intel, 2022); Septa's figures are from this run on this
machine: compare ratios, not microseconds across machines.
"""
import argparse

from common import run_json, septa_path, table

PAPER = {1: ((666.3, 186.1), (6.6, 1.1)), 2: ((1754.8, 673.6), (13.7, 2.5)), 3: ((3302.8, 1403.6), (26.3, 5.5))}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("septa")
    ap.add_argument("--count", type=int, default=100000, help="tetrahedra per N (the paper: 100)")
    ap.add_argument("--seed", type=int, default=0)
    a = ap.parse_args()
    septa = septa_path(a.septa)
    rows = []
    for n in (1, 2, 3):
        res = {}
        for lookup in (False, True):
            cmd = [septa, "bench", "tet", "--functions", str(n), "--count", str(a.count), "--seed", str(a.seed), "--json"]
            code, objs, err = run_json(cmd + ([] if lookup else ["--no-lookup"]))
            if code != 0 or not objs:
                raise SystemExit(f"{' '.join(cmd)} failed: {err.strip()}")
            res[lookup] = objs[-1]
        (cg, cs), (om, os_) = PAPER[n]
        inc = res[False]
        rows.append([n, f"{cg} ± {cs}", f"{om} ± {os_}", f"{inc['mean_us']:.2f} (median {inc['median_us']:.2f})",
                     f"{res[True]['mean_us']:.2f}", f"{inc['float_mean_us']:.2f}"])
    table(f"Du et al. Table 3 beside Septa (us per tetrahedron, {a.count} tetrahedra per N)",
          ["N", "paper CGAL mean ± sd", "paper ours mean ± sd", "Septa incremental mean", "Septa with tables",
           "Septa float variant"], rows)
    print("\nSepta's standard deviation is not comparable: its timer resolution per tetrahedron is coarse; "
          "the medians are printed instead.")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
