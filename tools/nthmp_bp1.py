#!/usr/bin/python3
"""Score a run of cases/nthmp-bp1 against NTHMP benchmark problem 1's analytic solution.

Benchmark problem 1 (Synolakis 1987; NTHMP 2011 workshop set): a solitary wave, H/d = 0.019,
climbs a 1:19.85 beach. The scene is the problem at d = 1 m, so metres are depths and the time
unit is tau = sqrt(d/g). The analytic profiles and gauge series are
data/nthmp-bp1/canonical_profiles.txt and canonical_ts.txt (x/d seaward from the initial
shoreline, as in the scene).

What is measured, as the NTHMP standards (Synolakis et al. 2007) ask:
- maximum run-up R: the highest bed elevation under a map cell whose maximum depth over the
  run exceeded the scene's wet depth, against the run-up law R/d = 2.831 sqrt(cot beta)
  (H/d)^(5/4) and against the highest wet point of the analytic profiles;
- at each gauge (x/d = 0.25 and 9.95): the maximum wave height's error, and the normalised
  RMS difference of the series over the analytic series' times, RMS(model - exact) / max|exact|,
  where the analytic solution is wet;
- the profiles along the channel's centre at t/tau = 35 ... 70: RMS difference over H.

    /usr/bin/python3 tools/nthmp_bp1.py cases/nthmp-bp1/nthmp-bp1.nc [--plot docs/img/nthmp-bp1.png]

Prints one line per measure and a last line "nthmp-bp1: ... PASS|FAIL" (run-up within 5 % of
the law, the NTHMP allowable error for analytic problems).
"""
import argparse
import math
import pathlib
import sys

import numpy as np
from netCDF4 import Dataset

HERE = pathlib.Path(__file__).resolve().parent
DATA = HERE.parent / "data" / "nthmp-bp1"
H_OVER_D = 0.019
COT_BETA = 19.85
ALLOWED_RUNUP_ERROR = 0.05


def runup_law():
    return 2.831 * math.sqrt(COT_BETA) * H_OVER_D ** 1.25


def read_table(path, skip):
    rows = []
    for line in path.read_text().splitlines()[skip:]:
        fields = line.split()
        if not fields:
            continue
        rows.append([float("nan") if f.lower() == "nan" else float(f) for f in fields])
    return rows


def canonical_profiles():
    lines = (DATA / "canonical_profiles.txt").read_text().splitlines()
    header = next(i for i, l in enumerate(lines) if l.startswith("x/d"))
    times = [float(w.split("=")[1]) for w in lines[header].split() if w.startswith("t/tau=")]
    rows = np.array(read_table(DATA / "canonical_profiles.txt", header + 1))
    return times, rows[:, 0], rows[:, 1:]


def canonical_series():
    lines = (DATA / "canonical_ts.txt").read_text().splitlines()
    header = next(i for i, l in enumerate(lines) if l.startswith("t/tau"))
    near, far = [], []
    for line in lines[header + 1:]:
        fields = line.split()
        if len(fields) >= 2:
            near.append((float(fields[0]), float(fields[1])))
        if len(fields) >= 4:
            far.append((float(fields[2]), float(fields[3])))
    return {"0.25": np.array(near), "9.95": np.array(far)}


