#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Plots the hydrostatic plate's mid-span deflection (and, when coupled, the load on the plate)
against time, with the analytic deflection of Fourey et al. (2017).

usage: python3 examples/hydrostatic_plate/plot.py [output dir]   (default out/hydrostatic_plate)
"""
import csv
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "common"))
from plot_setup import matplotlib_for_files  # noqa: E402

matplotlib = matplotlib_for_files()
import matplotlib.pyplot as plt  # noqa: E402

# Euler-Bernoulli, both ends clamped, water load only: w = rho g H L^4 / (384 D),
# D = E e^3 / (12 (1 - nu^2)) with E = 67.5 GPa, nu = 0.34, e = 0.05 m, H = 2 m, L = 1 m.
ANALYTIC = 6.4266e-5

out = Path(sys.argv[1] if len(sys.argv) > 1 else "out/hydrostatic_plate")
rows = list(csv.DictReader(open(out / "midspan.csv")))
t = [1e3 * float(r["t"]) for r in rows]
coupled = "load_over_weight" in rows[0]
fig, axes = plt.subplots(2 if coupled else 1, 1, figsize=(7, 6 if coupled else 3.5), sharex=True, squeeze=False)
ax = axes[0][0]
ax.plot(t, [1e6 * float(r["deflection"]) for r in rows], label="mid-span deflection, mpsfsi")
ax.axhline(1e6 * ANALYTIC, color="k", ls="--", lw=1, label="analytic (Euler-Bernoulli), 64.3 um")
ax.set_ylabel("deflection (um)")
ax.set_title("Hydrostatic water column on a clamped plate" + ("" if coupled else ": the plate alone under rho g H"))
ax.legend()
if coupled:
    ax2 = axes[1][0]
    ax2.plot(t, [float(r["load_over_weight"]) for r in rows], label="fluid force on the plate / water weight")
    ax2.axhline(1.0, color="k", ls="--", lw=1)
    ax2.set_ylabel("load / W")
    ax2.legend()
axes[-1][0].set_xlabel("t (ms)")
fig.tight_layout()
fig.savefig(out / "midspan.png", dpi=120)
print(f"wrote {out / 'midspan.png'}")
