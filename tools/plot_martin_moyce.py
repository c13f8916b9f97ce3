#!/usr/bin/python3
"""Plot the Martin & Moyce (1952) column-collapse runs of docs/ns-dam-break.md.

Reads the CSV files that `swemps-ns-dam-break` writes (--output NAME.csv and
--steps-output NAME-steps.csv, named as in the doc's run list) from one folder and draws

  mm_front_2d.png          surge front Z = z/a against T = t sqrt(2g/a), 2D kernels, with the data
  mm_front_3d.png          the same in 3D
  mm_front_refinement.png  the 2D standard kernel at a/l0 = 20, 40, 80, 160
  mm_floor_pressure.png    the floor probe p/(rho g a) at every step, its moving average and
                           the hydrostatic pressure of the depth above it, one panel per run

Runs that are missing are left out (with a note). With --tables it prints instead the doc's
markdown tables: cost and accuracy from the summary line at the end of each samples file, and
the front's signed error at each measured point for a few runs. Only
matplotlib and the csv module.

    /usr/bin/python3 tools/plot_martin_moyce.py --runs build/martin-moyce --out docs/img
    /usr/bin/python3 tools/plot_martin_moyce.py --runs build/martin-moyce --tables
"""
import argparse
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# (file stem, legend label); the stems are the run names of docs/ns-dam-break.md.
FRONT_2D = [
    ("2d-standard-2.1", "standard, 2.1 l0"),
    ("2d-sheu-quartic-2.0", "Sheu quartic, 2.0 l0"),
    ("2d-sheu-quartic-2.1", "Sheu quartic, 2.1 l0"),
    ("2d-logarithmic-2.1", "logarithmic, 2.1 l0"),
    ("2d-hyperbolic-3.1", "hyperbolic 4/2, 3.1 l0"),
    ("2d-hyperbolic-4.0", "hyperbolic 4/2, 4.0 l0"),
    ("2d-hyperbolic-4.0-mixed-0.97", "hyperbolic 4/2, 4.0 l0, mixed source"),
]
FRONT_3D = [
    ("3d-standard-2.1", "standard, 2.1 l0, a/l0 = 20"),
    ("3d-sheu-quartic-2.1", "Sheu quartic, 2.1 l0, a/l0 = 20"),
    ("3d-logarithmic-2.1", "logarithmic, 2.1 l0, a/l0 = 20"),
    ("3d-hyperbolic-3.1", "hyperbolic 4/2, 3.1 l0, a/l0 = 20"),
    ("3d-hyperbolic-4.0", "hyperbolic 4/2, 4.0 l0, a/l0 = 20"),
    ("3d-standard-2.1-r30", "standard, 2.1 l0, a/l0 = 30"),
    ("3d-sheu-quartic-2.1-r30", "Sheu quartic, 2.1 l0, a/l0 = 30"),
    ("3d-hyperbolic-3.1-r30", "hyperbolic 4/2, 3.1 l0, a/l0 = 30"),
]
REFINEMENT = [
    ("2d-standard-2.1-r20", "a/l0 = 20"),
    ("2d-standard-2.1", "a/l0 = 40"),
    ("2d-standard-2.1-r80", "a/l0 = 80"),
    ("2d-standard-2.1-r160", "a/l0 = 160"),
]
PRESSURE = [
    ("2d-standard-2.1", "2D standard, 2.1 l0"),
    ("2d-sheu-quartic-2.0", "2D Sheu quartic, 2.0 l0"),
    ("2d-logarithmic-2.1", "2D logarithmic, 2.1 l0"),
    ("2d-hyperbolic-4.0", "2D hyperbolic 4/2, 4.0 l0"),
    ("2d-standard-4.0", "2D standard, 4.0 l0"),
    ("2d-standard-2.1-mixed-0.97", "2D standard, 2.1 l0, mixed source"),
    ("2d-hyperbolic-4.0-mixed-0.97", "2D hyperbolic 4/2, 4.0 l0, mixed source"),
    ("3d-standard-2.1", "3D standard, 2.1 l0"),
    ("3d-hyperbolic-4.0", "3D hyperbolic 4/2, 4.0 l0"),
]
NOISE_WINDOW = (0.5, 3.0)  # where the summary's noise is measured
# Runs whose front is compared point by point with the data in the third table.
POINTWISE = [
    ("2d-standard-2.1", "2D standard 2.1, 40"),
    ("2d-standard-2.1-r160", "2D standard 2.1, 160"),
    ("2d-hyperbolic-4.0-mixed-0.97", "2D hyperbolic 4.0, mixed, 40"),
    ("3d-standard-2.1", "3D standard 2.1, 20"),
    ("3d-sheu-quartic-2.1-r30", "3D Sheu 2.1, 30"),
]
# Every run of the doc, in the order of its tables.
ALL_RUNS = [
    "2d-standard-2.1", "2d-sheu-quartic-2.0", "2d-sheu-quartic-2.1", "2d-logarithmic-2.1",
    "2d-hyperbolic-2.1", "2d-hyperbolic-3.1", "2d-hyperbolic-4.0", "2d-standard-3.1",
    "2d-standard-4.0", "2d-logarithmic-4.0", "2d-standard-2.1-mixed-0.97",
    "2d-standard-2.1-mixed-0.5", "2d-hyperbolic-4.0-mixed-0.97", "2d-hyperbolic-4.0-mixed-0.5",
    "2d-standard-2.1-no-collision", "2d-standard-2.1-r20", "2d-standard-2.1-r80",
    "2d-standard-2.1-r160", "3d-standard-2.1", "3d-sheu-quartic-2.1", "3d-logarithmic-2.1",
    "3d-hyperbolic-3.1", "3d-hyperbolic-4.0", "3d-standard-2.1-mixed-0.97",
    "3d-standard-2.1-r30", "3d-sheu-quartic-2.1-r30", "3d-hyperbolic-3.1-r30",
]


