#!/usr/bin/python3
"""NTHMP benchmark problem 4: the laboratory solitary wave on a 1:19.85 beach (Synolakis 1987).

Two measures, each against the Caltech tank's data in data/nthmp-bp4/:

  profiles   the surface along the channel at t/T = 30, 40, ..., 70 of a run of
             cases/nthmp-bp4 (H/d = 0.0185), or at t/T = 15, 20, 25, 30 of a run of its
             breaking.json (H/d = 0.3), against the tank's profiles: RMS difference over H at
             each time, where both are wet, and a plot; and the run-up against the tank's
             runs within 10 % of the wave's H/d.
  sweep      the maximum run-up over a range of H/d (the non-breaking waves, H/d < 0.045): for
             each height the shipped scene is written with that wave (its crest at X0 + L,
             as the problem places it), run by swe-mps, and its run-up measured as
             tools/nthmp_bp1.py measures it (the highest ground under a map cell ever wetter
             than the scene's 1 mm), against the tank's run-ups and the run-up law
             R/d = 2.831 sqrt(cot beta) (H/d)^(5/4).

    /usr/bin/python3 tools/nthmp_bp4.py profiles cases/nthmp-bp4/nthmp-bp4.nc [--plot P.png]
    /usr/bin/python3 tools/nthmp_bp4.py profiles cases/nthmp-bp4/nthmp-bp4-breaking.nc
    /usr/bin/python3 tools/nthmp_bp4.py sweep WORK_FOLDER [--heights 0.005 0.01 ...]
        [--spacing 0.05] [--threads 2] [--plot P.png]

The sweep's maps are on cells of half the particle spacing, which set the run-up's resolution.
"""
import argparse
import json
import math
import pathlib
import subprocess
import sys

import numpy as np
from netCDF4 import Dataset

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent
DATA = ROOT / "data" / "nthmp-bp4"
SCENE = ROOT / "cases" / "nthmp-bp4" / "scenario.json"
COT_BETA = 19.85
BREAKING = 0.045


def runup_law(h_over_d):
    return 2.831 * math.sqrt(COT_BETA) * h_over_d ** 1.25


def runup(result):
    """The highest bed elevation under a map cell whose maximum depth exceeded 1 mm."""
    d = Dataset(result)
    bed = d["bed_elevation"][:, :].filled(np.nan)
    wet = d["max_depth"][:, :].filled(0.0) > 0.001
    return float(np.max(bed[wet]))


def lab_runups():
    rows = [line.split() for line in (DATA / "Lab_runup.txt").read_text().splitlines()
            if line.strip() and not line.startswith("#")]
    return np.array([[float(r[0]), float(r[1])] for r in rows])


def profiles(args):
    d = Dataset(args.result)
    tau = math.sqrt(1.0 / 9.81)
    x = d["x"][:]
    y = d["y"][:]
    row = int(np.argmin(np.abs(y - 0.5 * (y[0] + y[-1]))))
    times = d["time"][:] / tau
    height = json.loads(d.getncattr("scenario"))["water"][0]["solitary_wave"]["height"]
    # The tank's profiles: the non-breaking wave at t/T = 30 ... 70, the breaking one at 15 ... 30.
    breaking = height > BREAKING
    label = "0.3" if breaking else "0.0185"
    panels = []
    for t in (15, 20, 25, 30) if breaking else (30, 40, 50, 60, 70):
        lab = np.loadtxt(DATA / f"profile_H{label}_t{t}.txt")
        m = int(np.argmin(np.abs(times - t)))
        if abs(times[m] - t) > 0.05:
            print(f"no output at t/T = {t}", file=sys.stderr)
            return 1
        surface = d["surface_elevation"][m, row, :].filled(np.nan)
        model = np.interp(lab[:, 0], x, surface, left=np.nan, right=np.nan)
        both = np.isfinite(model) & np.isfinite(lab[:, 1])
        rms = math.sqrt(np.mean((model[both] - lab[both, 1]) ** 2)) / height
        print(f"profile t/T = {t}: RMS {100 * rms:.1f} % of H over {both.sum()} lab points")
        panels.append((t, lab, surface))
    r = runup(args.result)
    # The run-up law is the non-breaking waves' (Synolakis 1987).
    law = "" if breaking else f" (law {runup_law(height):.4f})"
    print(f"maximum run-up R/d = {r:.4f}{law}")
    tank = lab_runups()
    near = tank[np.abs(tank[:, 0] - height) <= 0.1 * height]
    if len(near):
        mean = near[:, 1].mean()
        print(f"tank: {len(near)} runs at H/d {near[:, 0].min():g}-{near[:, 0].max():g}, mean R/d "
              f"{mean:.4f}: {100 * (r / mean - 1):+.1f} %")
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, axes = plt.subplots(len(panels), 1, figsize=(8, 2.0 * len(panels)), sharex=True)
        for ax, (t, lab, surface) in zip(axes, panels):
            ax.plot(x, surface, lw=1.2, label="swe-mps")
            ax.plot(lab[:, 0], lab[:, 1], "o", ms=3, color="k", label="tank")
            ax.set_xlim(-12 if breaking else -3, 20)
            ax.set_ylim(-0.1, 0.7) if breaking else ax.set_ylim(-0.03, 0.1)
            ax.set_ylabel("surface / d")
            ax.text(0.98, 0.85, f"t/T = {t}", transform=ax.transAxes, ha="right")
        axes[0].legend(fontsize=7, loc="upper center")
        axes[-1].set_xlabel("x / d")
        fig.suptitle(f"NTHMP BP4, H/d = {height:g}: surface profiles against the tank")
        fig.tight_layout()
        fig.savefig(args.plot, dpi=110)
    return 0


