// _isodel: the compiled half of the Python package (src/python/isodel/ is the other half, which
// documents and type-checks the calls and shapes the results). Every long call runs with the GIL
// released (released_call.h); errors map to Python exceptions as the CLI maps them to exit codes.
#include "released_call.h"
#include "volume_source.h"

#include <isodel/adaptive.h>
#include <isodel/errors.h>
#include <isodel/mesh.h>
#include <isodel/surface_mesh.h>
#include <isodel/verify.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>

namespace py = pybind11;
using namespace isodel;
using isodel::python::VolumeSource;

namespace {

template <class T, std::size_t N>
py::array_t<T> to_numpy(const std::vector<std::array<double, N>>& rows)
{
    py::array_t<T> out({py::ssize_t(rows.size()), py::ssize_t(N)});
    T* p = out.mutable_data();
    for (const auto& r : rows)
        for (std::size_t c = 0; c < N; ++c) *p++ = T(r[c]);
    return out;
}

template <class T, std::size_t N>
py::array_t<T> to_numpy(const std::vector<std::array<std::int32_t, N>>& rows)
{
    py::array_t<T> out({py::ssize_t(rows.size()), py::ssize_t(N)});
    T* p = out.mutable_data();
    for (const auto& r : rows)
        for (std::size_t c = 0; c < N; ++c) *p++ = T(r[c]);
    return out;
}

std::optional<Inside> parse_inside(const std::optional<std::string>& inside)
{
    if (!inside) return std::nullopt;
    if (*inside == "above") return Inside::Above;
    if (*inside == "below") return Inside::Below;
    throw InvalidInput("inside: '" + *inside + "' is not \"above\" or \"below\"");
}

TetRegion parse_tets(const std::optional<std::string>& tets)
{
    if (!tets) return TetRegion::None;
    if (*tets == "inside") return TetRegion::Inside;
    if (*tets == "outside") return TetRegion::Outside;
    if (*tets == "both") return TetRegion::Both;
    throw InvalidInput("tets: '" + *tets + "' is not None, \"inside\", \"outside\" or \"both\"");
}

struct MeshArgs {
    double iso = 0;
    std::optional<double> eps_voxels, eps;
    std::optional<std::string> inside, tets;
    std::string tet_spacing = "graded";
    double tet_size = 0, tet_grading = 0.5;
    bool adaptive = false, certify = false, snap = false, improve_tets = true, release_blocks = false;
    std::optional<int> threads;
    int max_rounds = 2000, block_voxels = 0, block_count = 0;
    std::size_t max_points = 0;
    double facet_angle_deg = 0;
    double tet_min_dihedral_deg = 0, tet_max_dihedral_deg = 180;
};

MeshOptions mesh_options(const MeshArgs& a)
{
    if (a.eps && a.eps_voxels) throw InvalidInput("eps and eps_voxels: give one bound, not both");
    MeshOptions mo;
    mo.isovalue = a.iso;
    if (a.eps) mo.eps = *a.eps;
    if (a.eps_voxels) mo.eps_voxels = *a.eps_voxels;
    // eps = 0 means "use eps_voxels" in MeshOptions; from Python it is a mistake.
    if (a.eps && !(*a.eps > 0)) throw InvalidInput("eps must be positive and finite (got " + py::str(py::float_(*a.eps)).cast<std::string>() + ")");
    mo.threads = a.threads.value_or(0);
    mo.max_rounds = a.max_rounds;
    mo.max_points = a.max_points;
    mo.snap = a.snap;
    mo.certify = a.certify;
    mo.block_voxels = a.block_voxels;
    mo.block_count = a.block_count;
    mo.release_blocks = a.release_blocks;
    mo.tets = parse_tets(a.tets);
    mo.improve_tets = a.improve_tets;
    if (a.tet_spacing != "graded" && a.tet_spacing != "uniform")
        throw InvalidInput("tet_spacing: '" + a.tet_spacing + "' is not \"graded\" or \"uniform\"");
    mo.tet_spacing = a.tet_spacing == "uniform" ? TetSpacing::Uniform : TetSpacing::Graded;
    mo.tet_size = a.tet_size;
    mo.tet_grading = a.tet_grading;
    mo.facet_angle_deg = a.facet_angle_deg;
    mo.tet_min_dihedral_deg = a.tet_min_dihedral_deg;
    mo.tet_max_dihedral_deg = a.tet_max_dihedral_deg;
    mo.adaptive = a.adaptive;
    check_mesh_options(mo); // before any work, with the CLI's messages
    return mo;
}

py::dict mesh(const py::object& volume, const MeshArgs& args, const std::array<double, 3>& spacing,
              const std::array<double, 3>& origin, const std::string& axis_order, const std::string& grid,
              const py::object& progress)
{
    MeshOptions mo = mesh_options(args);
    const auto inside = parse_inside(args.inside);
    const VolumeSource source = python::capture_volume(volume, spacing, origin, axis_order, grid);
    MeshResult res = python::released_call(
        [&](Interrupter* intr) {
            const Volume vol = [&] {
                InterruptScope scope(intr, "read");
                return python::load_volume(source);
            }();
            check_isovalue(vol, mo.isovalue);
            mo.inside = inside ? *inside : vol.default_inside;
            if (vol.adaptive_levels > 1 && mo.adaptive)
                throw InvalidInput(vol.path + ": adaptive=True needs the original volume, and this file is adaptive "
                                   "already (isodel decimate); mesh it with adaptive=False, or mesh the original");
            try {
                return vol.adaptive_levels > 1 ? mesh_isosurface(load_adaptive(vol.path), mo, intr)
                                               : mesh_isosurface(*vol.grid, mo, intr);
            } catch (const GuaranteeViolated& e) {
                throw GuaranteeViolated(python::source_name(source) + ": " + e.what()); // as the CLI
            }
        },
        progress);
    py::dict out;
    out["vertices"] = to_numpy<double>(res.surface.vertices);
    out["triangles"] = to_numpy<std::int64_t>(res.surface.triangles);
    if (mo.tets != TetRegion::None) {
        out["tet_vertices"] = to_numpy<double>(res.tets.vertices);
        out["tets"] = to_numpy<std::int64_t>(res.tets.tets);
        py::array_t<std::int64_t> regions(py::ssize_t(res.tets.tet_region.size()));
        for (std::size_t i = 0; i < res.tets.tet_region.size(); ++i) regions.mutable_at(i) = res.tets.tet_region[i];
        out["regions"] = regions;
    }
    out["stats_json"] = to_json(res.stats);
    return out;
}

SurfaceMesh surface_from_arrays(const py::array_t<double, py::array::c_style | py::array::forcecast>& v,
                                const py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>& t)
{
    if (v.ndim() != 2 || v.shape(1) != 3) throw InvalidInput("vertices: expected an n x 3 array");
    if (t.ndim() != 2 || t.shape(1) != 3) throw InvalidInput("triangles: expected an m x 3 array");
    SurfaceMesh m;
    m.vertices.resize(v.shape(0));
    for (py::ssize_t i = 0; i < v.shape(0); ++i) m.vertices[i] = {v.at(i, 0), v.at(i, 1), v.at(i, 2)};
    m.triangles.resize(t.shape(0));
    for (py::ssize_t i = 0; i < t.shape(0); ++i)
        for (int c = 0; c < 3; ++c) {
            const std::int64_t k = t.at(i, c);
            if (k < 0 || k >= v.shape(0))
                throw InvalidInput("triangles: index " + std::to_string(k) + " in row " + std::to_string(i) +
                                   " is not a vertex (" + std::to_string(v.shape(0)) + " vertices)");
            m.triangles[i][c] = std::int32_t(k);
        }
    return m;
}

std::string verify(const py::object& volume, double iso, const py::object& mesh, std::optional<double> eps,
                   std::optional<double> eps_voxels, const std::optional<std::string>& inside_word,
                   const std::array<double, 3>& spacing, const std::array<double, 3>& origin,
                   const std::string& axis_order, const std::string& grid, int refine, bool check_delaunay,
                   bool check_self_intersections, bool strict_topology, const py::object& progress)
{
    VerifyOptions opt;
    opt.isovalue = iso;
    opt.eps = eps.value_or(0);
    opt.eps_voxels = eps_voxels.value_or(0);
    opt.refine = refine;
    opt.check_delaunay = check_delaunay;
    opt.check_self_intersections = check_self_intersections;
    opt.require_determined_topology = strict_topology;
    const auto inside = parse_inside(inside_word);
    std::optional<std::string> mesh_path;
    SurfaceMesh surface;
    if (py::isinstance<py::str>(mesh)) mesh_path = mesh.cast<std::string>();
    else {
        const py::tuple vt = mesh.cast<py::tuple>();
        if (vt.size() != 2) throw InvalidInput("mesh: expected a path or (vertices, triangles)");
        surface = surface_from_arrays(vt[0].cast<py::array_t<double, py::array::c_style | py::array::forcecast>>(),
                                     vt[1].cast<py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>>());
    }
    const VolumeSource source = python::capture_volume(volume, spacing, origin, axis_order, grid);
    const VerifyReport rep = python::released_call(
        [&](Interrupter* intr) {
            InterruptScope scope(intr, "verify");
            const Volume vol = python::load_volume(source);
            const SurfaceMesh m = mesh_path ? read_surface_mesh(*mesh_path) : surface;
            opt.inside = inside ? *inside : vol.default_inside;
            return verify_surface(*vol.grid, m, opt);
        },
        progress);
    return rep.to_json();
}

py::tuple read_file(const std::string& path, const std::string& axis_order, const std::string& grid)
{
    if (axis_order != "zyx" && axis_order != "xyz")
        throw InvalidInput("axis_order: '" + axis_order + "' is not \"zyx\" or \"xyz\"");
    VolumeSource source;
    source.path = path;
    source.grid_name = grid;
    const Volume vol = python::released_call([&](Interrupter*) { return python::load_volume(source); }, py::none());
    const auto& xf = vol.grid->transform();
    const openvdb::math::Mat4d mat = xf.baseMap()->getAffineMap()->getMat4();
    bool axis_aligned = xf.isLinear();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) axis_aligned = axis_aligned && (r == c || mat(r, c) == 0);
    if (!axis_aligned)
        throw InvalidInput(path + ": its index-to-world map is not an axis-aligned scale and translation; "
                                  "pass the path to isodel.mesh instead of the array");
    const openvdb::Vec3d voxel = xf.voxelSize(), origin = xf.indexToWorld(vol.lattice.min());
    return py::make_tuple(python::lattice_to_numpy(vol, axis_order == "zyx"),
                          py::make_tuple(voxel[0], voxel[1], voxel[2]), py::make_tuple(origin[0], origin[1], origin[2]),
                          to_string(vol.default_inside), vol.format);
}

