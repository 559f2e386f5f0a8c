#!/usr/bin/env python3
"""Split every triangle of an OBJ mesh 1-to-4 at the midpoints of its PN triangles' edges.

    python3 scripts/pn-split.py IN.obj OUT.obj

Each edge's new vertex is the PN edge curve's midpoint (Vlachos et al.: control points from
the two corners' positions and normals) and its normal the quadratic normal field's value there,
so the split mesh's PN surface follows the original's closely (not exactly: PN triangles are
not closed under splitting). The corners keep area-weighted vertex normals, as meshrefine
computes them for a file without normals, or the normals the file gives them (one per
vertex: a vertex's last `f` reference wins); the output lists every normal (`f a//a ...`).
docs/benchmarks.md uses it to measure what splitting elements before choosing their levels
would save. Only `v` and `f` lines are read (polygons are fanned); no third-party modules.
"""
import math
import sys


def add(a, b):
    return [x + y for x, y in zip(a, b)]


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def scale(a, k):
    return [x * k for x in a]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def unit(a):
    return scale(a, 1.0 / math.sqrt(dot(a, a)))


def read(path):
    """Positions, triangles and the normal each vertex is given (None where a face gives none)."""
    verts, vns, faces, given = [], [], [], {}
    for line in open(path):
        s = line.split()
        if not s:
            continue
        if s[0] == "v":
            verts.append([float(x) for x in s[1:4]])
        elif s[0] == "vn":
            vns.append(unit([float(x) for x in s[1:4]]))
        elif s[0] == "f":
            idx = []
            for x in s[1:]:
                parts = x.split("/")
                i = int(parts[0])
                i = i - 1 if i > 0 else len(verts) + i
                if len(parts) == 3 and parts[2]:
                    n = int(parts[2])
                    given[i] = vns[n - 1 if n > 0 else len(vns) + n]
                idx.append(i)
            faces += [[idx[0], idx[k], idx[k + 1]] for k in range(1, len(idx) - 1)]
    return verts, faces, given


def normals(verts, faces):
    acc = [[0.0, 0.0, 0.0] for _ in verts]
    for f in faces:
        a, b, c = (verts[i] for i in f)
        n = cross(sub(b, a), sub(c, a))
        for i in f:
            acc[i] = add(acc[i], n)
    return [unit(n) for n in acc]


def midpoint(p0, p1, n0, n1):
    """The PN edge curve's point at t = 1/2 and the quadratic normal field's value there."""
    b210 = scale(sub(add(scale(p0, 2), p1), scale(n0, dot(sub(p1, p0), n0))), 1 / 3)
    b120 = scale(sub(add(scale(p1, 2), p0), scale(n1, dot(sub(p0, p1), n1))), 1 / 3)
    p = scale(add(add(p0, p1), scale(add(b210, b120), 3)), 1 / 8)
    d = sub(p1, p0)
    v = 2 * dot(d, add(n0, n1)) / dot(d, d)
    n110 = unit(sub(add(n0, n1), scale(d, v)))
    n = add(scale(add(n0, n1), 0.25), scale(n110, 0.5))
    return p, unit(n)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    verts, faces, given = read(sys.argv[1])
    norms = [given.get(i, n) for i, n in enumerate(normals(verts, faces))]
    out_v, out_n, mids = list(verts), list(norms), {}

    def mid(i, j):
        key = (min(i, j), max(i, j))
        if key not in mids:
            p, n = midpoint(verts[key[0]], verts[key[1]], norms[key[0]], norms[key[1]])
            mids[key] = len(out_v)
            out_v.append(p)
            out_n.append(n)
        return mids[key]

    out_f = []
    for a, b, c in faces:
        ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
        out_f += [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
    with open(sys.argv[2], "w") as o:
        o.write(f"# {sys.argv[1]} split 1-to-4 at its PN edge midpoints (scripts/pn-split.py)\n")
        for p in out_v:
            o.write("v %.7f %.7f %.7f\n" % tuple(p))
        for n in out_n:
            o.write("vn %.7f %.7f %.7f\n" % tuple(n))
        for f in out_f:
            o.write("f " + " ".join(f"{i + 1}//{i + 1}" for i in f) + "\n")
    print(f"{len(out_v)} vertices, {len(out_f)} triangles")


main()
