#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Renders the elastic-gate run to PNG.

usage: python3 examples/elastic_gate/plot.py [output dir]   (default out/elastic_gate)

Writes gate_tip.png: the horizontal and vertical displacement of the gate's free end against time.
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
fig, ax = plt.subplots(figsize=(7, 4))
ax.plot(t, [float(r["dx"]) for r in rows], label="horizontal")
ax.plot(t, [float(r["dy"]) for r in rows], label="vertical")
ax.set_xlabel("t (s)")
ax.set_ylabel("gate tip displacement (m)")
ax.set_title("Dam break through an elastic gate (Antoci et al. 2007 set-up)")
ax.legend()
ax.grid(alpha=0.3)
fig.tight_layout()
fig.savefig(out / "gate_tip.png", dpi=120)
print(f"wrote {out / 'gate_tip.png'}")
