#!/usr/bin/python3
"""Plot a `swe-mps study` table: accuracy against cost, and accuracy against spacing.

Reads the CSV table a study writes and draws one PNG with two panels:

- left: the error (fan L1 / h0 by default) against wall time, log-log. Each combination of
  the knobs other than spacing (splitting, scheme, gradient, kappa, dissipation, shifting,
  cfl and alpha_e, those that were swept) has its own colour and marker, with a line joining
  its spacings. The Pareto front
  (runs no other run beats on both wall time and error) is a dashed step line with its runs
  circled.
- right: the same error against particle spacing, log-log, with the observed order of
  convergence, log(e1/e2) / log(s1/s2), written beside each segment between neighbouring
  spacings.

Runs that broke down or failed have no error; they are listed on standard output.

    /usr/bin/python3 tools/plot_study.py cases/ritter-50m/ritter-50m-study.csv -o study.png
    /usr/bin/python3 tools/plot_study.py TABLE.csv -o study.png --error upstream_fan_l1

A table of a study against a reference map (max_depth_mad_m column) plots the mean absolute
difference of the maximum depth, in metres, by default; --mark adds another model's result
to the cost panel, such as a grid model's on the same reference:

    /usr/bin/python3 tools/plot_study.py cases/valley-flood/valley-flood-study.csv \
        -o valley-study.png --mark "FV1 82.6 m=2.5,0.40"
"""
import argparse
import csv
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# The knobs that, with the spacing, define a run; a series is one setting of all but spacing.
# Tables written before the scheme knobs have no scheme, kappa, dissipation or shifting
# column; a scheme's own knobs are empty in the other scheme's rows.
SERIES_KNOBS = ["splitting_threshold", "scheme", "gradient", "kappa", "dissipation", "shifting",
                "cfl", "alpha_e"]
MARKERS = ["o", "s", "^", "D", "v", "P", "X", "<", ">", "*"]


def number(text):
    """A table value as a float; "nan" and empty fields are NaN."""
    try:
        return float(text)
    except ValueError:
        return math.nan


def read_table(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def swept_knobs(rows):
    """The series knobs that take more than one value in the table: only they go in labels."""
    return [k for k in SERIES_KNOBS if len({r.get(k, "") for r in rows}) > 1]


def series_key(row):
    return tuple(row.get(k, "") for k in SERIES_KNOBS)


def series_label(row, knobs):
    parts = []
    for k in knobs:
        if not row.get(k, ""):
            continue  # a knob of the other scheme
        if k == "splitting_threshold":
            threshold = number(row[k])
            parts.append("no splitting" if math.isnan(threshold) else f"splitting {threshold:g}")
        elif k in ("scheme", "gradient"):
            parts.append(row[k])
        else:
            parts.append(f"{k} {row[k]}")
    return ", ".join(parts) or "runs"


def pareto_front(points):
    """(cost, error, ...) tuples no other point beats on both; cheapest first."""
    front = []
    for p in points:
        beaten = any(q[0] <= p[0] and q[1] <= p[1] and (q[0] < p[0] or q[1] < p[1])
                     for q in points)
        if not beaten:
            front.append(p)
    return sorted(front)


def observed_orders(spacings, errors):
    """The order between neighbouring spacings, log(e1/e2) / log(s1/s2)."""
    return [math.log(errors[k] / errors[k + 1]) / math.log(spacings[k] / spacings[k + 1])
            for k in range(len(spacings) - 1)]


def split_series(rows, error):
    """{series key: (label, [(spacing, wall_s, error)] sorted by spacing)} over finished runs."""
    knobs = swept_knobs(rows)
    series = {}
    for r in rows:
        if r["status"] != "ok" or not number(r[error]) > 0.0:
            continue
        key = series_key(r)
        label = series_label(r, knobs)
        series.setdefault(key, (label, []))[1].append(
            (number(r["spacing_m"]), number(r["wall_s"]), number(r[error])))
    for _, points in series.values():
        points.sort(reverse=True)  # coarse to fine
    return series


def error_label(error_name):
    """The error axis: fan errors are relative to h0, map differences in metres."""
    return f"{error_name} / h0" if "fan" in error_name else f"{error_name} (m)"


def finish_axes(ax, xlabel, error_name, title):
    """Log-log axes with labels, grid and legend, as both panels have them."""
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(error_label(error_name))
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)