def read_rows(path):
    """Rows of a CSV whose comment lines start with '#', as dicts of floats."""
    with open(path, newline="") as f:
        lines = [line for line in f if not line.startswith("#")]
    return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(lines)]


def summary_of(path):
    """The key=value pairs of the summary line at the end of a samples file, and the
    breakdown message if the run failed."""
    with open(path) as f:
        for line in f:
            if line.startswith("# summary:"):
                text, _, failure = line[len("# summary:"):].partition(" FAILED: ")
                pairs = dict(item.rsplit("=", 1) for item in text.split() if "=" in item)
                return pairs, failure.strip()
    return None, ""


def resolution_of(path):
    """a/l0 from the summary line at the end of a samples file."""
    pairs, _ = summary_of(path)
    return int(pairs["resolution"]) if pairs else None


def load(folder, stem, suffix=""):
    path = os.path.join(folder, stem + suffix + ".csv")
    if not os.path.exists(path):
        print(f"note: {path} not found, left out", file=sys.stderr)
        return None
    return read_rows(path)


def plot_fronts(folder, runs, data, title, output):
    fig, ax = plt.subplots(figsize=(7.5, 5))
    ax.plot([p["T"] for p in data], [p["Z"] for p in data], "ko", ms=6, mfc="none",
            label="Martin & Moyce (1952)", zorder=5)
    for stem, label in runs:
        rows = load(folder, stem)
        if rows is None:
            continue
        rows = [r for r in rows if math.isfinite(r["Z"])]
        ax.plot([r["T"] for r in rows], [r["Z"] for r in rows], lw=1.3, label=label)
    ax.set_xlabel("T = t sqrt(2g/a)")
    ax.set_ylabel("Z = z/a")
    ax.set_xlim(0, 3.3)
    ax.set_ylim(1, 4.2)
    ax.grid(alpha=0.3)
    ax.set_title(title)
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig(output, dpi=120)
    plt.close(fig)
    print(f"wrote {output}")


