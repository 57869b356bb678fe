"""Writes the label volume of docs/performance.md: N^3 voxels, label 0 with
four overlapping balls labelled 1..4 (later balls overwrite earlier ones).

    python scripts/make_label_blobs.py 128 blobs128.npy
"""
import sys

import numpy as np


def blobs(n):
    x = np.linspace(0, 1, n)
    X, Y, Z = np.meshgrid(x, x, x, indexing="ij")
    lab = np.zeros((n, n, n), dtype=np.int64)
    balls = [((0.35, 0.4, 0.45), 0.22), ((0.62, 0.55, 0.5), 0.25), ((0.5, 0.3, 0.7), 0.18), ((0.45, 0.7, 0.35), 0.2)]
    for i, (c, r) in enumerate(balls):
        lab[(X - c[0]) ** 2 + (Y - c[1]) ** 2 + (Z - c[2]) ** 2 < r * r] = i + 1
    return lab


if __name__ == "__main__":
    np.save(sys.argv[2], blobs(int(sys.argv[1])))