py::dict decimate_volume(const py::object& volume, const std::string& output, int k, double tolerance,
                         std::optional<double> iso, double band, int max_level, const std::array<double, 3>& spacing,
                         const std::array<double, 3>& origin, const std::string& axis_order,
                         const std::string& grid, const py::object& progress)
{
    DecimateOptions opt;
    opt.k = k;
    opt.tolerance = tolerance;
    opt.iso = iso;
    opt.band = band;
    opt.max_level = max_level;
    const VolumeSource source = python::capture_volume(volume, spacing, origin, axis_order, grid);
    opt.source = python::source_name(source);
    const DecimateResult r = python::released_call(
        [&](Interrupter* intr) {
            const Volume vol = python::load_volume(source);
            DecimateResult res = isodel::decimate(*vol.grid, opt, intr);
            save_adaptive(output, res.volume);
            return res;
        },
        progress);
    py::dict d;
    d["cells_before"] = r.cells_before;
    d["cells_after"] = r.cells_after;
    d["memory_before"] = r.memory_before;
    d["memory_after"] = r.memory_after;
    d["leaves_per_level"] = r.histogram;
    d["max_error"] = r.max_error;
    d["max_level_difference"] = r.max_level_difference;
    d["seconds"] = r.seconds;
    return d;
}

