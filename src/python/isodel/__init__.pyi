# Type hints for the isodel package (docs/python.md; each function's docstring is its manual).
import os
from typing import Any, Callable, Dict, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, "os.PathLike[str]"]
# A 3-d numpy array (any float or integer dtype), a volume file's path, or a pyopenvdb FloatGrid.
_Volume = Union[npt.ArrayLike, _Path, Any]
ProgressCallback = Callable[[str, float], Optional[bool]]

class GuaranteeViolated(RuntimeError): ...
class Cancelled(RuntimeError): ...

class Mesh:
    vertices: npt.NDArray[np.float64]
    triangles: npt.NDArray[np.int64]
    tet_vertices: Optional[npt.NDArray[np.float64]]
    tets: Optional[npt.NDArray[np.int64]]
    regions: Optional[npt.NDArray[np.int64]]
    stats: Dict[str, Any]
    def __init__(self, raw: Dict[str, Any]) -> None: ...
    def to_meshio(self, volume: bool = ...) -> Any: ...

class VolumeData:
    array: npt.NDArray[np.float32]
    spacing: Tuple[float, float, float]
    origin: Tuple[float, float, float]
    inside: str
    format: str
    def __init__(self, array: npt.NDArray[np.float32], spacing: Tuple[float, float, float],
                 origin: Tuple[float, float, float], inside: str, format: str) -> None: ...

def mesh(volume: _Volume, iso: float, *, eps_voxels: Optional[float] = ..., eps: Optional[float] = ...,
         inside: Optional[str] = ..., spacing: Sequence[float] = ..., origin: Sequence[float] = ...,
         axis_order: str = ..., tets: Optional[str] = ..., adaptive: bool = ...,
         threads: Optional[int] = ..., certify: bool = ..., progress: Optional[ProgressCallback] = ...,
         grid: str = ..., snap: bool = ..., improve_tets: bool = ..., facet_angle_deg: float = ...,
         block_voxels: int = ..., max_rounds: int = ..., max_points: int = ...,
         tet_spacing: str = ..., tet_size: float = ..., tet_grading: float = ...) -> Mesh: ...

def verify(volume: _Volume, iso: float,
           mesh: Union[Mesh, _Path, Tuple[npt.ArrayLike, npt.ArrayLike]], *,
           eps: Optional[float] = ..., eps_voxels: Optional[float] = ..., inside: Optional[str] = ...,
           spacing: Sequence[float] = ..., origin: Sequence[float] = ..., axis_order: str = ...,
           grid: str = ..., refine: int = ..., check_delaunay: bool = ...,
           check_self_intersections: bool = ..., strict_topology: bool = ...,
           progress: Optional[ProgressCallback] = ...) -> Dict[str, Any]: ...

def read_volume(path: _Path, *, axis_order: str = ..., grid: str = ...) -> VolumeData: ...

def decimate(volume: _Volume, output: _Path, *, k: int, tolerance: float, iso: Optional[float] = ...,
             band: float = ..., max_level: int = ..., spacing: Sequence[float] = ...,
             origin: Sequence[float] = ..., axis_order: str = ..., grid: str = ...,
             progress: Optional[ProgressCallback] = ...) -> Dict[str, Any]: ...

def info(volume: _Volume, *, spacing: Sequence[float] = ..., origin: Sequence[float] = ...,
         axis_order: str = ..., grid: str = ...) -> Dict[str, Any]: ...
