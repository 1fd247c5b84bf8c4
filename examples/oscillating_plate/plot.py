#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Plots the oscillating plate's tip displacement and energies to PNG.

usage: python3 examples/oscillating_plate/plot.py [output dir]   (default out/oscillating_plate)
"""
import csv
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "common"))
from plot_setup import matplotlib_for_files  # noqa: E402

matplotlib = matplotlib_for_files()
import matplotlib.pyplot as plt  # noqa: E402

out = Path(sys.argv[1] if len(sys.argv) > 1 else "out/oscillating_plate")
rows = list(csv.DictReader(open(out / "oscillating_plate.csv")))
t = [float(r["t"]) for r in rows]
fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
ax1.plot(t, [1e3 * float(r["tip_dy"]) for r in rows], label="tip displacement")
period = 0.25403  # Gray, Monaghan & Swift (2001), plane strain
for k in range(1, int(t[-1] / period) + 1):
    ax1.axvline(k * period, color="0.8", lw=0.8)
ax1.set_ylabel("tip displacement (mm)")
ax1.set_title("Oscillating plate; grey lines: multiples of the analytic period 0.254 s")
for key in ("kinetic", "strain", "total"):
    ax2.plot(t, [float(r[key]) for r in rows], label=key)
ax2.set_xlabel("t (s)")
ax2.set_ylabel("energy (J/m)")
ax2.legend()
fig.tight_layout()
fig.savefig(out / "oscillating_plate.png", dpi=120)
print(f"wrote {out / 'oscillating_plate.png'}")