def plot_pressure(folder, runs, output):
    present = [(stem, label, load(folder, stem, "-steps")) for stem, label in runs]
    present = [(stem, label, rows) for stem, label, rows in present if rows is not None]
    if not present:
        return
    columns = 2
    rows_of_panels = (len(present) + columns - 1) // columns
    fig, axes = plt.subplots(rows_of_panels, columns, figsize=(12, 2.0 * rows_of_panels),
                             sharex=True, sharey=True, squeeze=False)
    panels = [ax for row in axes for ax in row]
    for ax in panels[len(present):]:
        ax.set_visible(False)
    for ax, (stem, label, rows) in zip(panels, present):
        samples = os.path.join(folder, stem + ".csv")
        half_spacing = 0.5 / (resolution_of(samples) or 40)
        rows = [r for r in rows if math.isfinite(r["p_floor"])]
        T = [r["T"] for r in rows]
        ax.plot(T, [r["p_floor"] for r in rows], lw=0.4, color="tab:blue", label="every step")
        ax.plot(T, [r["p_floor_average"] for r in rows], lw=1.5, color="tab:orange",
                label="moving average (T +- 0.1)")
        ax.plot(T, [r["h_floor"] + half_spacing for r in rows], "k--", lw=1,
                label="hydrostatic, depth above")
        ax.axvspan(*NOISE_WINDOW, color="0.93", zorder=0)
        ax.set_ylim(-0.2, 3.0)
        ax.set_xlim(0, 3.2)
        ax.text(0.99, 0.92, label, transform=ax.transAxes, ha="right", va="top", fontsize=9,
                bbox={"facecolor": "white", "edgecolor": "none", "alpha": 0.8})
        ax.grid(alpha=0.3)
    for row in axes:
        row[0].set_ylabel("p / (rho g a)")
    for ax in panels[max(0, len(present) - columns):len(present)]:
        ax.set_xlabel("T = t sqrt(2g/a)")
        ax.tick_params(labelbottom=True)
    panels[0].legend(fontsize=7, loc="upper left")
    fig.suptitle("Floor probe at x = a/2 (shaded: where the noise is measured; values above 3 "
                 "are cut off)", fontsize=11)
    fig.tight_layout()
    fig.savefig(output, dpi=80)
    plt.close(fig)
    print(f"wrote {output}")


def setup_label(s):
    """Dimension, kernels, source and resolution of a run, from its summary."""
    def kernel(text):
        name, support, *kappa = text.split("/")
        return f"{name} {float(support):.1f}" + (f" k{kappa[0][5:]}" if kappa else "")
    label = f"{s['dim']}D {kernel(s['pressure_kernel'])}"
    if s["velocity_kernel"] != s["pressure_kernel"]:
        label += f" / {kernel(s['velocity_kernel'])}"
    if s["source"] == "mixed":
        label += f", mixed beta {s['beta']}"
    elif float(s["beta"]) != 0.97:
        label += f", beta {s['beta']}"
    if s["collision"] == "off":
        label += ", no collision"
    return label + f", a/l0 {s['resolution']}"


def front_at(rows, T):
    """The run's Z at T, linear between the steps around it (as the summary's error)."""
    for lo, hi in zip(rows, rows[1:]):
        if lo["T"] < T <= hi["T"]:
            return lo["Z"] + (hi["Z"] - lo["Z"]) * (T - lo["T"]) / (hi["T"] - lo["T"])
    return float("nan")


def early_means(rows, until=0.2):
    """Mean floor and wall probe pressure over the steps with T <= until."""
    rows = [r for r in rows if r["T"] <= until and math.isfinite(r["p_floor"])]
    if not rows:
        return float("nan"), float("nan")
    return (sum(r["p_floor"] for r in rows) / len(rows),
            sum(r["p_wall"] for r in rows) / len(rows))


def released_pressure(terms=200):
    """p / (rho g a) at the floor probe (x = a/2, z = 0) and the wall probe (x = 0, z = a/5)
    the instant the column is released, from rest: p solves Laplace's equation in the
    column with p = 0 on the top and on the open side, dp/dn = rho g n_z on the floor and
    dp/dx = 0 on the wall. Written as hydrostatic plus a cosine series in z,
    p = (1 - z) - sum_n (2 / k_n^2) cosh(k_n x) cos(k_n z) / cosh(k_n), k_n = (n + 1/2) pi,
    with a = 1."""
    k = [(n + 0.5) * math.pi for n in range(terms)]
    floor = 1.0 - sum(2.0 / kn ** 2 * math.cosh(0.5 * kn) / math.cosh(kn) for kn in k)
    wall = 0.8 - sum(2.0 / kn ** 2 * math.cos(0.2 * kn) / math.cosh(kn) for kn in k)
    return floor, wall


