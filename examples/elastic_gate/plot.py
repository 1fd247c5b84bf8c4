#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Renders the elastic-gate run to PNG.

usage: python3 examples/elastic_gate/plot.py [output dir]   (default out/elastic_gate)

Writes gate_tip.png: the horizontal and vertical displacement of the gate's free end against time,
and below it the fastest fluid particle's speed and the time step it sets (Courant limit).
"""
import csv
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "common"))
from plot_setup import matplotlib_for_files  # noqa: E402

matplotlib = matplotlib_for_files()
import matplotlib.pyplot as plt  # noqa: E402

out = Path(sys.argv[1] if len(sys.argv) > 1 else "out/elastic_gate")
rows = list(csv.DictReader(open(out / "gate_tip.csv")))
t = [float(r["t"]) for r in rows]
fig, (ax, speed_ax) = plt.subplots(2, 1, figsize=(7, 6), sharex=True, gridspec_kw={"height_ratios": (2, 1)})
ax.plot(t, [float(r["dx"]) for r in rows], label="horizontal")
ax.plot(t, [float(r["dy"]) for r in rows], label="vertical")
ax.set_ylabel("gate tip displacement (m)")
ax.set_title("Dam break through an elastic gate (Antoci et al. 2007 set-up)")
ax.legend()
ax.grid(alpha=0.3)
speed_ax.plot(t, [float(r["fastest_fluid_speed"]) for r in rows], color="C2")
speed_ax.set_ylabel("fastest fluid (m/s)", color="C2")
speed_ax.set_xlabel("t (s)")
speed_ax.grid(alpha=0.3)
dt_ax = speed_ax.twinx()
dt_ax.plot(t[1:], [1e3 * float(r["dt"]) for r in rows[1:]], color="C3", lw=0.8)
dt_ax.set_ylabel("time step (ms)", color="C3")
dt_ax.set_yscale("log")
fig.tight_layout()
fig.savefig(out / "gate_tip.png", dpi=120)
print(f"wrote {out / 'gate_tip.png'}")
