#!/usr/bin/python3
"""The terrain of the Environment Agency's 2D benchmark Test 2 (filling of floodplain
depressions; Neelz & Pender 2013), and where its water must end by volume alone.

The benchmark's terrain (test2DEM.asc, 2 m) is a closed form: every value of the published
file is, to its four decimals,

  z = 10 - x/2000 - 0.0006666 (2000 - y)            a plane falling east and south
      + 8e-6 max(0, 252 - y)^2                      a rise along the southern edge
      + 0.125 cos^2(pi x/500) cos^2(pi y/500)       humps between the depressions
      - 0.5 sin^2(pi x/500) sin^2(pi y/500)         16 depressions, inside [0, 2000]^2

with x east and y north in metres (docs/benchmarks.md, "Test 2", says how this was found).

This writes:
  data/ea-test-2/dem.asc      the terrain on 10 m cells over the 2000 m x 2000 m domain
  data/ea-test-2/fill.csv     the level each depression ends at if the inflow's 97,200 m^3 fill
                              the depressions in turn, each spilling over its lowest saddle
                              into the depression below it, none left on the slopes

The fill is found on the 2 m terrain: from each depression's lowest cell, cells are added
lowest first (a priority flood) until the next is lower than the level reached: that level is
the spill, and the cell the water spills to runs down the steepest neighbour to the next
depression. The volume below a level is summed over the flooded cells.
"""
import argparse
import heapq
import os

import numpy as np

ROOT = os.path.normpath(os.path.join(os.path.dirname(__file__), ".."))
INFLOW_M3 = 20.0 * 60.0 * (2.5 + 76.0 + 2.5)  # 0 -> 20 m^3/s over 5 min, held 76, down over 5
CENTRES = [250.0, 750.0, 1250.0, 1750.0]


def terrain(x, y):
    plane = 10.0 - (x / 2000.0 + (2000.0 - y) * 0.0006666)
    rise = 8e-6 * np.maximum(0.0, 252.0 - y) ** 2
    hump = 0.125 * np.cos(np.pi * x / 500.0) ** 2 * np.cos(np.pi * y / 500.0) ** 2
    inside = (x >= 0) & (x <= 2000) & (y >= 0) & (y <= 2000)
    bowl = 0.5 * np.sin(np.pi * x / 500.0) ** 2 * np.sin(np.pi * y / 500.0) ** 2
    return plane + rise + hump - np.where(inside, bowl, 0.0)


def write_dem(path, cell):
    n = int(round(2000.0 / cell))
    centres = (np.arange(n) + 0.5) * cell
    x, y = np.meshgrid(centres, centres[::-1])
    z = terrain(x, y)
    with open(path, "w") as f:
        f.write(f"ncols {n}\nnrows {n}\nxllcorner 0\nyllcorner 0\ncellsize {cell:g}\n")
        f.write("NODATA_value -9999\n")
        for row in z:
            f.write(" ".join(f"{v:.5f}" for v in row) + "\n")


class Grid:
    """The terrain on nodes 2 m apart over the closed domain."""

    def __init__(self, step=2.0):
        self.step = step
        self.n = int(round(2000.0 / step)) + 1
        coords = np.arange(self.n) * step
        self.x, self.y = np.meshgrid(coords, coords, indexing="ij")
        self.z = terrain(self.x, self.y)
        # Node areas: a quarter or half cell on the boundary.
        w = np.full(self.n, step)
        w[0] = w[-1] = step / 2
        self.area = np.outer(w, w)

    def node(self, x, y):
        return int(round(x / self.step)), int(round(y / self.step))

    def neighbours(self, i, j):
        for di, dj in ((1, 0), (-1, 0), (0, 1), (0, -1)):
            a, b = i + di, j + dj
            if 0 <= a < self.n and 0 <= b < self.n:
                yield a, b

    def run_down(self, i, j, surface):
        """Follows the steepest descent of `surface` from a node to where it stops."""
        while True:
            best = min(self.neighbours(i, j), key=lambda p: surface[p])
            if surface[best] >= surface[i, j]:
                return i, j
            i, j = best


def flood(grid, start, surface):
    """Floods `surface` from a node, lowest node first, until the water would run out over a
    saddle. Returns the spill level, the node it spills to (None when the whole domain is
    one lake), the levels reached on the way with the volume held below each, and the nodes
    flooded in order."""
    seen = np.zeros(surface.shape, dtype=bool)
    heap = [(surface[start], start)]
    seen[start] = True
    level, area, volume = surface[start], 0.0, 0.0
    levels, volumes, nodes = [level], [0.0], []
    while heap:
        z, node = heapq.heappop(heap)
        if z < level - 1e-12:
            return level, node, np.array(levels), np.array(volumes), nodes
        volume += area * (z - level)
        level = z
        area += grid.area[node]
        levels.append(level)
        volumes.append(volume)
        nodes.append(node)
        for nb in grid.neighbours(*node):
            if not seen[nb]:
                seen[nb] = True
                heapq.heappush(heap, (surface[nb], nb))
    return level, None, np.array(levels), np.array(volumes), nodes


def fill(grid, volume_m3):
    """The water's surface after `volume_m3` has run down from the inflow line at the north
    end of the western edge and filled what it met: each basin to its spill level, then on
    down from its saddle; a full basin is a flat surface the next water floods over."""
    surface = grid.z.copy()
    at = grid.run_down(*grid.node(0.0, 1950.0), surface)
    left = volume_m3
    while left > 0.0:
        spill, outlet, levels, volumes, nodes = flood(grid, at, surface)
        level = spill
        if left <= volumes[-1] or outlet is None:
            level = float(np.interp(left, volumes, levels))
        for node in nodes:
            surface[node] = max(surface[node], level)
        left -= min(left, volumes[-1])
        if left > 0.0:
            at = grid.run_down(*outlet, surface)
    return surface


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cell", type=float, default=10.0, help="DEM cell size (m)")
    parser.add_argument("--out", default=os.path.join(ROOT, "data", "ea-test-2"))
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    write_dem(os.path.join(args.out, "dem.asc"), args.cell)
    grid = Grid()
    surface = fill(grid, INFLOW_M3)
    held = float(np.sum((surface - grid.z) * grid.area))
    with open(os.path.join(args.out, "fill.csv"), "w") as f:
        f.write(f"# {INFLOW_M3:.0f} m3 poured, {held:.0f} m3 held; tools/make_ea_test2.py\n")
        f.write("point,x,y,floor_m,level_m,depth_m\n")
        point = 0
        for cx in CENTRES:
            for cy in CENTRES:
                point += 1
                node = grid.node(cx, cy)
                floor = float(grid.z[node])
                level = float(surface[node])
                f.write(f"{point},{cx:g},{cy:g},{floor:.4f},{level:.4f},{level - floor:.4f}\n")
    print(open(os.path.join(args.out, "fill.csv")).read())


if __name__ == "__main__":
    main()
