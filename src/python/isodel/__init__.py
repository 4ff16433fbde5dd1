"""isodel: Delaunay meshes of level sets of sampled volumes, with guarantees.

The mesh of {F = iso} of the trilinear interpolant F of a sampled volume is homeomorphic to the
level set, within a Hausdorff distance eps of it, and a subcomplex of the Delaunay triangulation of
its vertices (Goswami, Gillette, Bajaj). docs/python.md is the manual; each function's docstring
says the same.

    import isodel, mrcfile
    with mrcfile.open("map.mrc") as f:
        m = isodel.mesh(f.data, iso=0.5, eps_voxels=0.5, spacing=f.voxel_size.tolist()[::-1])
    m.to_meshio().write("surface.ply")

Volumes are numpy arrays (any float or integer dtype; axis order "zyx" by default, as MRC files,
mrcfile and scikit-image keep them), paths of files isodel reads (.vdb, .mrc/.map/.ccp4,
.inr/.inr.gz), or pyopenvdb FloatGrids (meshed sparse, never densified).

Errors: ValueError for unusable input (the CLI's exit status 2, same one-line message), OSError for
files that cannot be read or written, GuaranteeViolated when a stated bound stopped the run,
Cancelled when the progress callback returned False, KeyboardInterrupt on Ctrl-C.
"""
from __future__ import annotations

import json
import os
from typing import Any, Callable, Dict, Optional, Sequence, Tuple

import numpy as np

from . import _isodel

__all__ = ["mesh", "verify", "read_volume", "decimate", "info", "Mesh", "VolumeData",
           "GuaranteeViolated", "Cancelled"]

#: A stated bound of the algorithm (rounds, points, the voxel bound) stopped the run, or
#: certify=True found the mesh wrong; the message says which. Nothing is returned.
GuaranteeViolated = _isodel.GuaranteeViolated
#: The progress callback returned False; the run stopped and nothing is returned.
Cancelled = _isodel.Cancelled

GuaranteeViolated.__module__ = Cancelled.__module__ = "isodel"  # as users name them

ProgressCallback = Callable[[str, float], Optional[bool]]


def _volume_arg(volume: Any) -> Any:
    """A path as str, a pyopenvdb grid as is, anything else as a numpy array (no copy if it is one)."""
    if isinstance(volume, (str, os.PathLike)):
        return os.fspath(volume)
    if type(volume).__module__ == "pyopenvdb":
        return volume
    return np.asarray(volume)


def _progress_arg(progress: Optional[ProgressCallback]) -> Optional[ProgressCallback]:
    """Refused before any work, not at the first call from inside the run."""
    if progress is not None and not callable(progress):
        raise TypeError(f"progress: expected None or a callable(stage, fraction), got {type(progress).__name__}")
    return progress


def _triple(name: str, value: Sequence[float]) -> Tuple[float, float, float]:
    t = tuple(float(v) for v in np.broadcast_to(np.asarray(value, dtype=float), (3,)))
    if len(t) != 3:
        raise ValueError(f"{name}: expected 3 numbers, got {value!r}")
    return t  # type: ignore[return-value]


class Mesh:
    """The result of isodel.mesh.

    vertices: float64 (n, 3), world coordinates x, y, z.
    triangles: int64 (m, 3), counter-clockwise seen from outside (normals point outwards).
    tet_vertices, tets, regions: with tets=...: float64 (p, 3); int64 (q, 4) positively oriented;
        int64 (q,) region per tet, 1 inside, 2 outside. The first n tet vertices are `vertices`.
        None without tets.
    stats: what the run did and measured (the CLI's --stats JSON as a dict).
    """

    def __init__(self, raw: Dict[str, Any]):
        self.vertices: np.ndarray = raw["vertices"]
        self.triangles: np.ndarray = raw["triangles"]
        self.tet_vertices: Optional[np.ndarray] = raw.get("tet_vertices")
        self.tets: Optional[np.ndarray] = raw.get("tets")
        self.regions: Optional[np.ndarray] = raw.get("regions")
        self.stats: Dict[str, Any] = json.loads(raw["stats_json"])

    def to_meshio(self, volume: bool = False):
        """A meshio.Mesh: the triangles, or with volume=True the tetrahedra (cell data "region")
        with the surface triangles. Needs meshio (Debian: python3-meshio)."""
        import meshio  # imported here: meshio is optional

        # int32 indices where they fit: several of meshio's writers (PLY) cannot store int64.
        def cells(a: np.ndarray) -> np.ndarray:
            return a.astype(np.int32) if a.size == 0 or a.max() < 2**31 else a

        if not volume:
            return meshio.Mesh(self.vertices, [("triangle", cells(self.triangles))])
        if self.tets is None:
            raise ValueError("to_meshio(volume=True): this mesh has no tetrahedra (mesh with tets=...)")
        return meshio.Mesh(self.tet_vertices, [("tetra", cells(self.tets)), ("triangle", cells(self.triangles))],
                           cell_data={"region": [self.regions, np.zeros(len(self.triangles), np.int64)]})

    def __repr__(self) -> str:
        tets = "" if self.tets is None else f", {len(self.tets)} tets"
        return f"isodel.Mesh({len(self.vertices)} vertices, {len(self.triangles)} triangles{tets})"


