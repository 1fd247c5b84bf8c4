#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Plots the floating ice beam: the settled deflection against Hetenyi's semi-infinite beam, the
end load against the end deflection, and where the particles failed.

usage: python3 examples/floating_ice_beam/plot.py [output dir]   (default out/floating_ice_beam)
"""
import csv
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "common"))
from plot_setup import matplotlib_for_files  # noqa: E402

matplotlib = matplotlib_for_files()
import matplotlib.pyplot as plt  # noqa: E402

out = Path(sys.argv[1] if len(sys.argv) > 1 else "out/floating_ice_beam")


def read(name):
    return list(csv.DictReader(open(out / name)))


summary = read("summary.csv")[0]
lam = float(summary["lambda"])
x_f = float(summary["largest_moment_x"])
Pf = float(summary["failure_load"])

# The settled deflection at P_f / 2 against Hetenyi's w(x) = (2 P lambda / k) e^(-lambda x) cos(lambda x).
rows = read("deflection.csv")
x = [float(r["x"]) for r in rows]
fig, ax = plt.subplots(figsize=(8, 4))
ax.plot(x, [1e3 * float(r["hetenyi_w"]) for r in rows], "k-", lw=1, label="Hetényi, semi-infinite beam")
ax.plot(x, [1e3 * float(r["w"]) for r in rows], "o", ms=2.5, label="mpsfsi (column means)")
ax.axvline(3 / lam, color="0.7", lw=0.8)
ax.text(3 / lam, ax.get_ylim()[1], " 3/λ", va="top", color="0.4")
ax.invert_yaxis()
ax.set_xlabel("x from the loaded end (m)")
ax.set_ylabel("deflection, down (mm)")
ax.set_title(f"Settled deflection at P = P_f/2: end {100 * float(summary['end_error']):+.2f} %, "
             f"profile RMS {100 * float(summary['profile_rms']):.2f} %")
ax.legend()
fig.tight_layout()
fig.savefig(out / "deflection.png", dpi=120)
print(f"wrote {out / 'deflection.png'}")

# End load against end deflection; Hetenyi's line is the settled response.
rows = read("history.csv")
fig, ax = plt.subplots(figsize=(6, 4.5))
ax.plot([1e3 * float(r["end_deflection"]) for r in rows], [float(r["P"]) for r in rows], lw=1, label="mpsfsi")
ax.plot([1e3 * float(r["hetenyi_end_deflection"]) for r in rows], [float(r["P"]) for r in rows], "k--", lw=0.8,
        label="Hetényi, 2 P λ / k")
ax.axhline(Pf, color="0.6", lw=0.8)
ax.text(0, Pf, " P_f (Croasdale's breaking term)", va="bottom", color="0.4")
if int(float(summary["failures"])) > 0:
    ax.plot([], [], " ", label=f"first failure at P = {float(summary['load_at_failure']):.2f} N/m")
ax.set_xlabel("end deflection (mm)")
ax.set_ylabel("end load P (N/m)")
ax.set_title("While P ramps the end lags; at each hold it settles onto Hetényi's line", fontsize=10)
ax.legend(loc="lower right")
fig.tight_layout()
fig.savefig(out / "load_deflection.png", dpi=120)
print(f"wrote {out / 'load_deflection.png'}")

# Where particles failed (reference positions), coloured by time after the first failure.
if (out / "failures.csv").exists():
    rows = read("failures.csv")
    t0 = float(rows[0]["t"])
    h, l0 = float(summary["thickness"]), float(summary["l0"])
    xs, ys = [float(r["x0"]) for r in rows], [float(r["y0"]) for r in rows]
    top = max(ys) + l0 / 2  # the top face (the first failure is in the top row)
    fig, ax = plt.subplots(figsize=(9, 2.8))
    x0, x1 = min(xs + [x_f]) - 2 * h, max(xs + [x_f]) + 2 * h
    ax.plot([x0, x1, x1, x0, x0], [top - h, top - h, top, top, top - h], color="0.6", lw=0.8)
    sc = ax.scatter(xs, ys, c=[1e3 * (float(r["t"]) - t0) for r in rows], s=14, cmap="viridis", zorder=3)
    fig.colorbar(sc, ax=ax, label="ms after the first failure")
    ax.axvline(x_f, color="r", lw=0.8)
    ax.text(x_f, top + 0.1 * h, " π/(4λ)", color="r")
    ax.set_xlim(x0, x1)
    ax.set_ylim(top - 1.3 * h, top + 0.5 * h)
    ax.set_aspect("equal")
    ax.set_xlabel("x from the loaded end (m)")
    ax.set_ylabel("y (m)")
    pieces = int(float(summary["pieces"]))
    title = f"Failed particles (reference positions); pieces: {pieces}"
    if pieces >= 2:
        title += f", the far one from x = {float(summary['far_piece_x']):.4f} m"
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(out / "failures.png", dpi=120)
    print(f"wrote {out / 'failures.png'}")