def plot_marks(ax, marks):
    """Other models' (label, wall time, error) as black stars."""
    for label, wall, error in marks:
        ax.plot([wall], [error], "*", color="k", markersize=11)
        ax.annotate(label, (wall, error), textcoords="offset points", xytext=(6, -10), fontsize=8)


def parse_mark(text):
    """ "LABEL=WALL_S,ERROR" -> (label, wall, error)."""
    label, _, numbers = text.rpartition("=")
    wall, error = (float(v) for v in numbers.split(","))
    return label, wall, error


def plot_cost(ax, series, error_name, marks=()):
    plot_marks(ax, marks)
    everything = []
    for k, (label, points) in enumerate(series.values()):
        marker = MARKERS[k % len(MARKERS)]
        ax.plot([p[1] for p in points], [p[2] for p in points], marker=marker, label=label,
                color=f"C{k}")
        for s, t, e in points:
            ax.annotate(f"{s:g}", (t, e), textcoords="offset points", xytext=(4, 4), fontsize=7,
                        color=f"C{k}")
        everything += [(t, e) for _, t, e in points]
    front = pareto_front(everything)
    if front:
        ax.step([p[0] for p in front], [p[1] for p in front], where="post", color="k",
                linestyle="--", linewidth=1, label="Pareto front")
        ax.plot([p[0] for p in front], [p[1] for p in front], "o", markersize=14,
                markerfacecolor="none", markeredgecolor="k")
    finish_axes(ax, "wall time per run (s)", error_name,
                "accuracy against cost (labels: spacing, m)")


def plot_convergence(ax, series, error_name):
    for k, (label, points) in enumerate(series.values()):
        spacings = [p[0] for p in points]
        errors = [p[2] for p in points]
        ax.plot(spacings, errors, marker=MARKERS[k % len(MARKERS)], label=label, color=f"C{k}")
        for j, order in enumerate(observed_orders(spacings, errors)):
            s = math.sqrt(spacings[j] * spacings[j + 1])
            e = math.sqrt(errors[j] * errors[j + 1])
            ax.annotate(f"{order:.2f}", (s, e), textcoords="offset points", xytext=(0, 6),
                        fontsize=7, color=f"C{k}", ha="center")
    finish_axes(ax, "particle spacing (m)", error_name, "convergence (labels: observed order)")


def report(rows, series, error):
    for r in rows:
        if r["status"] != "ok":
            knobs = ", ".join(f"{k} {r[k]}" for k in SERIES_KNOBS if r.get(k, ""))
            print(f"run {r['run']} (spacing {r['spacing_m']}, {knobs}): {r['status']}: "
                  f"{r['message']}")
    for label, points in series.values():
        orders = observed_orders([p[0] for p in points], [p[2] for p in points])
        print(f"{label}: {error} " + ", ".join(f"{p[2]:.4g}" for p in points) +
              "; observed orders " + ", ".join(f"{o:.2f}" for o in orders))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("table", help="the CSV table of swe-mps study")
    parser.add_argument("-o", "--output", default="study.png", help="the PNG to write")
    parser.add_argument("--error",
                        help="the error column: fan_l1 (the default of an analytic reference), "
                             "fan_l2, fan_linf, upstream_fan_l1; max_depth_mad_m (the default "
                             "of a reference map)")
    parser.add_argument("--mark", action="append", default=[], type=parse_mark,
                        metavar="LABEL=WALL_S,ERROR",
                        help="another model's wall time and error, drawn as a star")
    args = parser.parse_args()
    rows = read_table(args.table)
    error = args.error or ("max_depth_mad_m" if rows and "max_depth_mad_m" in rows[0] else "fan_l1")
    series = split_series(rows, error)
    report(rows, series, error)
    fig, (cost, convergence) = plt.subplots(1, 2, figsize=(13, 5.5))
    plot_cost(cost, series, error, args.mark)
    plot_convergence(convergence, series, error)
    fig.tight_layout()
    fig.savefig(args.output, dpi=130)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
