#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Renders the droplet-on-ice-beam runs to PNG (the paper's Figs 11-14).

usage: python3 examples/droplet_on_ice_beam/plot.py [output dir]   (default out/droplet_on_ice_beam)

Writes snapshots.png (t = 4..10 ms; columns: sigma_xx without fracture, sigma_xx with fracture,
damage with fracture; water in blue; of a 3D run the layer of particles nearest mid-width),
tip.png (beam-tip displacement against time, both runs), energy.png (beam and droplet energy
against time, over its initial value) and crack_path.png (every particle failure at its initial
position, coloured by time).
"""
import csv
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "common"))
from plot_setup import matplotlib_for_files  # noqa: E402

matplotlib = matplotlib_for_files()
import matplotlib.pyplot as plt  # noqa: E402

out = Path(sys.argv[1] if len(sys.argv) > 1 else "out/droplet_on_ice_beam")
runs = [r for r in ("without_fracture", "with_fracture") if (out / r).is_dir()]
if not runs:
    sys.exit(f"no runs found in {out}")


def rows(path):
    return list(csv.DictReader(open(path)))


def mid_layer(beam, fluid):
    """Of a 3D run (beam rows with z0, the reference z): the beam's particle layer nearest
    mid-width and the water within half a spacing of it, as a section like the 2D run's. 2D rows
    are returned unchanged."""
    if not beam or "z0" not in beam[0]:
        return beam, fluid
    layers = sorted({float(p["z0"]) for p in beam})
    spacing = min(b - a for a, b in zip(layers, layers[1:])) if len(layers) > 1 else 1.0
    middle = min(layers, key=lambda z: abs(z - 0.5 * (layers[0] + layers[-1])))
    return ([p for p in beam if float(p["z0"]) == middle],
            [p for p in fluid if abs(float(p["z"]) - middle) <= 0.5 * spacing])


frames = range(4, 11)  # snapshots are written every millisecond from t = 0
columns = [(run, field) for run in runs for field in (("sxx_Pa",) if run == "without_fracture" else ("sxx_Pa", "damage"))]
fig, axes = plt.subplots(len(frames), len(columns), figsize=(4.2 * len(columns), 1.5 * len(frames)), squeeze=False,
                         constrained_layout=True)
last = {}
for r, frame in enumerate(frames):
    for c, (run, field) in enumerate(columns):
        ax = axes[r][c]
        beam_file = out / run / f"snapshot_{frame:02d}_beam.csv"
        if not beam_file.exists():
            ax.axis("off")
            continue
        beam, fluid = mid_layer(rows(beam_file), rows(out / run / f"snapshot_{frame:02d}_fluid.csv"))
        ax.scatter([float(p["x"]) for p in fluid], [float(p["y"]) for p in fluid], s=0.3, c="tab:blue", alpha=0.4)
        values = [float(p[field]) * (1e-6 if field == "sxx_Pa" else 1) for p in beam]
        kw = dict(cmap="coolwarm", vmin=-3, vmax=3) if field == "sxx_Pa" else dict(cmap="inferno_r", vmin=0, vmax=0.5)
        sc = ax.scatter([float(p["x"]) for p in beam], [float(p["y"]) for p in beam], c=values, s=0.5, **kw)
        ax.set_aspect("equal")
        ax.set_xlim(-0.01, 0.62)
        ax.set_ylim(-0.12, 0.2)
        ax.tick_params(labelsize=6)
        if r == 0:
            label = "sigma_xx (MPa)" if field == "sxx_Pa" else "damage"
            ax.set_title(f"{run.replace('_', ' ')}: {label}", fontsize=8)
        if c == 0:
            ax.set_ylabel(f"t = {frame} ms", fontsize=8)
        last[c] = sc
for c, sc in last.items():
    fig.colorbar(sc, ax=[axes[r][c] for r in range(len(frames))], orientation="horizontal", fraction=0.03, pad=0.01)
fig.savefig(out / "snapshots.png", dpi=130)

fig, ax = plt.subplots(figsize=(7, 4))
for run in runs:
    h = rows(out / run / "tip.csv")
    ax.plot([1e3 * float(p["t"]) for p in h], [1e3 * float(p["tip_dy"]) for p in h], label=run.replace("_", " "))
ax.set_xlabel("t (ms)")
ax.set_ylabel("beam-tip vertical displacement (mm)")
ax.legend()
fig.tight_layout()
fig.savefig(out / "tip.png", dpi=120)

fig, ax = plt.subplots(figsize=(7, 4))
for run in runs:
    h = rows(out / run / "tip.csv")
    total = [float(p["beam_kinetic_J"]) + float(p["beam_strain_J"]) + float(p["fluid_kinetic_J"]) for p in h]
    ax.plot([1e3 * float(p["t"]) for p in h], [e / total[0] for e in total], label=run.replace("_", " "))
ax.set_xlabel("t (ms)")
ax.set_ylabel("energy / initial energy")
ax.set_title("beam kinetic + strain energy + droplet kinetic energy", fontsize=9)
ax.legend()
fig.tight_layout()
fig.savefig(out / "energy.png", dpi=120)

if "with_fracture" in runs:
    fails = rows(out / "with_fracture" / "failures.csv")
    fig, ax = plt.subplots(figsize=(10, 2.2))
    ax.add_patch(plt.Rectangle((0, 0), 0.5, 0.05, fill=False, lw=0.8))
    sc = ax.scatter([float(p["x0"]) for p in fails], [float(p["y0"]) for p in fails],
                    c=[1e3 * float(p["t"]) for p in fails], s=4, cmap="viridis")
    fig.colorbar(sc, ax=ax, label="failure time (ms)")
    ax.set_aspect("equal")
    ax.set_xlabel("x (m), initial position")
    ax.set_title("crack paths: particle failures (clamp at x = 0, impact over x = 0.4-0.5 m)", fontsize=9)
    fig.tight_layout()
    fig.savefig(out / "crack_path.png", dpi=130)
print(f"wrote PNGs to {out}")