def sweep(args):
    work = pathlib.Path(args.work)
    work.mkdir(parents=True, exist_ok=True)
    base = json.loads(SCENE.read_text())
    cli = ROOT / "build" / "swe-mps"
    results = []
    for h in args.heights:
        scene = json.loads(json.dumps(base))
        half_length = math.acosh(math.sqrt(20.0)) / math.sqrt(3.0 * h / 4.0)
        scene["name"] = f"bp4-H{h:g}"
        wave = scene["water"][0]["solitary_wave"]
        wave["height"] = h
        wave["crest"][0] = COT_BETA + half_length
        scene["water"][0]["spacing"] = args.spacing
        scene["output"]["grid"]["spacing"] = args.spacing / 2.0
        scene["output"]["path"] = f"bp4-H{h:g}.nc"
        scene["output"].pop("times", None)
        path = work / f"bp4-H{h:g}.json"
        path.write_text(json.dumps(scene, indent=2))
        run = subprocess.run([str(cli), "run", str(path), "--threads", str(args.threads), "-q"],
                             capture_output=True, text=True)
        if run.returncode != 0:
            print(run.stdout + run.stderr, file=sys.stderr)
            return 1
        r = runup(work / f"bp4-H{h:g}.nc")
        results.append((h, r))
        print(f"H/d {h:.4f}: R/d {r:.4f}, law {runup_law(h):.4f} ({100 * (r / runup_law(h) - 1):+.1f} %)",
              flush=True)
    lab = lab_runups()
    nonbreaking = lab[lab[:, 0] < BREAKING]
    # The tank's run-ups scatter: compare with a power law fitted to them, R/d = a (H/d)^b.
    b, log_a = np.polyfit(np.log(nonbreaking[:, 0]), np.log(nonbreaking[:, 1]), 1)
    print(f"tank, non-breaking (H/d < {BREAKING}): {len(nonbreaking)} runs, fit R/d = "
          f"{math.exp(log_a):.3f} (H/d)^{b:.3f}")
    for h, r in results:
        fit = math.exp(log_a) * h ** b
        print(f"H/d {h:.4f}: swe-mps {r:.4f}, tank fit {fit:.4f} ({100 * (r / fit - 1):+.1f} %), "
              f"law {runup_law(h):.4f} ({100 * (r / runup_law(h) - 1):+.1f} %)")
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 4.2))
        ax.loglog(lab[:, 0], lab[:, 1], "o", ms=4, mfc="none", color="k", label="tank (Synolakis 1987)")
        hh = np.logspace(np.log10(0.004), np.log10(0.08), 50)
        ax.loglog(hh, [runup_law(v) for v in hh], "--", color="0.4", label="run-up law")
        ax.loglog([h for h, _ in results], [r for _, r in results], "s", color="C0", label="swe-mps")
        ax.axvline(BREAKING, color="0.7", lw=0.8)
        ax.set_xlabel("H / d")
        ax.set_ylabel("R / d")
        ax.legend(fontsize=8)
        ax.set_title("NTHMP BP4: maximum run-up on a 1:19.85 beach")
        fig.tight_layout()
        fig.savefig(args.plot, dpi=110)
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("profiles")
    p.add_argument("result", type=pathlib.Path)
    p.add_argument("--plot", type=pathlib.Path)
    s = sub.add_parser("sweep")
    s.add_argument("work")
    s.add_argument("--heights", type=float, nargs="+", default=[0.005, 0.01, 0.0185, 0.03, 0.04])
    s.add_argument("--spacing", type=float, default=0.05)
    s.add_argument("--threads", type=int, default=2)
    s.add_argument("--plot", type=pathlib.Path)
    args = parser.parse_args()
    return profiles(args) if args.command == "profiles" else sweep(args)


if __name__ == "__main__":
    sys.exit(main())
