#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Plots the floating ice beam: the deflection against Hetenyi's semi-infinite beam, the end load
against the end deflection, where the particles failed and, for the beam in water, snapshots of
the ice and the water before the first failure and at the end (from the VTU files).

usage: python3 examples/floating_ice_beam/plot.py [output dir]   (default out/floating_ice_beam)
"""
import csv
import re
import sys
from array import array
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
water = float(summary["water"]) > 0
P_profile = float(summary["profile_load"])

# The settled deflection at P_f / 2 against Hetenyi's w(x) = (2 P lambda / k) e^(-lambda x) cos(lambda x).
rows = read("deflection.csv")
x = [float(r["x"]) for r in rows]
fig, ax = plt.subplots(figsize=(8, 4))
ax.plot(x, [1e3 * float(r["hetenyi_w"]) for r in rows], "k-", lw=1, label="Hetényi, semi-infinite beam")
ax.plot(x, [1e3 * float(r["w"]) for r in rows], "o", ms=2.5,
        label="mpsfsi (column means from the shape at the load's start, plus the open water's rise)" if water
        else "mpsfsi (column means)")
ax.axvline(3 / lam, color="0.7", lw=0.8)
ax.text(3 / lam, ax.get_ylim()[1], " 3/λ", va="top", color="0.4")
ax.invert_yaxis()
ax.set_xlabel("x from the loaded end (m)")
ax.set_ylabel("deflection, down (mm)")
ax.set_title(f"{'In water' if water else 'On springs'}, P = {P_profile:.1f} N/m = {P_profile / Pf:.2f} P_f: "
             f"end {100 * float(summary['end_error']):+.2f} %, profile RMS {100 * float(summary['profile_rms']):.2f} %",
             fontsize=10)
ax.legend()
fig.tight_layout()
fig.savefig(out / "deflection.png", dpi=120)
print(f"wrote {out / 'deflection.png'}")

# End load against end deflection; Hetenyi's line is the settled response. In water the rows
# before the load starts measure the unloaded beam's settling, not the load's response.
rows = read("history.csv")
rows = rows[next((k for k, r in enumerate(rows) if float(r["P"]) > 0), 0):]
fig, ax = plt.subplots(figsize=(6, 4.5))
ax.plot([1e3 * float(r["end_deflection"]) for r in rows], [float(r["P"]) for r in rows], lw=1, label="mpsfsi")
ax.plot([1e3 * float(r["hetenyi_end_deflection"]) for r in rows], [float(r["P"]) for r in rows], "k--", lw=0.8,
        label="Hetényi, 2 P λ / k, less the open water's rise" if water else "Hetényi, 2 P λ / k")
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


def read_vtu(path, names):
    """The points' x, y, z and the named point arrays of one of the library's VTU files (raw
    appended data, each array preceded by its length in bytes as a UInt64)."""
    data = path.read_bytes()
    start = data.index(b"<AppendedData")
    start = data.index(b"_", start) + 1
    typecode = {"Float64": "d", "Int32": "i", "Int64": "q", "UInt8": "B"}
    arrays = {}
    for m in re.finditer(rb'<DataArray type="(\w+)" Name="(\w+)" NumberOfComponents="(\d+)" format="appended" '
                         rb'offset="(\d+)"', data[:start]):
        kind, name, offset = m.group(1).decode(), m.group(2).decode(), int(m.group(4))
        if name not in names + ["Points"]:
            continue
        size = int.from_bytes(data[start + offset:start + offset + 8], "little")
        values = array(typecode[kind])
        values.frombytes(data[start + offset + 8:start + offset + 8 + size])
        arrays[name] = values
    points = arrays.pop("Points")
    return points[0::3], points[1::3], points[2::3], arrays


def frames(name):
    """(time, file) of every snapshot listed in name.pvd."""
    text = (out / f"{name}.pvd").read_text()
    return [(float(t), f) for t, f in re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', text)]


# The beam in water: the loaded end's first 2 m at two instants, the water coloured by its
# pressure, the ice by its largest principal stress over its strength sigma_f; y stretched. A 3D
# strip is shown by its particles within half a spacing of the channel's mid-plane.
if water and (out / "ice.pvd").exists():
    ice_frames, water_frames = frames("ice"), frames("water")
    failed = (out / "failures.csv").exists()
    t_first = float(read("failures.csv")[0]["t"]) if failed else float("inf")
    before = max(k for k, (t, _) in enumerate(ice_frames) if t < t_first)
    shown = [before] + ([len(ice_frames) - 1] if failed else [])
    h, l0 = float(summary["thickness"]), float(summary["l0"])
    size = (250 * l0) ** 2  # a marker about a spacing wide along x
    fig, axes = plt.subplots(len(shown), 1, figsize=(10, 3.2 * len(shown)), squeeze=False)
    for ax, k in zip(axes[:, 0], shown):
        t = ice_frames[k][0]
        wx, wy, wz, w = read_vtu(out / water_frames[k][1], ["pressure", "kind"])
        ix, iy, iz, ice = read_vtu(out / ice_frames[k][1], ["max_principal_stress", "strength"])
        mid = 0.5 * (min(iz) + max(iz))

        def in_slice(z):
            return abs(z - mid) <= 0.5 * l0 * (1 + 1e-6)

        bottom, top = min(iy) - 2 * h, max(iy) + 1.5 * l0
        keep = [i for i in range(len(wx))
                if w["kind"][i] == 0 and wx[i] < 2.0 and wy[i] > bottom and in_slice(wz[i])]
        sc = ax.scatter([wx[i] for i in keep], [wy[i] for i in keep], c=[w["pressure"][i] / 1e3 for i in keep],
                        s=size, cmap="viridis", marker="s", linewidths=0)
        fig.colorbar(sc, ax=ax, label="water p (kPa)", pad=0.01)
        ice_keep = [i for i in range(len(ix)) if ix[i] < 2.0 and in_slice(iz[i])]
        si = ax.scatter([ix[i] for i in ice_keep], [iy[i] for i in ice_keep],
                        c=[ice["max_principal_stress"][i] / ice["strength"][i] for i in ice_keep], cmap="coolwarm",
                        vmin=-1, vmax=1, s=size, marker="s", linewidths=0)
        fig.colorbar(si, ax=ax, label="ice σ1 / σ_f", pad=0.01)
        ax.axvline(x_f, color="r", lw=0.6)
        ax.set_xlim(0, 2.0)
        ax.set_ylim(bottom, top)
        ax.set_ylabel("y (m)")
        ax.set_title(f"t = {t:.2f} s" + (" (before the first failure)" if k == before and failed else ""), fontsize=9)
    axes[-1, 0].set_xlabel("x from the loaded end (m); red: π/(4λ)")
    fig.tight_layout()
    fig.savefig(out / "snapshots.png", dpi=120)
    print(f"wrote {out / 'snapshots.png'}")
