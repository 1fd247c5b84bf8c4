#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Plots the dam-break surge front and residual column height (dam_break.csv) against Martin &
Moyce (1952) and Koshizuka & Oka (1996). Usage: python3 examples/dam_break/plot.py OUT_DIR [--shift T]  -> OUT_DIR/dam_break.png"""
import argparse
import csv
import os
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "common"))
from plot_setup import matplotlib_for_files  # noqa: E402

matplotlib = matplotlib_for_files()
import matplotlib.pyplot as plt  # noqa: E402

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "verification", "data")


def read(path, x, y):
    with open(path) as f:
        rows = [r for r in f if not r.startswith("#")]
    reader = csv.DictReader(rows)
    xs, ys = [], []
    for r in reader:
        xs.append(float(r[x]))
        ys.append(float(r[y]))
    return xs, ys


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--shift", type=float, default=0.29,
                    help="time-origin shift of the experiment in T (the one the verification test fits)")
    args = ap.parse_args()
    t, z = read(os.path.join(args.out, "dam_break.csv"), "T", "Z_over_a")
    tau, h = read(os.path.join(args.out, "dam_break.csv"), "tau", "H_over_2a")
    mm_t, mm_z = read(os.path.join(DATA, "dambreak_martin_moyce_front_table.csv"), "T", "Z_over_a")
    ko_t, ko_z = read(os.path.join(DATA, "dambreak_koshizuka_oka1996_front_pysph.csv"), "T", "Z_over_L")
    mh_t, mh_h = read(os.path.join(DATA, "dambreak_martin_moyce_height_table.csv"), "tau", "H_over_2a")

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    ax1.plot(t, z, "-", label="mpsfsi (2D MPS)")
    ax1.plot(mm_t, mm_z, "o", label="Martin & Moyce 1952")
    ax1.plot([v - args.shift for v in mm_t], mm_z, "o", mfc="none",
             label=f"Martin & Moyce, origin shifted by {args.shift:g}")
    ax1.plot(ko_t, ko_z, "s", label="Koshizuka & Oka 1996")
    ax1.set_xlabel(r"$T = t\sqrt{2g/a}$")
    ax1.set_ylabel("surge front $Z/a$")
    ax1.set_xlim(0, max(t))
    ax1.set_ylim(1, 4)
    ax1.grid(alpha=0.3)
    ax1.legend(fontsize=8)
    ax2.plot(tau, h, "-", label="mpsfsi (2D MPS)")
    ax2.plot(mh_t, mh_h, "o", label="Martin & Moyce 1952")
    ax2.set_xlabel(r"$\tau = t\sqrt{g/a}$")
    ax2.set_ylabel("column height $H/2a$")
    ax2.set_xlim(0, max(tau))
    ax2.grid(alpha=0.3)
    ax2.legend(fontsize=8)
    fig.tight_layout()
    path = os.path.join(args.out, "dam_break.png")
    fig.savefig(path, dpi=120)
    print("wrote", path)


if __name__ == "__main__":
    main()
