#!/usr/bin/python3
"""Makes the urban block of cases/urban-block (data/urban-block/): a town block laid out on a
300 m x 300 m piece of the Jacksboro fault DEM, with streets, terraced houses and land use.

The ground is the DEM itself, resampled to 2.5 m (a cubic spline through the 3 arc-second
cells); streets are cut 0.15 m into it (kerbs). Houses stand in terraces along both sides of
every street, set back from it, in rows of 6-9 m wide houses with gaps of 0-3 m between them;
the layout is drawn from a fixed seed, so the files are the same every time. Land use: 1 road
(Manning n 0.02), 2 gardens and yards (0.05), 3 buildings (0.05; the walls keep water off it).
The values of n are those of the UK Environment Agency's Test 8A.

Run from the repository root, with GDAL's command-line tools (Debian: gdal-bin):
  gdalwarp -t_srs EPSG:32616 -te 755000 4043500 755300 4043800 -tr 2.5 2.5 -r cubicspline \
      data/jacksboro_fault_dem.tif /tmp/block.tif
  gdal_translate -of AAIGrid /tmp/block.tif /tmp/block.asc
  /usr/bin/python3 tools/make_urban_block.py /tmp/block.asc /tmp/urban
  gdal_translate -a_srs EPSG:32616 -co COMPRESS=DEFLATE /tmp/urban/dem.asc data/urban-block/dem.tif
  gdal_translate -a_srs EPSG:32616 -ot Byte -co COMPRESS=DEFLATE /tmp/urban/land_use.asc \
      data/urban-block/land_use.tif
  cp /tmp/urban/buildings.geojson data/urban-block/
"""
import json
import os
import random
import sys

import numpy as np

STREET_WIDTH = 12.0  # m
KERB = 0.15  # m the streets lie below the plots
SETBACK = 4.0  # m from the street's edge to the houses' fronts
HOUSE_DEPTH = 9.0  # m
# Street centre lines, in metres from the block's south-west corner.
NORTH_SOUTH = [45.0, 150.0, 255.0]
EAST_WEST = [50.0, 155.0, 260.0]


def read_asc(path):
    header = {}
    with open(path) as f:
        for _ in range(6):
            key, value = f.readline().split()
            header[key.lower()] = float(value)
    return header, np.loadtxt(path, skiprows=6)


def write_asc(path, header, values, fmt):
    with open(path, "w") as f:
        for key in ("ncols", "nrows", "xllcorner", "yllcorner", "cellsize"):
            f.write(f"{key} {header[key]:.6f}\n" if "corner" in key or key == "cellsize"
                    else f"{key} {int(header[key])}\n")
        np.savetxt(f, values, fmt=fmt)


def on_street(x, y):
    return any(abs(x - c) < STREET_WIDTH / 2 for c in NORTH_SOUTH) or any(
        abs(y - c) < STREET_WIDTH / 2 for c in EAST_WEST)


def terraces(extent):
    """Rectangles (x0, y0, x1, y1) of houses along both sides of every street."""
    rng = random.Random(20261129)
    houses = []
    edge = STREET_WIDTH / 2 + SETBACK
    crossing = STREET_WIDTH / 2 + SETBACK + 2.0  # houses keep clear of the junctions

    def clear_of_cross_streets(a0, a1, cross):
        return all(a1 < c - crossing or a0 > c + crossing for c in cross)

    for streets, cross, along_x in ((EAST_WEST, NORTH_SOUTH, True), (NORTH_SOUTH, EAST_WEST, False)):
        for c in streets:
            for side in (-1.0, 1.0):
                near = c + side * edge
                far = near + side * HOUSE_DEPTH
                lo, hi = min(near, far), max(near, far)
                a = 3.0
                while a < extent - 3.0:
                    width = rng.uniform(6.0, 9.0)
                    a1 = a + width
                    if a1 > extent - 3.0:
                        break
                    if clear_of_cross_streets(a, a1, cross) and 0.0 < lo and hi < extent:
                        houses.append((a, lo, a1, hi) if along_x else (lo, a, hi, a1))
                    a = a1 + rng.choice([0.0, 0.0, 1.5, 3.0])
    # Terraces of the two directions meet near the junctions: keep the first of any overlap.
    kept = []
    for h in houses:
        if all(h[2] <= k[0] or h[0] >= k[2] or h[3] <= k[1] or h[1] >= k[3] for k in kept):
            kept.append(h)
    return kept


def main():
    header, z = read_asc(sys.argv[1])
    out = sys.argv[2]
    os.makedirs(out, exist_ok=True)
    n, cell = int(header["nrows"]), header["cellsize"]
    x0, y0 = header["xllcorner"], header["yllcorner"]
    extent = n * cell
    houses = terraces(extent)
    land = np.full(z.shape, 2, dtype=int)
    for row in range(n):
        y = extent - (row + 0.5) * cell
        for col in range(int(header["ncols"])):
            x = (col + 0.5) * cell
            if on_street(x, y):
                z[row, col] -= KERB
                land[row, col] = 1
            elif any(h[0] <= x <= h[2] and h[1] <= y <= h[3] for h in houses):
                land[row, col] = 3
    write_asc(os.path.join(out, "dem.asc"), header, z, "%.3f")
    write_asc(os.path.join(out, "land_use.asc"), header, land, "%d")
    features = []
    for k, (a, b, c, d) in enumerate(houses):
        ring = [[x0 + a, y0 + b], [x0 + c, y0 + b], [x0 + c, y0 + d], [x0 + a, y0 + d],
                [x0 + a, y0 + b]]
        features.append({"type": "Feature", "properties": {"id": k + 1},
                         "geometry": {"type": "Polygon", "coordinates": [ring]}})
    collection = {"type": "FeatureCollection",
                  "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::32616"}},
                  "features": features}
    with open(os.path.join(out, "buildings.geojson"), "w") as f:
        json.dump(collection, f, separators=(",", ":"))
    print(f"{len(houses)} houses")


if __name__ == "__main__":
    main()
