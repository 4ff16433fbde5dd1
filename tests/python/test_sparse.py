"""A pyopenvdb level set is meshed where it is stored: two spheres 1500 voxels apart per axis
(a dense box of their bounds would hold 1544^3 floats, 14 GB) mesh within a small peak memory."""
import resource

import numpy as np
import pytest

import isodel

vdb = pytest.importorskip("pyopenvdb")


def test_two_far_spheres_mesh_sparse():
    a = vdb.createLevelSetSphere(20.0, (0, 0, 0), 1.0, 3.0)  # radius, centre, voxel, half width
    b = vdb.createLevelSetSphere(20.0, (1500, 1500, 1500), 1.0, 3.0)
    a.combine(b, min)  # CSG union of level sets; visits stored values only, never a dense box
    lo, hi = a.evalActiveVoxelBoundingBox()
    assert min(h - l for l, h in zip(lo, hi)) > 1500  # the box is huge, the grid is not
    m = isodel.mesh(a, 0.0, eps_voxels=1.0)
    peak_mib = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"peak memory {peak_mib:.0f} MiB, {len(m.triangles)} triangles")
    assert peak_mib < 1024, f"peak memory {peak_mib:.0f} MiB: was the grid densified?"
    assert [c["genus"] for c in m.stats["topology"]["per_component"]] == [0, 0]
    # Each sphere's vertices lie on it, within the bound plus the interpolation error.
    for centre in (np.zeros(3), np.full(3, 1500.0)):
        near = np.linalg.norm(m.vertices - centre, axis=1) < 100
        assert near.sum() > 100
        r = np.linalg.norm(m.vertices[near] - centre, axis=1)
        assert np.abs(r - 20.0).max() < 1.5
    # The grid was shared, not consumed: it still has its voxels.
    assert a.activeVoxelCount() > 0


def test_double_grid_is_refused():
    g = vdb.Vec3SGrid()
    g.fill((0, 0, 0), (3, 3, 3), (1.0, 0.0, 0.0))
    with pytest.raises(ValueError, match="only FloatGrid"):
        isodel.mesh(g, 0.5)
