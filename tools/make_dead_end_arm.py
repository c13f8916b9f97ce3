#!/usr/bin/python3
"""Write a scene that asks whether water filled in by flow comes to rest level: a basin opening
into a dry dead-end arm.

The basin is 200 m square with a flat floor at z = 0, filled to a level surface at 0.6 m
(seeded at rest, geometric volumes). Along its southern edge a dead-end arm runs 60 m south:
its floor at 0.1 m, 10 m wide, its walls rising 1 in 2 to 5 m (12 m wide at the water line).
The arm starts dry; the water runs into it and should come to rest at the basin's level, the
arm then holding the water that level puts over its bed (298 m³ between 5 m and 60 m south of
the basin's edge, for a basin level near 0.593 m). Slip walls close the domain; Manning's n is
0.024 (the valley flood's 0.035 at a tenth of its size). The case reproduces, in miniature, the
upper basin's narrow southern arm of cases/valley-flood (docs/valley-flood.md, "Where the
middle reach's shortfall sits"): measured, the arm comes to rest with its edges bare, holding
the water of a level 0.085 m below the basin's at 3 m spacing (19 % of its water missing) and
0.033 m below at 1.5 m (7 %).

Writes bed.asc (an ESRI ASCII grid of 0.5 m cells, local metres) and arm-<spacing>.json in the
given folder; run the scene with swe-mps run and read the particles it writes every 30 s.

    /usr/bin/python3 tools/make_dead_end_arm.py /tmp/arm --spacing 3
"""

import os

from scene_grids import boxed_scene, scene_arguments, write_ascii_grid, write_scene

X_MIN, X_MAX, Y_MIN, Y_MAX = 0.0, 200.0, -60.0, 200.0
CELL = 0.5
LEVEL = 0.6


def bed(x, y):
    if y >= 0.0:
        return 0.0
    return min(5.0, 0.1 + max(0.0, abs(x - 100.0) - 5.0) * 0.5)


def main():
    args = scene_arguments(__doc__.splitlines()[0], 3.0, 900.0)
    write_ascii_grid(os.path.join(args.folder, "bed.asc"), X_MIN, Y_MIN,
                     int((X_MAX - X_MIN) / CELL), int((Y_MAX - Y_MIN) / CELL), CELL, bed)
    name = f"arm-{args.spacing:g}"
    description = ("a basin filled to 0.6 m opening into a dry dead-end arm: does the water "
                   "that runs in come to rest at the basin's level?")
    scene = boxed_scene(name, description, args.end_time, (X_MIN, X_MAX, Y_MIN, Y_MAX), 0.024)
    scene.update({
        "water": [{"fill": {"polygon": [[X_MIN, 0], [X_MAX, 0], [X_MAX, Y_MAX], [X_MIN, Y_MAX]]},
                   "surface_elevation": LEVEL, "spacing": args.spacing,
                   "volumes": "geometric"}],
        "output": {"path": f"{name}.nc", "interval": 30, "particles": True,
                   "grid": {"spacing": 2 * args.spacing}},
    })
    write_scene(args.folder, scene)


if __name__ == "__main__":
    main()
