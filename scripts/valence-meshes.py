#!/usr/bin/env python3
"""Writes the high-valence meshes of docs/bench/loop-valence.md as OBJ files.

  python3 scripts/valence-meshes.py bicone N out.obj   # a closed bicone: two valence-N poles, 2N triangles
  python3 scripts/valence-meshes.py fan K out.obj      # an open half disc: a boundary vertex of K + 1 edges
                                                       # (mesh::generate::half_disc_fan_mesh(K))
"""
import math
import sys


def bicone(n):
    v = [(0.0, 0.0, 1.0), (0.0, 0.0, -1.0)]
    v += [(math.cos(2 * math.pi * i / n), math.sin(2 * math.pi * i / n), 0.0) for i in range(n)]
    r = lambda i: 3 + i % n
    f = []
    for i in range(n):
        f.append((1, r(i), r(i + 1)))
        f.append((2, r(i + 1), r(i)))
    return v, f


def fan(k):
    v = [(0.0, 0.0, 0.0)]
    for ring in (1, 2):
        for i in range(k * ring + 1):
            a = math.pi * i / (k * ring)
            v.append((ring * math.cos(a), ring * math.sin(a), 0.0))
    r1 = lambda i: 2 + i
    r2 = lambda i: 3 + k + i
    f = []
    for i in range(k):
        f.append((1, r1(i), r1(i + 1)))
        f.append((r1(i), r2(2 * i), r2(2 * i + 1)))
        f.append((r1(i), r2(2 * i + 1), r1(i + 1)))
        f.append((r1(i + 1), r2(2 * i + 1), r2(2 * i + 2)))
    return v, f


def main():
    if len(sys.argv) != 4 or sys.argv[1] not in ("bicone", "fan"):
        sys.exit(__doc__)
    v, f = (bicone if sys.argv[1] == "bicone" else fan)(int(sys.argv[2]))
    with open(sys.argv[3], "w") as out:
        out.writelines(f"v {x:.9g} {y:.9g} {z:.9g}\n" for x, y, z in v)
        out.writelines(f"f {a} {b} {c}\n" for a, b, c in f)


main()
