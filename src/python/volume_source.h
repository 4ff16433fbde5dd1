#pragma once
// The volume a Python call names (a numpy array, a file path or a pyopenvdb FloatGrid), captured
// as plain C++ data while the GIL is held, then loaded into an isodel::Volume on the worker thread
// (released_call.h) so reading and converting happen with the GIL released too.
#include <isodel/volume.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <cstdint>
#include <string>

// Hidden, as pybind11's own types: nothing here is part of a C++ API.
namespace isodel {
namespace python __attribute__((visibility("hidden"))) {

namespace py = pybind11;

struct VolumeSource {
    enum class Kind { Path, Array, Grid } kind = Kind::Path;
    std::string path;           ///< Kind::Path
    std::string grid_name;      ///< Kind::Path, .vdb: the grid to read
    /// Kind::Array: the numpy buffer, read in place (the caller keeps `array` alive).
    py::array array;
    const char* data = nullptr;
    std::array<std::int64_t, 3> shape{0, 0, 0}, strides{0, 0, 0};
    char dtype_kind = 'f';
    int itemsize = 4;
    bool zyx = true;            ///< array index [z,y,x] -> OpenVDB index (x,y,z)
    std::array<double, 3> spacing{1, 1, 1}, origin{0, 0, 0}; ///< world x, y, z
    openvdb::FloatGrid::Ptr grid; ///< Kind::Grid: shared with the Python object, never copied
};

/// Captures \p volume (GIL held). Refuses wrong dimensions, empty arrays, unsupported dtypes and
/// bad spacing/origin/axis_order with isodel::InvalidInput naming the argument.
VolumeSource capture_volume(const py::object& volume, const std::array<double, 3>& spacing,
                            const std::array<double, 3>& origin, const std::string& axis_order,
                            const std::string& grid_name);

/// Reads or converts the captured volume (no GIL needed): every array sample an active voxel,
/// value range computed, non-finite samples refused (InvalidInput naming the index).
Volume load_volume(const VolumeSource& source);

/// The name used in messages: the path, or "volume" for arrays and grids.
std::string source_name(const VolumeSource& source);

/// A dense numpy copy of \p vol's lattice in \p axis_order ("zyx" or "xyz"), float32.
py::array_t<float> lattice_to_numpy(const Volume& vol, bool zyx);

} // namespace python
} // namespace isodel