def mesh(volume: Any, iso: float, *, eps_voxels: Optional[float] = None, eps: Optional[float] = None,
         inside: Optional[str] = None, spacing: Sequence[float] = (1, 1, 1),
         origin: Sequence[float] = (0, 0, 0), axis_order: str = "zyx", tets: Optional[str] = None,
         adaptive: bool = False, threads: Optional[int] = None, certify: bool = False,
         progress: Optional[ProgressCallback] = None, grid: str = "", snap: bool = False,
         improve_tets: bool = True, facet_angle_deg: float = 0.0, block_voxels: int = 0,
         max_rounds: int = 2000, max_points: int = 0, tet_spacing: str = "graded",
         tet_size: float = 0.0, tet_grading: float = 0.5, tet_min_dihedral_deg: float = 0.0,
         tet_max_dihedral_deg: float = 180.0, release_blocks: bool = False, block_count: int = 0) -> Mesh:
    """Mesh the level set {F = iso} of a volume, with guarantees (as `isodel mesh`).

    volume: a 3-d numpy array (any float or integer dtype; read in place, not copied first), a
        path (.vdb, .mrc/.map/.ccp4, .inr/.inr.gz, an isodel adaptive .vdb), or a pyopenvdb
        FloatGrid (meshed sparse, shared, never densified; do not modify it during the call).
    iso: the isovalue; it must lie within the samples' value range.
    eps_voxels / eps: the Hausdorff bound in smallest voxel edges (default 0.5) or in world units;
        give at most one.
    inside: "above" or "below" the isovalue; default "below" for level-set grids, else "above".
    spacing, origin: arrays only: voxel size and the world position of sample [0,0,0], both in
        world axis order (x, y, z) whatever axis_order is.
    axis_order: arrays only: "zyx" (default: array[z, y, x], as MRC files, mrcfile and
        scikit-image keep them) or "xyz" (array[x, y, z]).
    tets: None, "inside", "outside" or "both": also build the tetrahedral mesh of that region.
    tet_spacing: "graded" (default: points off M one voxel apart next to it, doubling with the
        distance, so the tet count follows the surface) or "uniform" (every sample).
    tet_size, tet_grading: graded spacing: the largest spacing in world units (0 = 8 voxels) and
        its growth per voxel of distance from M (as the CLI's --tet-size, --grading).
    tet_min_dihedral_deg, tet_max_dihedral_deg: the range the tets M pins down are freed to
        (as the CLI's --tet-min-dihedral, --tet-max-dihedral; default 0 and 180: off).
    adaptive: certified adaptive meshing (coarse cells where a certificate allows; dense input).
    threads: worker threads (None = all); the mesh does not depend on it.
    certify: verify the mesh before returning it; GuaranteeViolated if it fails.
    progress: progress(stage, fraction) is called from the calling thread while the mesher runs
        (fraction in [0, 1], or -1 when the stage does not know); return False to cancel
        (Cancelled is raised). Ctrl-C cancels too (KeyboardInterrupt).
    grid: .vdb paths: the name of the grid to read (default: the first float grid).
    snap, improve_tets, facet_angle_deg, block_voxels, block_count, release_blocks, max_rounds,
        max_points: as the CLI's --snap, --no-improve-tets, --facet-angle, --blocks,
        --block-count, --release-blocks, --max-rounds, --max-points.

    Returns a Mesh (vertices, triangles, tet_vertices, tets, regions, stats, to_meshio()).
    Raises ValueError (bad input, the CLI's message), OSError (unreadable file),
    GuaranteeViolated, Cancelled, KeyboardInterrupt. The GIL is released while meshing.
    """
    args = _isodel._MeshArgs()
    args.iso = float(iso)
    args.eps_voxels = None if eps_voxels is None else float(eps_voxels)
    args.eps = None if eps is None else float(eps)
    args.inside = inside
    args.tets = tets
    args.adaptive = bool(adaptive)
    args.certify = bool(certify)
    args.snap = bool(snap)
    args.improve_tets = bool(improve_tets)
    args.tet_spacing = str(tet_spacing)
    args.tet_size = float(tet_size)
    args.tet_grading = float(tet_grading)
    args.threads = threads
    args.max_rounds = int(max_rounds)
    args.block_voxels = int(block_voxels)
    args.block_count = int(block_count)
    args.release_blocks = bool(release_blocks)
    args.max_points = int(max_points)
    args.facet_angle_deg = float(facet_angle_deg)
    args.tet_min_dihedral_deg = float(tet_min_dihedral_deg)
    args.tet_max_dihedral_deg = float(tet_max_dihedral_deg)
    raw = _isodel.mesh(_volume_arg(volume), args, _triple("spacing", spacing), _triple("origin", origin),
                       axis_order, grid, _progress_arg(progress))
    return Mesh(raw)