def print_tables(folder, data):
    runs, stems = [], []
    for stem in ALL_RUNS:
        path = os.path.join(folder, stem + ".csv")
        if os.path.exists(path):
            pairs, failure = summary_of(path)
            runs.append((pairs, failure))
            stems.append(stem)
        else:
            print(f"note: {path} not found, left out", file=sys.stderr)

    def num(text, digits):
        value = float(text)
        return "–" if math.isnan(value) else f"{value:.{digits}f}"

    print("| run | fluid / wall / dummy | steps | Poisson iterations mean / max | lost | "
          "CPU time (s) | wall time (s) |")
    print("|---|---|---|---|---|---|---|")
    for s, failure in runs:
        steps = s["steps"] + (f" (broke down at T = {float(s['reached_T']):.3f})"
                              if failure else "")
        print(f"| {setup_label(s)} | {s['fluid']} / {s['wall']} / {s['dummy']} | {steps} | "
              f"{num(s['poisson_mean'], 1)} / {s['poisson_max']} | {s['lost']} | "
              f"{num(s.get('cpu_time_s', 'nan'), 1)} | {num(s['wall_time_s'], 1)} |")
    print()
    print("| run | mean / max abs(Z error), all points | mean / max abs(Z error), T >= 1 | "
          "floor noise | wall noise | floor / wall p, mean over T <= 0.2 | "
          "floor p / hydrostatic, T 0.5-3 |")
    print("|---|---|---|---|---|---|---|")
    for (s, failure), stem in zip(runs, stems):
        if failure:
            print(f"| {setup_label(s)} | – | – | – | – | – | – |")
            continue
        floor, wall = early_means(load(folder, stem, "-steps") or [])
        print(f"| {setup_label(s)} | {num(s['Z_err_mean'], 3)} / {num(s['Z_err_max'], 3)} | "
              f"{num(s['Z_err_mean_T>=1'], 3)} / {num(s['Z_err_max_T>=1'], 3)} | "
              f"{num(s['floor_noise'], 3)} | {num(s['wall_noise'], 3)} | "
              f"{floor:.3f} / {wall:.3f} | {num(s['floor_over_hydrostatic_late'], 2)} |")
    floor, wall = released_pressure()
    print(f"\nPressure of potential flow just after release: floor probe {floor:.3f}, "
          f"wall probe {wall:.3f} (rho g a, at the floor and wall planes).")
    print()
    present = [(label, load(folder, stem, "-steps")) for stem, label in POINTWISE]
    present = [(label, rows) for label, rows in present if rows is not None]
    print("| T | Z measured | " + " | ".join(label for label, _ in present) + " |")
    print("|---|---|" + "---|" * len(present))
    for point in data:
        errors = [front_at(rows, point["T"]) - point["Z"] for _, rows in present]
        print(f"| {point['T']:.2f} | {point['Z']:.2f} | " +
              " | ".join(f"{e:+.3f}" for e in errors) + " |")


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", default="build/martin-moyce", help="folder of the run CSV files")
    ap.add_argument("--data", default="data/martin_moyce_1952_square_column.csv")
    ap.add_argument("--out", default="docs/img", help="folder for the PNG files")
    ap.add_argument("--tables", action="store_true", help="print the markdown tables instead")
    args = ap.parse_args()
    data = read_rows(args.data)
    if args.tables:
        print_tables(args.runs, data)
        return
    os.makedirs(args.out, exist_ok=True)
    plot_fronts(args.runs, FRONT_2D, data, "2D, a/l0 = 40: kernels",
                os.path.join(args.out, "mm_front_2d.png"))
    plot_fronts(args.runs, FRONT_3D, data, "3D channel: kernels",
                os.path.join(args.out, "mm_front_3d.png"))
    plot_fronts(args.runs, REFINEMENT, data, "2D, standard kernel at 2.1 l0: refinement",
                os.path.join(args.out, "mm_front_refinement.png"))
    plot_pressure(args.runs, PRESSURE, os.path.join(args.out, "mm_floor_pressure.png"))


if __name__ == "__main__":
    main()
