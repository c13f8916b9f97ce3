#!/usr/bin/python3
"""Plot a `swe-mps compare` run: shallow water against 3D Navier-Stokes and Ritter.

Reads STEM.swe.nc, STEM.ns.nc and STEM.fronts.csv and writes into OUTDIR:

- compare_profiles.png: the depth along the channel's centre line at each output time
  after t = 0, both models and Ritter's dry-bed profile;
- compare_fronts.png: the front position against time, both models and Ritter (its
  zero-depth tip, and where its depth falls to the wet depth the shallow-water front is
  measured at).

    /usr/bin/python3 tools/plot_compare.py cases/dam-break-compare/dam-break-compare docs/img

The dam (x_dam) and its depth (h0) are read back from Ritter's column of the fronts table,
x_dam + 2 sqrt(g h0) t, so nothing about the scene needs repeating here.
"""
import argparse
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import netCDF4  # noqa: E402
import numpy as np  # noqa: E402


def ritter_depth(x, t, x_dam, h0, g):
    """Ritter's dry-bed dam break: h0 upstream of the rarefaction, the parabola
    (2 c0 - (x - x_dam)/t)^2 / (9 g) across it, dry beyond the front x_dam + 2 c0 t."""
    c0 = math.sqrt(g * h0)
    if t <= 0.0:
        return np.where(x <= x_dam, h0, 0.0)
    xi = (x - x_dam) / t
    fan = (2.0 * c0 - xi) ** 2 / (9.0 * g)
    return np.where(xi <= -c0, h0, np.where(xi >= 2.0 * c0, 0.0, fan))


def centre_line(path):
    """Output times, cell-centre x and the depth of the grid row(s) nearest the channel's
    centre line (the mean of the two middle rows when the rows are even in number)."""
    with netCDF4.Dataset(path) as ds:
        depth = np.ma.filled(ds["depth"][:], np.nan)
        ny = depth.shape[1]
        rows = [ny // 2] if ny % 2 else [ny // 2 - 1, ny // 2]
        return (np.asarray(ds["time"][:]), np.asarray(ds["x"][:]), depth[:, rows, :].mean(axis=1),
                float(ds.getncattr("gravity_m_s2")))


def dam_from_fronts(fronts, g):
    """x_dam and h0 from Ritter's front x_dam + 2 sqrt(g h0) t in the table."""
    t, x = fronts["time_s"], fronts["ritter_front_m"]
    speed = (x[-1] - x[0]) / (t[-1] - t[0])
    return float(x[0]), (speed / 2.0) ** 2 / g


def plot_profiles(swe, ns, x_dam, h0, g, path):
    t_swe, x_swe, h_swe, _ = swe
    t_ns, x_ns, h_ns, _ = ns
    times = [t for t in t_swe if t > 0.0]
    cols = 2
    rows = math.ceil(len(times) / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(11, 2.6 * rows), sharex=True, sharey=True, squeeze=False)
    c0 = math.sqrt(g * h0)
    x = np.linspace(min(x_swe[0], x_ns[0]), max(x_swe[-1], x_ns[-1]), 3000)
    for ax, t in zip(axes.flat, times):
        k_swe = int(np.argmin(np.abs(t_swe - t)))
        k_ns = int(np.argmin(np.abs(t_ns - t)))
        ax.plot(x_swe, h_swe[k_swe], "-", lw=1.4, color="tab:blue", label="shallow water (MPS)")
        ax.plot(x_ns, h_ns[k_ns], "-", lw=1.4, color="tab:red", label="Navier-Stokes 3D (MPS)")
        # Once the rarefaction has reached the back wall (t > x_dam / c0) the profile is no
        # longer Ritter's upstream; its front is unaffected.
        valid = t <= x_dam / c0
        ax.plot(x, ritter_depth(x, t, x_dam, h0, g), "k-" if valid else "k:", lw=1.2,
                label="Ritter" if valid else "Ritter (back wall reached)")
        ax.set_title(f"t = {t:.2f} s", fontsize=10)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="upper right")
    for ax in axes.flat[len(times):]:
        ax.set_visible(False)
    for ax in axes[-1]:
        ax.set_xlabel("x (m)")
    for ax in axes[:, 0]:
        ax.set_ylabel("depth on the centre line (m)")
    axes[0, 0].set_ylim(0.0, 1.15 * h0)
    fig.suptitle(f"Dam break: h0 = {h0:.3g} m, dam at x = {x_dam:.3g} m")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")


def wet_depth(path):
    """The wet depth the shallow-water front was measured at (the scene's output.wet_depth)."""
    with netCDF4.Dataset(path) as ds:
        return float(ds["max_depth"].getncattr("wet_depth_threshold_m"))


def plot_fronts(fronts, x_dam, h0, g, h_wet, path):
    t = fronts["time_s"]
    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.plot(t, fronts["swe_front_m"], "-", color="tab:blue", label=f"shallow water (MPS), depth > {h_wet:g} m")
    ax.plot(t, fronts["ns_front_m"], "-", color="tab:red", label="Navier-Stokes 3D (MPS)")
    ax.plot(t, fronts["ritter_front_m"], "k--", label=r"Ritter, $x_{dam} + 2\sqrt{g h_0}\,t$")
    # Where Ritter's depth falls to the wet depth: (2 c0 - 3 sqrt(g h_wet)) t past the dam. A
    # front measured at a finite depth is to be set against this line, not the zero-depth tip.
    if 0.0 < h_wet < h0:
        speed = 2.0 * math.sqrt(g * h0) - 3.0 * math.sqrt(g * h_wet)
        ax.plot(t, x_dam + speed * t, "k:", label=f"Ritter, where its depth is {h_wet:g} m")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("front position x (m)")
    ax.set_title(f"Surge front: h0 = {h0:.3g} m, dam at x = {x_dam:.3g} m")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("stem", help="the stem swe-mps compare wrote its files under")
    ap.add_argument("outdir", help="folder for the PNG files")
    args = ap.parse_args()
    swe = centre_line(args.stem + ".swe.nc")
    ns = centre_line(args.stem + ".ns.nc")
    g = swe[3]
    fronts = np.genfromtxt(args.stem + ".fronts.csv", delimiter=",", names=True)
    x_dam, h0 = dam_from_fronts(fronts, g)
    os.makedirs(args.outdir, exist_ok=True)
    plot_profiles(swe, ns, x_dam, h0, g, os.path.join(args.outdir, "compare_profiles.png"))
    plot_fronts(fronts, x_dam, h0, g, wet_depth(args.stem + ".swe.nc"),
                os.path.join(args.outdir, "compare_fronts.png"))


if __name__ == "__main__":
    main()
