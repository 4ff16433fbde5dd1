#!/usr/bin/env python3
"""tet_census.py T.mesh [T.mesh ...]: the dihedral census of tetrahedral meshes (any format meshio
reads): tets, smallest and largest dihedral angle, tets under 10 degrees, tets outside [12, 165]
degrees (docs/benchmarks.md). The angle at an edge is pi minus the angle between the outward
normals of the two faces through it."""
import sys

import meshio
import numpy as np


def census(path):
    m = meshio.read(path)
    p = m.points
    t = m.cells_dict["tetra"]
    a, b, c, d = (p[t[:, i]] for i in range(4))
    normals = []
    for (x, y, z), opposite in zip([(b, c, d), (a, c, d), (a, b, d), (a, b, c)], [a, b, c, d]):
        n = np.cross(y - x, z - x)
        n *= -np.sign(np.einsum("ij,ij->i", n, opposite - x))[:, None]
        normals.append(n / np.linalg.norm(n, axis=1)[:, None])
    angles = np.array([180 - np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", normals[i], normals[j]), -1, 1)))
                       for i in range(4) for j in range(i + 1, 4)]).T
    lo, hi = angles.min(1), angles.max(1)
    return len(t), lo.min(), hi.max(), int((lo < 10).sum()), int(((lo < 12) | (hi > 165)).sum())


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: tet_census.py T.mesh [T.mesh ...]")
    print("%-40s %9s %8s %8s %7s %7s" % ("file", "tets", "min", "max", "<10deg", "out"))
    for f in sys.argv[1:]:
        n, lo, hi, under10, out = census(f)
        print("%-40s %9d %8.2f %8.1f %7d %7d" % (f, n, lo, hi, under10, out))