py::dict info(const py::object& volume, const std::array<double, 3>& spacing, const std::array<double, 3>& origin,
              const std::string& axis_order, const std::string& grid)
{
    const VolumeSource source = python::capture_volume(volume, spacing, origin, axis_order, grid);
    const Volume vol = python::released_call([&](Interrupter*) { return python::load_volume(source); }, py::none());
    auto ijk = [](const openvdb::Coord& c) { return py::make_tuple(c.x(), c.y(), c.z()); };
    const auto& xf = vol.grid->transform();
    const openvdb::Vec3d voxel = xf.voxelSize();
    py::dict d;
    d["file"] = vol.path;
    d["format"] = vol.format;
    d["grid_name"] = vol.grid->getName();
    d["grid_class"] = openvdb::GridBase::gridClassToString(vol.grid->getGridClass());
    d["default_inside"] = to_string(vol.default_inside);
    d["dims"] = ijk(vol.lattice.dim());
    d["index_bbox"] = py::make_tuple(ijk(vol.lattice.min()), ijk(vol.lattice.max()));
    d["voxel_size"] = py::make_tuple(voxel[0], voxel[1], voxel[2]);
    d["value_range"] = py::make_tuple(double(vol.value_min), double(vol.value_max));
    d["background"] = double(vol.grid->background());
    d["active_voxels"] = vol.grid->activeVoxelCount();
    d["leaf_nodes"] = vol.grid->tree().leafCount();
    d["memory_bytes"] = vol.grid->memUsage();
    if (source.kind == VolumeSource::Kind::Path)
        if (const auto a = adaptive_info(vol.path))
            d["adaptive"] = py::dict(py::arg("levels") = a->levels, py::arg("k") = a->k,
                                     py::arg("leaves_per_level") = a->histogram, py::arg("source") = a->source);
    return d;
}

} // namespace