def verify(volume: Any, iso: float, mesh: Any, *, eps: Optional[float] = None,
           eps_voxels: Optional[float] = None, inside: Optional[str] = None,
           spacing: Sequence[float] = (1, 1, 1), origin: Sequence[float] = (0, 0, 0),
           axis_order: str = "zyx", grid: str = "", refine: int = 4, check_delaunay: bool = True,
           check_self_intersections: bool = True, strict_topology: bool = False,
           progress: Optional[ProgressCallback] = None) -> Dict[str, Any]:
    """Check a surface mesh against {F = iso} of a volume (as `isodel verify`), independently of
    the mesher: topology, Hausdorff distance (when eps or eps_voxels is given), Delaunay
    conformity, manifoldness, quality.

    volume and its keywords: as isodel.mesh. mesh: a Mesh, a (vertices, triangles) pair of arrays,
    or a path (.ply, .obj, .off, .stl). Returns the report (the CLI's --json) as a dict; its
    "passed" entry is the verdict.
    """
    if isinstance(mesh, Mesh):
        mesh = (mesh.vertices, mesh.triangles)
    elif isinstance(mesh, (str, os.PathLike)):
        mesh = os.fspath(mesh)
    else:
        mesh = tuple(mesh)
    report = _isodel.verify(_volume_arg(volume), float(iso), mesh,
                            None if eps is None else float(eps),
                            None if eps_voxels is None else float(eps_voxels), inside,
                            _triple("spacing", spacing), _triple("origin", origin), axis_order, grid,
                            int(refine), bool(check_delaunay), bool(check_self_intersections),
                            bool(strict_topology), _progress_arg(progress))
    return json.loads(report)


class VolumeData:
    """A volume read by isodel.read_volume.

    array: float32, the sample lattice in the requested axis order ("zyx": array[z, y, x]).
    spacing, origin: voxel size and world position of array sample [0,0,0], world order (x, y, z),
        so isodel.mesh(v.array, iso, spacing=v.spacing, origin=v.origin) meshes the file's samples.
    inside: the default inside side ("below" for level sets, else "above").
    format: "vdb", "mrc", "inr" or "raw".
    """

    def __init__(self, array: np.ndarray, spacing: Tuple[float, float, float],
                 origin: Tuple[float, float, float], inside: str, format: str):
        self.array = array
        self.spacing = spacing
        self.origin = origin
        self.inside = inside
        self.format = format

    def __repr__(self) -> str:
        return (f"isodel.VolumeData(shape={self.array.shape}, spacing={self.spacing}, "
                f"origin={self.origin}, format={self.format!r})")


def read_volume(path: "str | os.PathLike[str]", *, axis_order: str = "zyx", grid: str = "") -> VolumeData:
    """Read a volume file into a dense numpy array (as isodel reads it for meshing).

    Sparse .vdb grids are densified over their active bounding box: to mesh a large sparse grid,
    pass its path (or a pyopenvdb grid) to isodel.mesh instead. Files whose index-to-world map
    is sheared (some crystallographic maps) raise ValueError: mesh their path directly.
    """
    array, spacing, origin, inside, fmt = _isodel.read_volume(os.fspath(path), axis_order, grid)
    return VolumeData(array, spacing, origin, inside, fmt)


def decimate(volume: Any, output: "str | os.PathLike[str]", *, k: int, tolerance: float,
             iso: Optional[float] = None, band: float = 1.0, max_level: int = 8,
             spacing: Sequence[float] = (1, 1, 1), origin: Sequence[float] = (0, 0, 0),
             axis_order: str = "zyx", grid: str = "",
             progress: Optional[ProgressCallback] = None) -> Dict[str, Any]:
    """Coarsen a volume into an adaptive grid written to `output` (.vdb), as `isodel decimate`:
    leaves of touching cells differ by at most k levels, every replaced sample is reproduced
    within `tolerance`; with iso, cells within `band` voxels of {F = iso} stay fine. Mesh the
    file with isodel.mesh(output, iso). Returns the statistics as a dict."""
    return _isodel.decimate(_volume_arg(volume), os.fspath(output), int(k), float(tolerance),
                            None if iso is None else float(iso), float(band), int(max_level),
                            _triple("spacing", spacing), _triple("origin", origin), axis_order, grid,
                            _progress_arg(progress))


def info(volume: Any, *, spacing: Sequence[float] = (1, 1, 1), origin: Sequence[float] = (0, 0, 0),
         axis_order: str = "zyx", grid: str = "") -> Dict[str, Any]:
    """What isodel reads from a volume (as `isodel info --json`): format, grid class, default
    inside, dims, index bounding box, voxel size, value range, background, active voxels, leaf
    nodes, memory, and for isodel adaptive files their levels."""
    return _isodel.info(_volume_arg(volume), _triple("spacing", spacing), _triple("origin", origin),
                        axis_order, grid)