def gauge_scores(times, level, exact):
    t_exact, z_exact = exact[:, 0], exact[:, 1]
    keep = np.isfinite(z_exact) & (t_exact <= times[-1])
    t_exact, z_exact = t_exact[keep], z_exact[keep]
    model = np.interp(t_exact, times, level)
    wet = np.isfinite(model)
    scale = np.max(np.abs(z_exact))
    nrms = math.sqrt(np.mean((model[wet] - z_exact[wet]) ** 2)) / scale
    height_error = (np.nanmax(level) - np.max(z_exact)) / np.max(z_exact)
    return height_error, nrms


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("result", type=pathlib.Path)
    parser.add_argument("--plot", type=pathlib.Path)
    args = parser.parse_args()
    d = Dataset(args.result)
    tau = math.sqrt(1.0 / 9.81)
    x = d["x"][:].filled(np.nan)
    y = d["y"][:].filled(np.nan)
    row = int(np.argmin(np.abs(y - 0.5 * (y[0] + y[-1]))))
    bed = d["bed_elevation"][row, :].filled(np.nan)
    wet_depth = float(getattr(d, "wet_depth_m", 0.001)) if hasattr(d, "wet_depth_m") else 0.001
    max_depth = d["max_depth"][:, :].filled(0.0)
    wet_any = (max_depth > wet_depth).any(axis=0)
    runup = float(np.max(bed[wet_any]))
    law = runup_law()
    times, xp, zp = canonical_profiles()
    exact_runup = max(float(-xp[np.isfinite(zp[:, k])].min() / COT_BETA) for k in range(len(times)))
    runup_error = (runup - law) / law
    print(f"maximum run-up R/d = {runup:.4f}: law {law:.4f} ({100 * runup_error:+.1f} %), "
          f"analytic profiles at least {exact_runup:.4f}")

    # Gauges.
    names = [str(n) for n in d["gauge_name"][:]]
    series_t = d["series_time"][:] / tau
    exact = canonical_series()
    scores = {}
    for k, name in enumerate(names):
        key = "0.25" if "0.25" in name else "9.95"
        level = d["gauge_surface_elevation"][:, k].filled(np.nan)
        scores[key] = gauge_scores(series_t, level, exact[key])
        print(f"gauge x/d = {key}: maximum wave height {100 * scores[key][0]:+.1f} %, "
              f"normalised RMS {100 * scores[key][1]:.1f} %")

    # Profiles along the centre row.
    out_t = d["time"][:] / tau
    profile_rms = {}
    for k, t in enumerate(times):
        m = int(np.argmin(np.abs(out_t - t)))
        if abs(out_t[m] - t) > 0.05:
            continue
        surface = d["surface_elevation"][m, row, :].filled(np.nan)
        model = np.interp(xp, x, surface)
        both = np.isfinite(model) & np.isfinite(zp[:, k])
        profile_rms[t] = math.sqrt(np.mean((model[both] - zp[both, k]) ** 2)) / H_OVER_D
    print("profiles, RMS / H: " + ", ".join(f"t = {t:g} tau {100 * v:.1f} %"
                                           for t, v in profile_rms.items()))

    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, axes = plt.subplots(1, 3, figsize=(15, 4.2))
        for k, t in enumerate(times):
            if t not in (40.0, 55.0, 70.0):
                continue
            m = int(np.argmin(np.abs(out_t - t)))
            surface = d["surface_elevation"][m, row, :].filled(np.nan)
            line, = axes[0].plot(x, surface, lw=1.2, label=f"swe-mps, t = {t:g} tau")
            axes[0].plot(xp, zp[:, k], "--", color=line.get_color(), lw=1,
                         label=f"analytic, t = {t:g} tau")
        axes[0].plot(x, bed, color="0.4", lw=0.8)
        axes[0].set_xlim(-3, 20)
        axes[0].set_ylim(-0.04, 0.11)
        axes[0].set_xlabel("x / d")
        axes[0].set_ylabel("surface / d")
        axes[0].legend(fontsize=7)
        for ax, (k, name) in zip(axes[1:], enumerate(names)):
            key = "0.25" if "0.25" in name else "9.95"
            level = d["gauge_surface_elevation"][:, k].filled(np.nan)
            ax.plot(series_t, level, lw=1.2, label="swe-mps")
            ax.plot(exact[key][:, 0], exact[key][:, 1], "--", lw=1, label="analytic")
            ax.set_xlim(0, series_t[-1])
            ax.set_xlabel("t / tau")
            ax.set_title(f"gauge x/d = {key}")
            ax.legend(fontsize=7)
        fig.suptitle(f"NTHMP BP1, H/d = 0.019: run-up R/d {runup:.4f} (law {law:.4f})")
        fig.tight_layout()
        fig.savefig(args.plot, dpi=110)

    ok = abs(runup_error) <= ALLOWED_RUNUP_ERROR
    print(f"nthmp-bp1: R/d {runup:.4f} ({100 * runup_error:+.1f} % of the law), gauges "
          + ", ".join(f"x/d {k}: height {100 * v[0]:+.1f} % NRMS {100 * v[1]:.1f} %"
                      for k, v in scores.items())
          + (" PASS" if ok else " FAIL"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
