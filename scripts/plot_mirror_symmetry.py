#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Renders the double-notched plate of verification.fracture.mirror_symmetry: where particles
failed with each cutting rule (CrackSide::fixed_sign, CrackSide::attachment and the default
CrackSide::slab), at l0 = 1 mm and 32 m/s, coloured by the time of failure.

    python3 scripts/plot_mirror_symmetry.py build/tests/work [docs/images/fracture_mirror_symmetry.png]
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return ([float(r["x0"]) * 1e3 for r in rows], [float(r["y0"]) * 1e3 for r in rows],
            [float(r["t"]) * 1e6 for r in rows])


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    folder = sys.argv[1]
    out = sys.argv[2] if len(sys.argv) > 2 else "fracture_mirror_symmetry.png"
    fig, axes = plt.subplots(1, 3, figsize=(14, 5.0), constrained_layout=True)
    rules = (("fixed_sign", "fixed_sign"), ("attachment", "attachment"), ("slab", "slab (default)"))
    for ax, (side, title) in zip(axes, rules):
        try:
            x, y, t = read(f"{folder}/mirror_symmetry_{side}_l0_1mm_32ms.csv")
        except OSError as e:
            sys.exit(f"plot_mirror_symmetry.py: {e}; run ctest -R verification.fracture.mirror_symmetry first")
        points = ax.scatter(x, y, c=t, s=6, cmap="viridis", vmin=0, vmax=60)
        for notch_x in (-12, 12):
            ax.plot([notch_x, notch_x], [0, 25], color="black", lw=1.5)
        ax.axvline(0, color="grey", lw=0.5, ls="--")
        ax.annotate("impact", (0, 1), xytext=(0, 8), ha="center", arrowprops={"arrowstyle": "->"})
        ax.set_xlim(-50, 50)
        ax.set_ylim(0, 100)
        ax.set_aspect("equal")
        ax.set_xlabel("x (mm)")
        ax.set_title(f"CrackSide::{title}")
    axes[0].set_ylabel("y (mm)")
    fig.colorbar(points, ax=axes, label="time of failure (us)", shrink=0.8)
    fig.savefig(out, dpi=110)
    print("wrote", out)


if __name__ == "__main__":
    main()
