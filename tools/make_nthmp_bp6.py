#!/usr/bin/python3
"""Write NTHMP benchmark problem 6's inputs (the conical island) in formats a scene reads.

From the benchmark's description (the USACE wave basin: water 0.32 m deep over a flat floor;
the island a truncated right circular cone, 7.2 m across at its toe and 2.2 m at its crest,
0.625 m high, faces 1:4, centred at x = 12.96, y = 13.80 m), this writes into data/nthmp-bp6/:
- conical_island.asc: the bed elevation (m, still water at z = 0) as an ESRI ASCII grid of
  0.05 m cells over x in [0, 25], y in [0, 27.6] (the basin inside its absorbers, centred on
  the island's axis), cell centres from 0.025 m;
- the laboratory files copied as they are: ts2a.txt, ts2b.txt, ts2cnew1.txt (gauge series,
  m), run2a.txt, run2b.txt, run2c.txt (run-up around the island, cm).

    /usr/bin/python3 tools/make_nthmp_bp6.py SOURCE_FOLDER
"""
import math
import pathlib
import shutil
import sys

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE.parent / "data" / "nthmp-bp6"

DEPTH = 0.32                  # m, still water over the basin floor
CENTRE = (12.96, 13.80)       # m, the island's axis
TOE, CREST = 3.6, 1.1         # m, radii
HEIGHT = 0.625                # m, above the floor
CELL = 0.05                   # m
WIDTH, LENGTH = 25.0, 27.6    # m, x and y extents


def bed(x, y):
    r = math.hypot(x - CENTRE[0], y - CENTRE[1])
    rise = min(HEIGHT, max(0.0, (TOE - r) * HEIGHT / (TOE - CREST)))
    return -DEPTH + rise


def main():
    source = pathlib.Path(sys.argv[1])
    columns = round(WIDTH / CELL)
    rows = round(LENGTH / CELL)
    OUT.mkdir(parents=True, exist_ok=True)
    with open(OUT / "conical_island.asc", "w") as out:
        out.write(f"ncols {columns}\nnrows {rows}\nxllcorner 0\nyllcorner 0\n"
                  f"cellsize {CELL}\nNODATA_value -9999\n")
        for j in reversed(range(rows)):
            y = (j + 0.5) * CELL
            out.write(" ".join(f"{bed((i + 0.5) * CELL, y):.5g}" for i in range(columns)) + "\n")
    for name in ("ts2a.txt", "ts2b.txt", "ts2cnew1.txt", "run2a.txt", "run2b.txt", "run2c.txt"):
        shutil.copy(source / name, OUT / name)
    print(f"wrote {OUT}: a {columns} x {rows} bed, the gauge series and the run-up")


if __name__ == "__main__":
    main()
