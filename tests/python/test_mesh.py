"""isodel.mesh on arrays and files: the same mesh as the CLI, both axis orders, tets, meshio."""
import subprocess

import numpy as np
import pytest

import isodel
from conftest import blobs

mrcfile = pytest.importorskip("mrcfile")
meshio = pytest.importorskip("meshio")


def write_mrc(path, array, voxel=1.0):
    with mrcfile.new(str(path), overwrite=True) as f:
        f.set_data(array)
        f.voxel_size = voxel


def cli_mesh(cli, volume, out, iso, *extra):
    subprocess.run([cli, "mesh", str(volume), "-o", str(out), "--iso", str(iso), "--quiet", *extra], check=True)
    m = meshio.read(str(out))
    return m.points, m.cells_dict["triangle"].astype(np.int64)


def test_mrc_to_meshio_round_trip(tmp_path, data):
    with mrcfile.open(str(data / "two_blobs.mrc")) as f:
        arr = f.data.copy()
        voxel = float(f.voxel_size.x)
        origin = (float(f.header.origin.x), float(f.header.origin.y), float(f.header.origin.z))
    m = isodel.mesh(arr, 0.5, eps_voxels=0.5, spacing=(voxel,) * 3, origin=origin)
    assert m.vertices.dtype == np.float64 and m.vertices.shape[1] == 3
    assert m.triangles.dtype == np.int64 and m.triangles.shape[1] == 3
    assert [c["genus"] for c in m.stats["topology"]["per_component"]] == [0, 0]  # two blobs
    assert m.stats["counts"]["triangles"] == len(m.triangles)
    # World units: every vertex within the file's world box.
    assert (m.vertices >= np.array(origin) - 1e-9).all()
    assert (m.vertices <= np.array(origin) + voxel * (np.array(arr.shape[::-1]) - 1) + 1e-9).all()
    for name in ("surface.vtu", "surface.ply"):
        out = tmp_path / name
        m.to_meshio().write(str(out))
        back = meshio.read(str(out))
        np.testing.assert_array_equal(back.points, m.vertices)
        np.testing.assert_array_equal(back.cells_dict["triangle"], m.triangles)
    # The file itself meshes the same (path input, its own spacing and origin).
    by_path = isodel.mesh(data / "two_blobs.mrc", 0.5, eps_voxels=0.5)
    np.testing.assert_array_equal(by_path.vertices, m.vertices)
    np.testing.assert_array_equal(by_path.triangles, m.triangles)


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_array_matches_cli_in_both_axis_orders(tmp_path, cli, dtype):
    arr = blobs()  # [z, y, x]
    write_mrc(tmp_path / "blobs.mrc", arr)
    iso = 0.45
    ref_v, ref_t = cli_mesh(cli, tmp_path / "blobs.mrc", tmp_path / "ref.ply", iso, "--eps-voxels", "0.5")
    assert len(ref_t) > 100
    # float32 samples held as float64 convert back exactly, so the mesh is the same.
    zyx = isodel.mesh(arr.astype(dtype), iso, eps_voxels=0.5)
    np.testing.assert_array_equal(zyx.vertices, ref_v)
    np.testing.assert_array_equal(zyx.triangles, ref_t)
    xyz_c = np.ascontiguousarray(arr.transpose(2, 1, 0)).astype(dtype)  # [x, y, z], C-contiguous
    xyz = isodel.mesh(xyz_c, iso, eps_voxels=0.5, axis_order="xyz")
    np.testing.assert_array_equal(xyz.vertices, ref_v)
    np.testing.assert_array_equal(xyz.triangles, ref_t)
    # A strided view (no copy anywhere) reads the same samples.
    view = arr.astype(dtype).transpose(2, 1, 0)
    assert not view.flags.c_contiguous
    strided = isodel.mesh(view, iso, eps_voxels=0.5, axis_order="xyz")
    np.testing.assert_array_equal(strided.vertices, ref_v)
    # The wrong axis order is a different mesh (the field is not symmetric).
    swapped = isodel.mesh(arr, iso, eps_voxels=0.5, axis_order="xyz")
    assert swapped.vertices.shape != ref_v.shape or not np.array_equal(swapped.vertices, ref_v)


