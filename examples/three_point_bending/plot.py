#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Renders the three-point bending study to PNG (the paper's Figs 5-7).

usage: python3 examples/three_point_bending/plot.py [output dir]   (default out/three_point_bending)

Writes load_deflection.png, stress_history.png (Fig 6: sigma_xx at the top and bottom of
mid-span against time), flexural_strain.png (Fig 7: simulated against experimental flexural
strain) and crack_caseNN.png (Fig 5: final particles coloured by damage and by sigma_xx); for a
3D run also fracture_surface_caseNN.png (where the two pieces meet, seen along the beam).
"""
import collections
import csv
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "common"))
from plot_setup import matplotlib_for_files  # noqa: E402

matplotlib = matplotlib_for_files()
import matplotlib.pyplot as plt  # noqa: E402

out = Path(sys.argv[1] if len(sys.argv) > 1 else "out/three_point_bending")
summary = list(csv.DictReader(open(out / "summary.csv")))
cases = ["%02d" % int(float(r["case"])) for r in summary]


def history(case):
    return list(csv.DictReader(open(out / f"case{case}_history.csv")))


fig, ax = plt.subplots(figsize=(7, 5))
for case, row in zip(cases, summary):
    h = history(case)
    line, = ax.plot([1e3 * float(r["deflection_m"]) for r in h], [float(r["load_N"]) for r in h], label=f"case {case}")
    ax.plot([1e3 * float(row["dd_exp_m"])], [float(row["P_exp_N"])], "o", color=line.get_color())
ax.set_xlabel("mid-span deflection (mm)")
ax.set_ylabel("load P (N)")
ax.set_title("Load against deflection (dots: Table 1 peak)")
ax.legend()
fig.tight_layout()
fig.savefig(out / "load_deflection.png", dpi=120)

fig, axes = plt.subplots(len(cases), 1, figsize=(7, 2.2 * len(cases)), squeeze=False)
for ax, case in zip(axes[:, 0], cases):
    h = history(case)
    t = [1e3 * float(r["t"]) for r in h]
    ax.plot(t, [1e-6 * float(r["sxx_top_Pa"]) for r in h], label="top")
    ax.plot(t, [1e-6 * float(r["sxx_bottom_Pa"]) for r in h], label="bottom")
    ax.set_ylabel("sigma_xx (MPa)")
    ax.set_title(f"case {case}: horizontal stress at mid-span", fontsize=9)
    ax.legend(fontsize=8)
axes[-1, 0].set_xlabel("t (ms)")
fig.tight_layout()
fig.savefig(out / "stress_history.png", dpi=120)

fig, ax = plt.subplots(figsize=(5, 5))
exp = [float(r["eps_exp"]) for r in summary]
sim = [float(r["eps_sim"]) for r in summary]
ax.plot(exp, sim, "o")
for case, x, y in zip(cases, exp, sim):
    ax.annotate(case, (x, y), textcoords="offset points", xytext=(4, 4))
hi = 1.1 * max(exp + sim)
ax.plot([0, hi], [0, hi], "k-", lw=0.8, label="equal")
ax.plot([0, hi], [0, 1.075 * hi], "k--", lw=0.6, label="+-7.5 %")
ax.plot([0, hi], [0, 0.925 * hi], "k--", lw=0.6)
ax.set_xlabel("experimental flexural strain (Table 1)")
ax.set_ylabel("simulated flexural strain")
ax.set_title("Flexural strain 6 h dd / L^2")
ax.legend()
fig.tight_layout()
fig.savefig(out / "flexural_strain.png", dpi=120)

for case in cases:
    rows = list(csv.DictReader(open(out / f"case{case}_final.csv")))
    x = [1e3 * float(r["x"]) for r in rows]
    y = [1e3 * float(r["y"]) for r in rows]
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(8, 4.5), sharex=True)
    s1 = a1.scatter(x, y, c=[float(r["damage"]) for r in rows], s=4, cmap="inferno_r", vmin=0, vmax=0.5)
    fig.colorbar(s1, ax=a1, label="damage")
    s2 = a2.scatter(x, y, c=[1e-6 * float(r["sxx_Pa"]) for r in rows], s=4, cmap="coolwarm", vmin=-1.5, vmax=1.5)
    fig.colorbar(s2, ax=a2, label="sigma_xx (MPa)")
    for a in (a1, a2):
        a.set_aspect("equal")
        a.set_ylabel("y (mm)")
    a2.set_xlabel("x (mm)")
    a1.set_title(f"case {case}: crack path (damage) and sigma_xx at the end of the run")
    fig.tight_layout()
    fig.savefig(out / f"crack_case{case}.png", dpi=120)
    # 3D runs: the fracture surface seen along the beam, i.e. for every row of particles along x
    # (one reference y, z) where its two large pieces meet, as the x halfway between the last
    # particle of one and the first of the other (blank: the row is not split).
    if "z0" not in rows[0] or all(float(r["z0"]) == 0 for r in rows):
        continue
    sizes = collections.Counter(r["fragment"] for r in rows)
    large = {f for f, n in sizes.items() if n > len(rows) / 10}
    lines = collections.defaultdict(list)
    for r in rows:
        lines[(round(1e3 * float(r["y0"]), 3), round(1e3 * float(r["z0"]), 3))].append((float(r["x0"]), r["fragment"]))
    ys = sorted({k[0] for k in lines})
    zs = sorted({k[1] for k in lines})
    surface = [[float("nan")] * len(zs) for _ in ys]
    for (yk, zk), line in lines.items():
        line = sorted(p for p in line if p[1] in large)  # chips (particles with no bond left) skipped
        cuts = [0.5e3 * (a[0] + b[0]) for a, b in zip(line, line[1:]) if a[1] != b[1]]
        if cuts:
            surface[ys.index(yk)][zs.index(zk)] = max(cuts, key=abs)
    fig, ax = plt.subplots(figsize=(8, 3.5))
    image = ax.pcolormesh(zs, ys, surface, cmap="coolwarm", vmin=-6, vmax=6, shading="nearest")
    fig.colorbar(image, ax=ax, label="x of the fracture surface (mm)")
    ax.set_aspect("equal")
    ax.set_xlabel("z across the width (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title(f"case {case}, 3D: fracture surface between the two pieces")
    fig.tight_layout()
    fig.savefig(out / f"fracture_surface_case{case}.png", dpi=120)
print(f"wrote PNGs to {out}")
