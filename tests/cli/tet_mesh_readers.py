#!/usr/bin/python3
"""Loads a tetrahedral mesh written by `isodel mesh --tets` with the readers FEM users have
(DELVOLMESH's output): meshio (.mesh, .vtu, .msh), VTK's XML reader (.vtu) and the Gmsh CLI (.msh: `gmsh
-check` parses it and reports counts; a conversion to MSH 2.2 gives the physical tag of every
element). Each must agree with the expected counts; tet volumes must be positive.

usage: tet_mesh_readers.py FILE VERTICES TRIANGLES TETS_INSIDE TETS_OUTSIDE
Prints one line per reader; exit status 1 on any disagreement, 2 if a reader is missing."""
import collections
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

errors = []


def expect(reader, what, got, want):
    ok = got == want
    print(f"{reader}: {what} = {got} (expected {want}){'' if ok else '  MISMATCH'}")
    if not ok:
        errors.append(f"{reader} {what}")


def positive_volumes(reader, points, tets):
    p = np.asarray(points, dtype=float)
    t = np.asarray(tets)
    if len(t) == 0:
        return
    a, b, c, d = (p[t[:, k]] for k in range(4))
    vol = np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a)) / 6.0
    expect(reader, "tets with volume <= 0", int((vol <= 0).sum()), 0)


def check_meshio(path, nv, ntri, nin, nout):
    import meshio

    m = meshio.read(path)
    expect("meshio", "points", len(m.points), nv)
    ext = os.path.splitext(path)[1]
    key = {".mesh": "medit:ref", ".vtu": "region", ".msh": "gmsh:physical"}[ext]
    tets, tris, regions = [], 0, collections.Counter()
    for block, tags in zip(m.cells, m.cell_data[key]):
        if block.type == "tetra":
            tets.append(block.data)
            regions.update(int(x) for x in tags)
        elif block.type == "triangle":
            tris += len(block.data)
            if ext == ".mesh":
                expect("meshio", "triangle refs", sorted(set(int(x) for x in tags)), [1])
            if ext == ".msh":
                expect("meshio", "triangle physical tags", sorted(set(int(x) for x in tags)), [3])
    if ext != ".vtu":
        expect("meshio", "triangles", tris, ntri)
    expect("meshio", "tets in region 1", regions[1], nin)
    expect("meshio", "tets in region 2", regions[2], nout)
    positive_volumes("meshio", m.points, np.concatenate(tets) if tets else [])


def check_vtk(path, nv, nin, nout):
    import vtk

    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    expect("vtk", "error code", r.GetErrorCode(), 0)
    g = r.GetOutput()
    expect("vtk", "points", g.GetNumberOfPoints(), nv)
    expect("vtk", "cells", g.GetNumberOfCells(), nin + nout)
    expect("vtk", "cell types", sorted({g.GetCellType(i) for i in range(g.GetNumberOfCells())}), [10] if nin + nout else [])
    a = g.GetCellData().GetArray("region")
    c = collections.Counter(int(a.GetValue(i)) for i in range(a.GetNumberOfTuples())) if a else collections.Counter()
    expect("vtk", "tets in region 1", c[1], nin)
    expect("vtk", "tets in region 2", c[2], nout)


def check_gmsh(path, nv, ntri, nin, nout):
    out = subprocess.run(["gmsh", "-check", path], capture_output=True, text=True, timeout=600)
    text = out.stdout + out.stderr
    expect("gmsh -check", "exit status", out.returncode, 0)
    expect("gmsh -check", "errors", len(re.findall(r"^Error", text, re.M)), 0)
    nodes = re.search(r"(\d+) nodes", text)
    elems = re.search(r"(\d+) elements", text)
    expect("gmsh -check", "nodes", int(nodes.group(1)) if nodes else None, nv)
    expect("gmsh -check", "elements", int(elems.group(1)) if elems else None, ntri + nin + nout)
    # MSH 2.2 lists each element with its physical tag: count by (type, physical).
    with tempfile.TemporaryDirectory() as tmp:
        v2 = os.path.join(tmp, "v2.msh")
        subprocess.run(["gmsh", path, "-0", "-format", "msh22", "-o", v2],
                       capture_output=True, text=True, timeout=600, check=True)
        with open(v2) as f:
            lines = f.read().split("$Elements\n", 1)[1].split("$EndElements", 1)[0].split("\n")
        c = collections.Counter()
        for line in lines[1:]:
            w = line.split()
            if w:
                c[(int(w[1]), int(w[3]))] += 1
    expect("gmsh msh22", "triangles tagged surface (3)", c[(2, 3)], ntri)
    expect("gmsh msh22", "tets tagged inside (1)", c[(4, 1)], nin)
    expect("gmsh msh22", "tets tagged outside (2)", c[(4, 2)], nout)


def main():
    if len(sys.argv) != 6:
        print(__doc__)
        return 2
    path = sys.argv[1]
    nv, ntri, nin, nout = (int(x) for x in sys.argv[2:])
    try:
        check_meshio(path, nv, ntri, nin, nout)
        if path.endswith(".vtu"):
            check_vtk(path, nv, nin, nout)
        if path.endswith(".msh"):
            check_gmsh(path, nv, ntri, nin, nout)
    except ImportError as e:
        print(f"reader missing: {e} (apt-get install python3-meshio python3-vtk9 gmsh)")
        return 2
    if errors:
        print("FAILED: " + ", ".join(errors))
        return 1
    print("OK")
    return 0


if __name__ == "__main__":
    sys.exit(main())
