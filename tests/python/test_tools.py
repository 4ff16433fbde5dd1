"""isodel.verify, read_volume, decimate and info."""
import numpy as np
import pytest

import isodel

mrcfile = pytest.importorskip("mrcfile")


def test_verify_arrays_and_paths(tmp_path, data):
    path = data / "two_blobs.mrc"
    m = isodel.mesh(path, 0.5, eps_voxels=0.5)
    rep = isodel.verify(path, 0.5, m, eps_voxels=0.5)
    assert rep["passed"] is True
    assert rep["hausdorff"]["passed"] is True
    # The same mesh from a file, and the volume as an array.
    meshio = pytest.importorskip("meshio")
    m.to_meshio().write(str(tmp_path / "m.ply"))
    v = isodel.read_volume(path)
    rep2 = isodel.verify(v.array, 0.5, str(tmp_path / "m.ply"), eps_voxels=0.5, spacing=v.spacing, origin=v.origin)
    assert rep2["passed"] is True
    # A mesh with a hole is not verified.
    holed = isodel.verify(path, 0.5, (m.vertices, m.triangles[1:]), eps_voxels=0.5)
    assert holed["passed"] is False
    with pytest.raises(ValueError, match="triangles: index"):
        isodel.verify(path, 0.5, (m.vertices, m.triangles + len(m.vertices)))


def test_read_volume(data):
    v = isodel.read_volume(data / "two_blobs.mrc")
    with mrcfile.open(str(data / "two_blobs.mrc")) as f:
        np.testing.assert_array_equal(v.array, f.data)
    assert v.spacing == (0.5, 0.5, 0.5) and v.origin == (-8.0, -8.0, -8.0)
    assert v.format == "mrc" and v.inside == "above"
    xyz = isodel.read_volume(data / "two_blobs.mrc", axis_order="xyz")
    np.testing.assert_array_equal(xyz.array, v.array.transpose(2, 1, 0))
    a = isodel.mesh(v.array, 0.5, spacing=v.spacing, origin=v.origin)
    b = isodel.mesh(data / "two_blobs.mrc", 0.5)
    np.testing.assert_array_equal(a.vertices, b.vertices)
    t = isodel.read_volume(data / "torus.vdb")
    assert t.inside == "below" and t.format == "vdb"
    with pytest.raises(OSError, match="nothing.mrc"):
        isodel.read_volume(data / "nothing.mrc")


def test_info(data):
    i = isodel.info(data / "two_blobs.mrc")
    assert i["dims"] == (32, 32, 32) and i["format"] == "mrc"
    with mrcfile.open(str(data / "two_blobs.mrc")) as f:
        assert i["value_range"] == (float(f.data.min()), float(f.data.max()))
    arr = np.zeros((2, 3, 4), np.int16)
    arr[1, 2, 3] = 7
    j = isodel.info(arr)
    assert j["dims"] == (4, 3, 2) and j["value_range"] == (0.0, 7.0) and j["format"] == "array"


def test_decimate_then_mesh(tmp_path, data):
    out = tmp_path / "coarse.vdb"
    r = isodel.decimate(data / "two_blobs.mrc", out, k=1, tolerance=0.01, iso=0.5)
    assert r["cells_after"] < r["cells_before"]
    assert r["max_error"] <= 0.01
    assert isodel.info(out)["adaptive"]["levels"] == len(r["leaves_per_level"])
    m = isodel.mesh(out, 0.5, eps_voxels=1)
    assert len(m.stats["topology"]["per_component"]) == 2
