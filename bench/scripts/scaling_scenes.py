#!/usr/bin/env python3
"""Writes the scaling scenes of `make bench` (BENCHMARKS.md, "Scaling: 1,000
to 10,000 bodies") into config/scenes: Box3D's stress scenes from the same
files for every engine.

  pyramid_45, pyramid_90      one pyramid of 1 m cubes in the x-z plane with a
                              base of 45 / 90 boxes (1,035 / 4,095 boxes)
  many_pyramids_10k           182 pyramids of base 10 (55 boxes each, 10,010
                              boxes), 13 along x by 14 along y
  joint_grid_32, joint_grid_100
                              a 32 x 32 / 100 x 100 grid of spheres in the x-z
                              plane joined as a comb by ball joints, hanging
                              from the middle 7 spheres of its top row
                              (BodyGrid.comb_joints, service/scene/grid_comb.h)

many_pyramids (1,100 boxes) is the small member of the many-pyramids family.
Usage: bench/scripts/scaling_scenes.py [--out config/scenes]
"""
import argparse
import os

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
HEADER = """gravity { z: -9.81 }
dt: 0.004166666666666667
steps: 600
default_material { restitution: 0 friction: 0.5 }
bodies { name: "ground" plane { normal { z: 1 } offset: 0 } }
"""
CUBE = 'box { half_extents { x: 0.5 y: 0.5 z: 0.5 } } density: 1000'


def pyramid(base):
    """Row r (0-based) holds base - r touching cubes from x = -(base - 1) / 2 + r / 2 at z = 0.5 + r."""
    boxes = base * (base + 1) // 2
    lines = ["# Benchmark scene (bench/scripts/scaling_scenes.py): Box3D's pyramid of 1 m",
             "# cubes in the x-z plane, base %d, exactly touching; %s boxes, %s bodies." %
             (base, format(boxes, ","), format(boxes + 1, ","))]
    text = "\n".join(lines) + "\n" + HEADER
    for r in range(base):
        text += ('grids { prototype { name: "row%d" %s }\n        nx: %d origin { x: %g z: %g } spacing { x: 1 } }\n'
                 % (r, CUBE, base - r, -(base - 1) / 2 + r / 2, 0.5 + r))
    return text


def many_pyramids(along_x, along_y, base):
    count = along_x * along_y
    boxes = count * base * (base + 1) // 2
    text = ("# Benchmark scene (bench/scripts/scaling_scenes.py): Box3D's many pyramids,\n"
            "# %d pyramids of 1 m cubes with a base of %d, %d along x (%d m apart) by %d\n"
            "# along y (2 m apart), exactly touching; %s boxes, %s bodies.\n"
            % (count, base, along_x, base + 1, along_y, format(boxes, ","), format(boxes + 1, ",")))
    text += HEADER
    x0 = -(along_x - 1) * (base + 1) / 2
    y0 = -(along_y - 1)
    for c in range(along_x):
        for r in range(base):
            text += ('grids { prototype { name: "p%d_row%d" %s }\n'
                     '        nx: %d ny: %d origin { x: %g y: %g z: %g } spacing { x: 1 y: 2 } }\n'
                     % (c, r, CUBE, base - r, along_y, x0 + c * (base + 1) - (base - 1) / 2 + r / 2, y0,
                        0.5 + r))
    return text


def joint_grid(n, anchors=7):
    text = ("# Benchmark scene (bench/scripts/scaling_scenes.py): Box3D's joint grid as a\n"
            "# comb, %d x %d spheres of radius 0.4 m 1 m apart in the x-z plane, each\n"
            "# joined by a ball joint to the one above it and the top row along x\n"
            "# (BodyGrid.comb_joints), hanging from the middle %d spheres of its top row\n"
            "# (fixed) above the ground; %s bodies, %s joints.\n"
            % (n, n, anchors, format(n * n + 1, ","), format(n * (n - 1) + (n - 1) - (anchors - 1), ",")))
    text += HEADER
    text += ('grids { prototype { name: "ball" sphere { radius: 0.4 } density: 1000 }\n'
             '        nx: %d nz: %d origin { x: %g z: 1 } spacing { x: 1 z: 1 }\n'
             '        comb_joints: "ball" fixed_top: %d }\n' % (n, n, -(n - 1) / 2, anchors))
    return text


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=os.path.join(ROOT, "config", "scenes"))
    args = parser.parse_args()
    scenes = {
        "pyramid_45": pyramid(45),
        "pyramid_90": pyramid(90),
        "many_pyramids_10k": many_pyramids(13, 14, 10),
        "joint_grid_32": joint_grid(32),
        "joint_grid_100": joint_grid(100),
    }
    for name, text in scenes.items():
        with open(os.path.join(args.out, name + ".pbtxt"), "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
