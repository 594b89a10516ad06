#!/usr/bin/env python3
"""Writes a rock as a closed triangle mesh (OBJ) for a rigid [[obstacle]]
block of shape "mesh": an icosahedron subdivided twice (320 triangles), its
vertices pushed out to an ellipsoid and roughened by a fixed pseudo-random
factor each (the same file on every machine). The default arguments make
scenes/rock3d.obj:

    /usr/bin/python3 scripts/rock_mesh.py > scenes/rock3d.obj
"""
import argparse
import math


def icosphere(levels):
    t = (1.0 + math.sqrt(5.0)) / 2.0
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
         (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    v = [unit(p) for p in v]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
         (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(levels):
        middle = {}

        def mid(i, j):
            key = (min(i, j), max(i, j))
            if key not in middle:
                a, b = v[i], v[j]
                v.append(unit(((a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2)))
                middle[key] = len(v) - 1
            return middle[key]

        finer = []
        for a, b, c in f:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            finer += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
        f = finer
    return v, f


def unit(p):
    n = math.sqrt(p[0] ** 2 + p[1] ** 2 + p[2] ** 2)
    return (p[0] / n, p[1] / n, p[2] / n)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--radii", type=float, nargs=3, default=[0.06, 0.045, 0.035],
                   help="semi-axes of the ellipsoid, m")
    p.add_argument("--rough", type=float, default=0.15, help="relative roughness")
    p.add_argument("--seed", type=int, default=7, help="seed of the roughness")
    a = p.parse_args()
    v, f = icosphere(2)
    state = a.seed
    print("# a rock: an ellipsoid of semi-axes %g, %g, %g m roughened by %g, seed %d"
          % (a.radii[0], a.radii[1], a.radii[2], a.rough, a.seed))
    print("# written by scripts/rock_mesh.py; centred on the origin")
    for x, y, z in v:
        state = (1103515245 * state + 12345) % 2 ** 31  # a fixed linear congruential sequence
        s = 1.0 + a.rough * (2.0 * state / 2 ** 31 - 1.0)
        print("v %.6f %.6f %.6f" % (s * a.radii[0] * x, s * a.radii[1] * y, s * a.radii[2] * z))
    for i, j, k in f:
        print("f %d %d %d" % (i + 1, j + 1, k + 1))


if __name__ == "__main__":
    main()
