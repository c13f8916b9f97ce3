#!/usr/bin/python3
"""Write NTHMP benchmark problem 7's inputs (the Monai valley) in formats a scene reads.

From the benchmark's files (Benchmark_2_Bathymetry.txt: x, y and still-water depth on a
0.014 m grid; Benchmark_2_input.txt: the incident wave's level at x = 0), this writes into
data/nthmp-bp7/:
- monai_bed.asc: the bed elevation (minus the still-water depth, m) as an ESRI ASCII grid whose
  cell centres are the benchmark's grid points;
- incident_wave.csv: time_s,level_m, the level series of the scene's level boundary;
- gauges_ch5_ch7_ch9.csv and OBS_RUNUP.txt copied as they are (the measured gauge series, cm,
  and the observed run-up).

    /usr/bin/python3 tools/make_nthmp_bp7.py SOURCE_FOLDER
"""
import pathlib
import shutil
import sys

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE.parent / "data" / "nthmp-bp7"


def main():
    source = pathlib.Path(sys.argv[1])
    points = {}
    for line in (source / "Benchmark_2_Bathymetry.txt").read_text().splitlines()[1:]:
        fields = line.split()
        if len(fields) == 3:
            x, y, depth = (float(f) for f in fields)
            points[(round(x / 0.014), round(y / 0.014))] = -depth
    columns = 1 + max(i for i, _ in points)
    rows = 1 + max(j for _, j in points)
    if len(points) != columns * rows:
        raise SystemExit(f"the bathymetry is not a full grid: {len(points)} of {columns} x {rows}")
    OUT.mkdir(parents=True, exist_ok=True)
    with open(OUT / "monai_bed.asc", "w") as out:
        out.write(f"ncols {columns}\nnrows {rows}\nxllcenter 0\nyllcenter 0\ncellsize 0.014\n")
        out.write("NODATA_value -9999\n")
        for j in reversed(range(rows)):
            out.write(" ".join(f"{points[(i, j)]:.6g}" for i in range(columns)) + "\n")
    with open(OUT / "incident_wave.csv", "w") as out:
        out.write("# NTHMP benchmark problem 7: the incident wave's level at x = 0\n")
        out.write("time_s,level_m\n")
        for line in (source / "Benchmark_2_input.txt").read_text().splitlines()[1:]:
            fields = line.split()
            if len(fields) == 2:
                out.write(f"{float(fields[0]):g},{float(fields[1]):.6g}\n")
    for name in ("gauges_ch5_ch7_ch9.csv", "OBS_RUNUP.txt"):
        shutil.copy(source / name, OUT / name)
    print(f"wrote {OUT}: a {columns} x {rows} bed, the incident wave, the gauges and run-up")


if __name__ == "__main__":
    main()
