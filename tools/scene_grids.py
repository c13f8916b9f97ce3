"""Shared pieces of the scripts that write synthetic scenes (make_dead_end_arm.py,
make_flow_filled_pond.py): the bed as an ESRI ASCII grid, slip walls around the domain, and
the scene file."""

import argparse
import json
import os


def write_ascii_grid(path, x_min, y_min, columns, rows, cell, elevation):
    """Writes elevation(x, y) at the centres of columns x rows square cells, rows from the
    north, as an ESRI ASCII grid in local metres."""
    y_max = y_min + rows * cell
    with open(path, "w") as out:
        out.write(f"ncols {columns}\nnrows {rows}\nxllcorner {x_min}\nyllcorner {y_min}\n"
                  f"cellsize {cell}\nNODATA_value -9999\n")
        for row in range(rows):
            y = y_max - (row + 0.5) * cell
            out.write(" ".join(f"{elevation(x_min + (c + 0.5) * cell, y):.4f}"
                               for c in range(columns)) + "\n")


def box_walls(x_min, x_max, y_min, y_max):
    """The scene's `walls` entry for slip walls along the domain's four edges."""
    return [{"polyline": [[x_min, y_min], [x_max, y_min], [x_max, y_max],
                          [x_min, y_max], [x_min, y_min]], "condition": "slip"}]


def boxed_scene(name, description, end_time, box, manning_n):
    """What both scenes share: the domain `box` (x_min, x_max, y_min, y_max) walled with slip
    walls, the bed from bed.asc beside the scene, Manning friction, splitting and merging."""
    x_min, x_max, y_min, y_max = box
    return {
        "name": name,
        "description": description,
        "end_time": end_time,
        "domain": {"x_min": x_min, "x_max": x_max, "y_min": y_min, "y_max": y_max},
        "bed": {"raster": "bed.asc"},
        "friction": {"manning_n": manning_n},
        "splitting": {},
        "merging": {},
        "walls": box_walls(x_min, x_max, y_min, y_max),
    }


def write_scene(folder, scene):
    """Writes the scene as <name>.json in `folder` and says so."""
    path = os.path.join(folder, f"{scene['name']}.json")
    with open(path, "w") as out:
        json.dump(scene, out, indent=1)
    print(f"wrote {path} and bed.asc")


def scene_arguments(purpose, spacing_m, end_time_s, spacing_help="particle spacing, m"):
    """The command line both scripts take (a folder, --spacing, --end-time); makes the folder."""
    ap = argparse.ArgumentParser(description=purpose)
    ap.add_argument("folder", help="where to write bed.asc and the scene")
    ap.add_argument("--spacing", type=float, default=spacing_m, help=spacing_help)
    ap.add_argument("--end-time", type=float, default=end_time_s, help="simulated time, s")
    args = ap.parse_args()
    os.makedirs(args.folder, exist_ok=True)
    return args