PYBIND11_MODULE(_isodel, m)
{
    m.doc() = "Compiled core of the isodel package; use the functions of `isodel` instead.";
    openvdb::initialize();
#ifdef ISODEL_WITH_PYOPENVDB
    // A pyopenvdb grid can only be recognised once pyopenvdb registered its converters; importing
    // it is cheap and optional.
    try {
        py::module_::import("pyopenvdb");
    } catch (py::error_already_set&) {
    }
#endif
    static py::exception<GuaranteeViolated> guarantee(m, "GuaranteeViolated", PyExc_RuntimeError);
    static py::exception<Cancelled> cancelled(m, "Cancelled", PyExc_RuntimeError);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const GuaranteeViolated& e) {
            guarantee(e.what());
        } catch (const Cancelled& e) {
            cancelled(e.what());
        } catch (const InvalidInput& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const IoError& e) {
            PyErr_SetString(PyExc_OSError, e.what());
        } catch (const openvdb::IoError& e) {
            PyErr_SetString(PyExc_OSError, e.what());
        } catch (const openvdb::Exception& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        }
    });

    py::class_<MeshArgs>(m, "_MeshArgs")
        .def(py::init<>())
        .def_readwrite("iso", &MeshArgs::iso)
        .def_readwrite("eps_voxels", &MeshArgs::eps_voxels)
        .def_readwrite("eps", &MeshArgs::eps)
        .def_readwrite("inside", &MeshArgs::inside)
        .def_readwrite("tets", &MeshArgs::tets)
        .def_readwrite("adaptive", &MeshArgs::adaptive)
        .def_readwrite("certify", &MeshArgs::certify)
        .def_readwrite("snap", &MeshArgs::snap)
        .def_readwrite("improve_tets", &MeshArgs::improve_tets)
        .def_readwrite("tet_spacing", &MeshArgs::tet_spacing)
        .def_readwrite("tet_size", &MeshArgs::tet_size)
        .def_readwrite("tet_grading", &MeshArgs::tet_grading)
        .def_readwrite("threads", &MeshArgs::threads)
        .def_readwrite("max_rounds", &MeshArgs::max_rounds)
        .def_readwrite("block_voxels", &MeshArgs::block_voxels)
        .def_readwrite("block_count", &MeshArgs::block_count)
        .def_readwrite("release_blocks", &MeshArgs::release_blocks)
        .def_readwrite("max_points", &MeshArgs::max_points)
        .def_readwrite("facet_angle_deg", &MeshArgs::facet_angle_deg)
        .def_readwrite("tet_min_dihedral_deg", &MeshArgs::tet_min_dihedral_deg)
        .def_readwrite("tet_max_dihedral_deg", &MeshArgs::tet_max_dihedral_deg);
    m.def("mesh", &mesh, py::arg("volume"), py::arg("args"), py::arg("spacing"), py::arg("origin"),
          py::arg("axis_order"), py::arg("grid"), py::arg("progress"));
    m.def("verify", &verify, py::arg("volume"), py::arg("iso"), py::arg("mesh"), py::arg("eps"),
          py::arg("eps_voxels"), py::arg("inside"), py::arg("spacing"), py::arg("origin"), py::arg("axis_order"),
          py::arg("grid"), py::arg("refine"), py::arg("check_delaunay"), py::arg("check_self_intersections"),
          py::arg("strict_topology"), py::arg("progress"));
    m.def("read_volume", &read_file, py::arg("path"), py::arg("axis_order"), py::arg("grid"));
    m.def("decimate", &decimate_volume, py::arg("volume"), py::arg("output"), py::arg("k"), py::arg("tolerance"),
          py::arg("iso"), py::arg("band"), py::arg("max_level"), py::arg("spacing"), py::arg("origin"),
          py::arg("axis_order"), py::arg("grid"), py::arg("progress"));
    m.def("info", &info, py::arg("volume"), py::arg("spacing"), py::arg("origin"), py::arg("axis_order"),
          py::arg("grid"));
}