def test_spacing_and_origin_place_the_mesh():
    arr = blobs()
    base = isodel.mesh(arr, 0.45, eps_voxels=0.5)
    # Doubling every coordinate is exact in floating point: the same mesh, scaled.
    scaled = isodel.mesh(arr, 0.45, eps_voxels=0.5, spacing=(2, 2, 2))
    np.testing.assert_array_equal(scaled.vertices, base.vertices * 2)
    np.testing.assert_array_equal(scaled.triangles, base.triangles)
    # Anisotropic spacing and an origin: the mesh is where the samples are, and verifies there.
    spacing, origin = (0.5, 1.0, 2.0), (10.0, -4.0, 3.0)
    moved = isodel.mesh(arr, 0.45, eps_voxels=0.5, spacing=spacing, origin=origin)
    lo, hi = base.vertices.min(axis=0), base.vertices.max(axis=0)
    np.testing.assert_allclose(moved.vertices.min(axis=0), lo * spacing + origin, atol=0.5 * 0.5)
    np.testing.assert_allclose(moved.vertices.max(axis=0), hi * spacing + origin, atol=0.5 * 0.5)
    rep = isodel.verify(arr, 0.45, moved, eps_voxels=0.5, spacing=spacing, origin=origin)
    assert rep["passed"] is True


def test_integer_dtype(tmp_path, cli):
    arr = (blobs() * 200).astype(np.uint8)
    write_mrc(tmp_path / "u8.mrc", arr.astype(np.float32))
    ref_v, ref_t = cli_mesh(cli, tmp_path / "u8.mrc", tmp_path / "u8.ply", 90)
    m = isodel.mesh(arr, 90)
    np.testing.assert_array_equal(m.vertices, ref_v)
    np.testing.assert_array_equal(m.triangles, ref_t)


def test_tets_and_meshio_volume(tmp_path, data):
    m = isodel.mesh(data / "two_blobs.mrc", 0.5, eps_voxels=1, tets="both")
    assert m.tets.shape[1] == 4 and m.tets.dtype == np.int64
    assert set(np.unique(m.regions)) == {1, 2}
    np.testing.assert_array_equal(m.tet_vertices[: len(m.vertices)], m.vertices)
    vol = m.to_meshio(volume=True)
    vol.write(str(tmp_path / "tets.vtu"))
    assert len(meshio.read(str(tmp_path / "tets.vtu")).cells_dict["tetra"]) == len(m.tets)
    assert isodel.mesh(data / "two_blobs.mrc", 0.5, eps_voxels=1).tets is None


def test_graded_tets_keep_the_surface_with_fewer_points():
    z, y, x = np.meshgrid(*[np.arange(36.0)] * 3, indexing="ij")
    ball = (14.0 - np.sqrt((x - 17.3) ** 2 + (y - 17.6) ** 2 + (z - 17.1) ** 2)).astype(np.float32)
    graded = isodel.mesh(ball, 0.0, tets="inside")
    uniform = isodel.mesh(ball, 0.0, tets="inside", tet_spacing="uniform")
    finer = isodel.mesh(ball, 0.0, tets="inside", tet_size=2.0)  # 2 voxels at most, not 8
    np.testing.assert_array_equal(graded.triangles, uniform.triangles)
    np.testing.assert_array_equal(graded.vertices, uniform.vertices)
    assert len(graded.tet_vertices) < len(finer.tet_vertices) < len(uniform.tet_vertices)
    assert graded.stats["tets"]["volume_inside"] == pytest.approx(uniform.stats["tets"]["volume_inside"], rel=1e-9)


def test_threads_do_not_change_the_mesh(data):
    one = isodel.mesh(data / "torus.vdb", 0.0, eps_voxels=1, threads=1)
    two = isodel.mesh(data / "torus.vdb", 0.0, eps_voxels=1, threads=2)
    np.testing.assert_array_equal(one.vertices, two.vertices)
    np.testing.assert_array_equal(one.triangles, two.triangles)
    assert [c["genus"] for c in one.stats["topology"]["per_component"]] == [1]


def test_block_count_matches_cli(tmp_path, cli, data):
    # Two blocks of about equal work, as the CLI's --block-count: the same mesh, at 1 and 2 threads.
    ref_v, ref_t = cli_mesh(cli, data / "torus.vdb", tmp_path / "ref.ply", 0.0, "--eps-voxels", "0.5",
                            "--block-count", "2")
    for threads in (1, 2):
        m = isodel.mesh(data / "torus.vdb", 0.0, eps_voxels=0.5, block_count=2, threads=threads)
        assert m.stats["partition"]["blocks"] == 2
        np.testing.assert_array_equal(m.vertices, ref_v)
        np.testing.assert_array_equal(m.triangles, ref_t)
    assert [c["genus"] for c in m.stats["topology"]["per_component"]] == [1]
    with pytest.raises(ValueError, match="block_count"):
        isodel.mesh(data / "torus.vdb", 0.0, block_count=2, block_voxels=16)
