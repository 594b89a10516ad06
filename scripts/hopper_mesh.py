#!/usr/bin/env python3
"""Writes a conical hopper as a closed triangle mesh (OBJ) for a [[obstacle]]
block of shape "mesh": the solid of revolution about the vertical axis of a
quadrilateral profile, whose inner face is a cone from the neck up to the
rim and whose outer face is a cylinder. The default arguments make
scenes/hopper3d.obj:

    /usr/bin/python3 scripts/hopper_mesh.py > scenes/hopper3d.obj
"""
import argparse
import math


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--center", type=float, nargs=2, default=[0.08, 0.08], help="axis (x, y), m")
    p.add_argument("--neck", type=float, default=0.02, help="neck radius, m")
    p.add_argument("--neck-z", type=float, default=0.06, help="height of the neck, m")
    p.add_argument("--rim", type=float, default=0.08, help="rim radius, m")
    p.add_argument("--rim-z", type=float, default=0.13, help="height of the rim, m")
    p.add_argument("--outer", type=float, default=0.12, help="outer radius, m")
    p.add_argument("--segments", type=int, default=48, help="facets around the axis")
    a = p.parse_args()
    # The profile (r, z), counter-clockwise in the (r, z) half-plane, so that
    # the revolved faces point out of the solid.
    profile = [(a.neck, a.neck_z), (a.outer, a.neck_z), (a.outer, a.rim_z), (a.rim, a.rim_z)]
    n, m = a.segments, len(profile)
    print("# conical hopper: neck r = %g m at z = %g m, rim r = %g m at z = %g m, outer r = %g m"
          % (a.neck, a.neck_z, a.rim, a.rim_z, a.outer))
    print("# written by scripts/hopper_mesh.py")
    for k in range(n):
        t = 2.0 * math.pi * k / n
        for r, z in profile:
            print("v %.9g %.9g %.9g" % (a.center[0] + r * math.cos(t), a.center[1] + r * math.sin(t), z))
    vid = lambda k, i: (k % n) * m + i + 1
    for k in range(n):
        for i in range(m):
            j = (i + 1) % m
            # The quad between profile edge (i, j) at angles k and k + 1.
            a0, a1, b0, b1 = vid(k, i), vid(k, j), vid(k + 1, i), vid(k + 1, j)
            print("f %d %d %d" % (a0, a1, b1))
            print("f %d %d %d" % (a0, b1, b0))


if __name__ == "__main__":
    main()
