#!/usr/bin/python3
"""Write the bed and initial-depth rasters of Thacker's planar surface in a paraboloid.

The 2D case of the SWASHES collection (Delestre et al. 2013, "SWASHES: a compilation of
shallow water analytic solutions for hydraulic and environmental studies", section 4.2.2):
a paraboloid bowl z(r) = -h0 (1 - r^2 / a^2), r measured from the centre (L/2, L/2) of an
L x L domain, holding water whose surface is a plane that rotates around the bowl without
changing shape:

    h(x, y, t) = eta h0 / a^2 (2 (x - L/2) cos(w t) + 2 (y - L/2) sin(w t) - eta) - z(x, y)

where that is positive (dry elsewhere), with the uniform velocity u = -eta w sin(w t),
v = eta w cos(w t), w = sqrt(2 g h0) / a and period T = 2 pi / w. SWASHES' values: a = 1 m,
h0 = 0.1 m, eta = 0.5, L = 4 m; T = 4.4857 s.

Writes ESRI ASCII grids (cell-centred values, no CRS: a local metric frame) that
cases/thacker/scenario.json reads: bed.asc (z) and depth.asc (h at t = 0).

    /usr/bin/python3 tools/make_thacker_rasters.py cases/thacker [--cells 100]
"""

import argparse
import math
import os

A, H0, ETA, L, G = 1.0, 0.1, 0.5, 4.0, 9.81


def bed(x, y):
    return -H0 * (1.0 - ((x - L / 2) ** 2 + (y - L / 2) ** 2) / A ** 2)


def depth(x, y, t=0.0):
    w = math.sqrt(2.0 * G * H0) / A
    surface = ETA * H0 / A ** 2 * (2.0 * (x - L / 2) * math.cos(w * t)
                                   + 2.0 * (y - L / 2) * math.sin(w * t) - ETA)
    return max(0.0, surface - bed(x, y))


def write(path, cells, value):
    size = L / cells
    with open(path, "w") as f:
        f.write(f"ncols {cells}\nnrows {cells}\nxllcorner 0\nyllcorner 0\n"
                f"cellsize {size:.10g}\nNODATA_value -9999\n")
        for row in range(cells - 1, -1, -1):  # the first row is the northern one
            y = (row + 0.5) * size
            f.write(" ".join(f"{value((col + 0.5) * size, y):.7f}" for col in range(cells)))
            f.write("\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("folder", help="where bed.asc and depth.asc are written")
    ap.add_argument("--cells", type=int, default=100, help="cells along each side (default 100)")
    args = ap.parse_args()
    os.makedirs(args.folder, exist_ok=True)
    write(os.path.join(args.folder, "bed.asc"), args.cells, bed)
    write(os.path.join(args.folder, "depth.asc"), args.cells, depth)
    w = math.sqrt(2.0 * G * H0) / A
    print(f"wrote {args.folder}/bed.asc and depth.asc ({args.cells} x {args.cells}); "
          f"omega {w:.10g} 1/s, period {2 * math.pi / w:.10g} s")


if __name__ == "__main__":
    main()
