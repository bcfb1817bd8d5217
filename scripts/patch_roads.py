#!/usr/bin/env python3
"""Writes the road surfaces of the patch presets (presets/roads/*.csv).

Both are `x_m,y_m,z_m` grids, one row per node, looped along x (the last
column is not the first repeated). Run from the repository's root:

    python3 scripts/patch_roads.py

wheel_path.csv: a road whose roughness varies across the width: a 5 cm
transverse corrugation whose amplitude grows from 0.1 mm at y = -0.1 m to
0.7 mm at y = +0.1 m (a rut on one side of the wheel path), on a 0.5 m
period, 2 mm along and 5 mm across.

chip_seal.csv: a surface dressing: stones of 2.5 to 4.5 mm radius, seeded,
as spherical caps standing up to 2 mm above the binder, on a 0.3 m by 0.2 m
period, 2 mm along and across.
"""
import math
import random


def write(path, xs, ys, z):
    with open(path, "w", encoding="ascii", newline="\n") as f:
        f.write("# written by scripts/patch_roads.py\n")
        f.write("x_m,y_m,z_m\n")
        for j, y in enumerate(ys):
            for i, x in enumerate(xs):
                f.write(f"{x:.6g},{y:.6g},{z(i, j, x, y):.6e}\n")


def wheel_path():
    xs = [i * 0.002 for i in range(250)]
    ys = [-0.1 + j * 0.005 for j in range(41)]

    def z(i, j, x, y):
        amp = 1e-4 + 6e-4 * (y + 0.1) / 0.2
        return amp * math.sin(2 * math.pi * x / 0.05)

    write("presets/roads/wheel_path.csv", xs, ys, z)


def chip_seal():
    rng = random.Random(2026)
    lx, ly, h = 0.3, 0.2, 0.002
    xs = [i * h for i in range(round(lx / h))]
    ys = [-0.1 + j * h for j in range(round(ly / h))]
    stones = []
    for _ in range(1500):
        r = rng.uniform(0.0025, 0.0045)
        stones.append((rng.uniform(0, lx), rng.uniform(-0.1, 0.1), r, rng.uniform(0.0005, 0.002)))
    grid = {}
    for sx, sy, r, top in stones:
        for i, x in enumerate(xs):
            dx = (x - sx + lx / 2) % lx - lx / 2  # periodic
            if abs(dx) >= r:
                continue
            for j, y in enumerate(ys):
                dy = (y - sy + ly / 2) % ly - ly / 2
                d2 = dx * dx + dy * dy
                if d2 < r * r:
                    cap = top - r + math.sqrt(r * r - d2)
                    if cap > grid.get((i, j), 0.0):
                        grid[(i, j)] = cap
    write("presets/roads/chip_seal.csv", xs, ys, lambda i, j, x, y: grid.get((i, j), 0.0))


if __name__ == "__main__":
    wheel_path()
    chip_seal()
