#include "volume_source.h"

#include "io/dense_volume.h" // finish_volume: the same lattice, range and finiteness checks as the readers

#include <isodel/errors.h>

#ifdef ISODEL_WITH_PYOPENVDB
#include <boost/python.hpp>
#endif

#include <climits>
#include <cmath>
#include <cstring>
#include <sstream>

namespace isodel::python {
namespace {

const char* const kArrayName = "volume";

[[noreturn]] void refuse(const std::string& what) { throw InvalidInput(std::string(kArrayName) + ": " + what); }

std::string shape_text(const py::array& a)
{
    std::ostringstream s;
    s << "(";
    for (py::ssize_t d = 0; d < a.ndim(); ++d) s << (d ? ", " : "") << a.shape(d);
    s << (a.ndim() == 1 ? ",)" : ")");
    return s.str();
}

/// Copies the samples straight from the numpy buffer into the grid, converting each value:
/// no intermediate dense copy. Loops in array order, so the buffer is read sequentially.
template <class T>
void fill_grid(const VolumeSource& s, openvdb::FloatGrid& grid)
{
    auto acc = grid.getAccessor();
    openvdb::Coord ijk;
    for (std::int64_t a = 0; a < s.shape[0]; ++a)
        for (std::int64_t b = 0; b < s.shape[1]; ++b) {
            const char* row = s.data + a * s.strides[0] + b * s.strides[1];
            for (std::int64_t c = 0; c < s.shape[2]; ++c) {
                T value;
                std::memcpy(&value, row + c * s.strides[2], sizeof(T)); // unaligned views are legal in numpy
                if (s.zyx) ijk.reset(int(c), int(b), int(a));
                else ijk.reset(int(a), int(b), int(c));
                // setValue() marks every sample active, as the dense file readers do.
                acc.setValue(ijk, static_cast<float>(value));
            }
        }
}

void fill_from_array(const VolumeSource& s, openvdb::FloatGrid& grid)
{
    switch (s.dtype_kind) {
    case 'f':
        if (s.itemsize == 4) return fill_grid<float>(s, grid);
        if (s.itemsize == 8) return fill_grid<double>(s, grid);
        if (s.itemsize == sizeof(long double)) return fill_grid<long double>(s, grid);
        break;
    case 'i':
        if (s.itemsize == 1) return fill_grid<std::int8_t>(s, grid);
        if (s.itemsize == 2) return fill_grid<std::int16_t>(s, grid);
        if (s.itemsize == 4) return fill_grid<std::int32_t>(s, grid);
        if (s.itemsize == 8) return fill_grid<std::int64_t>(s, grid);
        break;
    case 'u':
    case 'b':
        if (s.itemsize == 1) return fill_grid<std::uint8_t>(s, grid);
        if (s.itemsize == 2) return fill_grid<std::uint16_t>(s, grid);
        if (s.itemsize == 4) return fill_grid<std::uint32_t>(s, grid);
        if (s.itemsize == 8) return fill_grid<std::uint64_t>(s, grid);
        break;
    }
    refuse("unsupported dtype"); // capture_volume refused it already
}

bool is_pyopenvdb_grid(const py::object& o)
{
    const py::handle type = py::type::handle_of(o);
    return py::hasattr(type, "__module__") && py::str(type.attr("__module__")).cast<std::string>() == "pyopenvdb";
}

openvdb::FloatGrid::Ptr extract_grid(const py::object& o)
{
#ifdef ISODEL_WITH_PYOPENVDB
    // pyopenvdb registers its grid converters in boost.python's registry, shared by every
    // extension that links the same libboost_python: the FloatGrid is shared, not copied.
    namespace bp = boost::python;
    bp::object obj{bp::handle<>(bp::borrowed(o.ptr()))};
    bp::extract<openvdb::FloatGrid::Ptr> grid(obj);
    if (grid.check()) return grid();
    refuse("a pyopenvdb grid of type " + py::str(py::type::handle_of(o).attr("__name__")).cast<std::string>() +
           "; only FloatGrid is meshed");
#else
    (void)o;
    refuse("this isodel was built without pyopenvdb support (libboost-python-dev was not found)");
#endif
}

} // namespace

VolumeSource capture_volume(const py::object& volume, const std::array<double, 3>& spacing,
                            const std::array<double, 3>& origin, const std::string& axis_order,
                            const std::string& grid_name)
{
    VolumeSource s;
    if (py::isinstance<py::str>(volume)) {
        s.kind = VolumeSource::Kind::Path;
        s.path = volume.cast<std::string>();
        s.grid_name = grid_name;
        return s;
    }
    if (is_pyopenvdb_grid(volume)) {
        s.kind = VolumeSource::Kind::Grid;
        s.grid = extract_grid(volume);
        return s;
    }
    if (!py::isinstance<py::array>(volume)) refuse("expected a numpy array, a path or a pyopenvdb FloatGrid");
    s.kind = VolumeSource::Kind::Array;
    s.array = py::reinterpret_borrow<py::array>(volume);
    const py::array& a = s.array;
    if (a.ndim() != 3)
        refuse("expected a 3-d array, got " + std::to_string(a.ndim()) + " dimension(s), shape " + shape_text(a));
    if (a.size() == 0) refuse("empty array, shape " + shape_text(a));
    for (int d = 0; d < 3; ++d) {
        if (a.shape(d) > INT_MAX) refuse("axis " + std::to_string(d) + " is longer than OpenVDB's index range");
        s.shape[d] = a.shape(d);
        s.strides[d] = a.strides(d);
    }
    const py::dtype dt = a.dtype();
    s.dtype_kind = dt.kind();
    s.itemsize = int(dt.itemsize());
    const bool native = dt.attr("byteorder").cast<std::string>() != (io::host_is_little_endian() ? ">" : "<");
    const bool float_size = s.itemsize == 4 || s.itemsize == 8 || s.itemsize == int(sizeof(long double));
    if (std::string("fiub").find(s.dtype_kind) == std::string::npos || !native ||
        (s.dtype_kind == 'f' && !float_size))
        refuse("unsupported dtype " + dt.attr("name").cast<std::string>() + " (use a native float32/float64 or integer dtype)");
    s.data = static_cast<const char*>(a.data());
    if (axis_order != "zyx" && axis_order != "xyz")
        throw InvalidInput("axis_order: '" + axis_order + "' is not \"zyx\" or \"xyz\"");
    s.zyx = axis_order == "zyx";
    for (int d = 0; d < 3; ++d) {
        if (!(std::isfinite(spacing[d]) && spacing[d] > 0))
            throw InvalidInput("spacing: " + std::to_string(spacing[d]) + " is not a positive finite voxel size");
        if (!std::isfinite(origin[d])) throw InvalidInput("origin: non-finite coordinate");
    }
    s.spacing = spacing;
    s.origin = origin;
    return s;
}

Volume load_volume(const VolumeSource& s)
{
    if (s.kind == VolumeSource::Kind::Path) {
        ReadOptions opt;
        opt.grid_name = s.grid_name;
        return read_volume(s.path, opt);
    }
    Volume vol;
    vol.path = kArrayName;
    if (s.kind == VolumeSource::Kind::Grid) {
        vol.format = "vdb";
        vol.grid = s.grid;
    } else {
        vol.format = "array";
        vol.grid = openvdb::FloatGrid::create(0.0f);
        vol.grid->setName("density");
        // The transform an orthogonal MRC map gets (src/io/read_mrc.cpp), so an array and the
        // same samples in a file mesh identically.
        const openvdb::Vec3d step(s.spacing[0], s.spacing[1], s.spacing[2]);
        const openvdb::Vec3d t(s.origin[0], s.origin[1], s.origin[2]);
        vol.grid->setTransform(openvdb::math::Transform::Ptr(new openvdb::math::Transform(
            openvdb::math::MapBase::Ptr(new openvdb::math::ScaleTranslateMap(step, t)))));
        fill_from_array(s, *vol.grid);
    }
    vol.default_inside = default_inside(*vol.grid);
    io::finish_volume(vol);
    return vol;
}

std::string source_name(const VolumeSource& s) { return s.kind == VolumeSource::Kind::Path ? s.path : kArrayName; }

py::array_t<float> lattice_to_numpy(const Volume& vol, bool zyx)
{
    const openvdb::Coord lo = vol.lattice.min(), dim = vol.lattice.dim();
    std::vector<py::ssize_t> shape = zyx ? std::vector<py::ssize_t>{dim.z(), dim.y(), dim.x()}
                                         : std::vector<py::ssize_t>{dim.x(), dim.y(), dim.z()};
    py::array_t<float> out(shape);
    float* p = out.mutable_data();
    auto acc = vol.grid->getConstAccessor();
    std::size_t n = 0;
    for (py::ssize_t a = 0; a < shape[0]; ++a)
        for (py::ssize_t b = 0; b < shape[1]; ++b)
            for (py::ssize_t c = 0; c < shape[2]; ++c, ++n) {
                const openvdb::Coord ijk = zyx ? openvdb::Coord(int(c), int(b), int(a)) : openvdb::Coord(int(a), int(b), int(c));
                p[n] = acc.getValue(lo + ijk);
            }
    return out;
}

} // namespace isodel::python
