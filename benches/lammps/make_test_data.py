"""A loose, random, non-overlapping packing of glass spheres in the 39 mm die, written as a LAMMPS data
file in the format `powderfmu bed export-lammps` writes (atom_style sphere: id type diameter density
x y z; Velocities: id vx vy vz wx wy wz), to test benches/lammps/*.in without the engine.

Diameters uniform in [0.59, 1.41] mm, density 2456 kg/m^3, SI units, die axis z through x = y = 0,
radius 19.5 mm, floor z = 0. Spheres are placed by random sequential addition in a column of height
--height (default 20 mm, about 30 % solids for 10^4 spheres); settle it with settle.in.
Standard library only.  Usage: python3 make_test_data.py [-n 10000] [--height 0.02] [--seed 1] OUT
"""

import argparse
import math
import random

D_MIN, D_MAX, DENSITY, DIE_RADIUS = 0.59e-3, 1.41e-3, 2456.0, 0.0195
GAP = 1e-6  # clearance between spheres and from the walls [m]


def pack(n, height, rng):
    cell = D_MAX + GAP  # any two spheres that may touch lie in neighbouring cells
    grid = {}
    spheres = []
    tries = 0
    while len(spheres) < n:
        tries += 1
        if tries > 200 * n:
            raise SystemExit(f"only {len(spheres)} spheres fit in {height} m; raise --height")
        d = rng.uniform(D_MIN, D_MAX)
        r = 0.5 * d
        rmax = DIE_RADIUS - r - GAP
        x, y = rng.uniform(-rmax, rmax), rng.uniform(-rmax, rmax)
        if x * x + y * y > rmax * rmax:
            continue
        z = rng.uniform(r + GAP, height - r)
        key = (math.floor(x / cell), math.floor(y / cell), math.floor(z / cell))
        ok = True
        for i in (-1, 0, 1):
            for j in (-1, 0, 1):
                for k in (-1, 0, 1):
                    for (u, v, w, s) in grid.get((key[0] + i, key[1] + j, key[2] + k), ()):
                        if (x - u) ** 2 + (y - v) ** 2 + (z - w) ** 2 < (r + s + GAP) ** 2:
                            ok = False
                            break
                    if not ok:
                        break
                if not ok:
                    break
            if not ok:
                break
        if ok:
            grid.setdefault(key, []).append((x, y, z, r))
            spheres.append((d, x, y, z))
    return spheres


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out")
    ap.add_argument("-n", type=int, default=10000)
    ap.add_argument("--height", type=float, default=0.02, help="column height filled [m]")
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    spheres = pack(a.n, a.height, random.Random(a.seed))
    b = DIE_RADIUS + 1e-4  # the box holds the die; f f f boundaries lose atoms that leave it
    with open(a.out, "w") as f:
        f.write(f"LAMMPS data file: powderfmu bed\n\n{len(spheres)} atoms\n1 atom types\n\n")
        f.write(f"{-b} {b} xlo xhi\n{-b} {b} ylo yhi\n-0.001 {a.height + 0.002} zlo zhi\n\n")
        f.write("Atoms # sphere\n\n")
        for i, (d, x, y, z) in enumerate(spheres, 1):
            f.write(f"{i} 1 {d:.9e} {DENSITY} {x:.9e} {y:.9e} {z:.9e}\n")
        f.write("\nVelocities\n\n")
        for i in range(1, len(spheres) + 1):
            f.write(f"{i} 0 0 0 0 0 0\n")
    print(f"{len(spheres)} spheres written to {a.out}")


if __name__ == "__main__":
    main()
