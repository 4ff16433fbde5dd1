// DELSURFMESH (paper Fig. 3), the data flow visible top-down:
//   samples --edge_crossings--> E,  crossed cells --protective_layer--> G   (seeding/)
//   Del(E u G)                                                              (delaunay/)
//   --closed ball checks, then eps refinement--> Del(E u G u N)             (surface/refiner.h)
//   its restricted facets: M                                                (surface_extraction.h)
//   optionally, DELVOLMESH's tetrahedra                                     (volume/)
// On an adaptive grid the same flow runs with E on leaf edges and G from the leaves
// (seeding/adaptive_points.h), F read through the grid's exact resampling. The public entry
// points (and --certify) are mesh_isosurface.cpp.
#include "surface/stage_clock.h"
#include "surface/mesh_field.h"
#include "surface/thread_limit.h"

#include "delaunay/initial_delaunay.h"
#include "seeding/initial_points.h"
#include "surface/refiner.h"
#include "surface/surface_extraction.h"
#include "volume/volume_mesh.h"

#include <isodel/errors.h>
#include <isodel/mesh.h>


#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

namespace isodel {
using namespace mesher;
namespace {

using Clock = std::chrono::steady_clock;

std::size_t peak_memory_bytes()
{
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    return std::size_t(ru.ru_maxrss) * 1024;
}

} // namespace

namespace mesher {

Inside inside_side(const openvdb::FloatGrid& grid, const MeshOptions& options)
{
    if (options.inside) return *options.inside;
    return default_inside(grid);
}

namespace {

/// Block mode (FieldRun::inserted): the N points the loops inserted, in insertion order.
void collect_block_points(const Delaunay& dt, std::uint32_t first_inserted, std::vector<SeedPoint>& out)
{
    std::vector<std::pair<std::uint32_t, SeedPoint>> n;
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
        const PointKind k = v->info().kind;
        if (v->info().id >= first_inserted && (k == PointKind::Topology || k == PointKind::Geometry))
            n.push_back({v->info().id, SeedPoint{{v->point().x(), v->point().y(), v->point().z()}, k}});
    }
    std::sort(n.begin(), n.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [id, p] : n) out.push_back(p);
}

/// Every vertex of \p dt, world coordinates, in id order (FieldRun::final_points).
std::vector<std::array<double, 3>> all_points(const Delaunay& dt)
{
    std::vector<std::pair<std::uint32_t, Point>> all;
    all.reserve(dt.number_of_vertices());
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) all.emplace_back(v->info().id, v->point());
    std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<std::array<double, 3>> out;
    out.reserve(all.size());
    for (const auto& [id, p] : all) out.push_back({p.x(), p.y(), p.z()});
    return out;
}

} // namespace

MeshResult mesh_field(const FieldRun& run, const MeshOptions& options, Interrupter* interrupter)
{
    const auto t_start = Clock::now();
    MeshResult result;
    MeshStats& st = result.stats;
    check_mesh_options(options);
    const ThreadLimit threads(options.threads);

    const octree::AdaptiveGrid* adaptive = run.adaptive;
    st.effective_isovalue = run.field->effective_isovalue();
    std::unique_ptr<octree::AdaptiveGrid::Reader> leaves;
    if (adaptive) leaves = std::make_unique<octree::AdaptiveGrid::Reader>(*adaptive);
    const double eps_user = options.eps > 0 ? options.eps : options.eps_voxels * run.field->min_voxel_edge();
    st.eps_world = eps_user;
    // The surface meshed is Sigma' (octree/face_slabs.h): slabs around the grid planes blunt
    // the knife-edge creases, and M within eps - slab_shift of Sigma' keeps Sigma within eps of M.
    octree::SampleField field = *run.field;
    field.set_face_slabs(field.face_slabs_for_eps_world(eps_user));
    const double slab_shift = field.face_slab_shift();
    const double eps = eps_user - slab_shift;
    const double snap_radius = options.snap ? 0.5 * eps : 0.0; // snap_edge_points.h: eps / 2

    // Steps 1-2: E and G (initial_points.h).
    auto t0 = Clock::now();
    InitialPoints ip = initial_points(field, adaptive, leaves.get(), options.snap, snap_radius, run.seeds, st, interrupter);
    st.seconds["points"] = seconds_since(t0);
    if (st.e_points == 0 && run.inserted) return result; // a block Sigma misses
    if (st.e_points == 0) throw InvalidInput("the level set is empty: no grid edge crosses the isovalue");

    // Step 3: Del(E u G), spatially sorted insertion.
    t0 = Clock::now();
    Delaunay dt;
    {
        InterruptScope scope(interrupter, "delaunay");
        build_initial_delaunay(dt, ip.points, &scope);
        scope.check(100);
    }
    const auto first_inserted = std::uint32_t(ip.points.size());
    ip.points.clear();
    ip.points.shrink_to_fit();
    st.seconds["delaunay"] = seconds_since(t0);

    // Steps 4-5: the closed ball property, then eps refinement (refiner.h).
    RefinerInput in;
    in.field = &field;
    in.adaptive = adaptive;
    in.leaves = leaves.get();
    in.g_mask = &ip.g_mask;
    in.layer_radius = {{ip.layer.radius[0], ip.layer.radius[1], ip.layer.radius[2]}};
    in.eps = eps;
    // A snapped grid point is within snap_radius of Sigma, and Sigma' within slab_shift of it.
    in.snap_radius = snap_radius + slab_shift;
    in.slab_h_world = field.face_slabs().h * field.min_voxel_edge();
    in.keep = run.keep;
    Refiner refiner(dt, in, std::move(ip.crossed_cells), options, st, first_inserted, interrupter);
    t0 = Clock::now();
    refiner.measure_voxel_bound();
    st.seconds["voxel_bound"] = seconds_since(t0);
    const std::size_t n_before_loops = st.n_topology + st.n_geometry;
    refiner.run(run.inserted != nullptr);
    if (!run.seeds.empty()) st.partition.seam_points = st.n_topology + st.n_geometry - n_before_loops;
    if (run.inserted) {
        collect_block_points(dt, first_inserted, *run.inserted);
        st.seconds["total"] = seconds_since(t_start);
        return result;
    }

    // Step 6: M, the restricted Delaunay surface.
    const auto t_extract = Clock::now();
    result.surface = extract_surface(dt, refiner.cache());
    if (run.final_points) *run.final_points = all_points(dt);
    st.vertices = result.surface.vertices.size();
    st.triangles = result.surface.triangles.size();
    st.components = surface_topology(result.surface);
    st.seconds["extract"] = seconds_since(t_extract);
    if (options.tets != TetRegion::None) {
        // DELVOLMESH (Section 4.1): fill the region(s) with G', keeping M (src/volume/volume_mesh.h).
        t0 = Clock::now();
        std::uint32_t next_id = refiner.next_id();
        VolumeMeshParams vp;
        vp.region = options.tets;
        vp.max_cells_walk = refiner.max_cells_walk();
        vp.next_id = &next_id;
        vp.interrupter = interrupter;
        vp.adaptive = leaves.get();
        vp.improve = options.improve_tets;
        GradedSpacing spacing{options.tet_grading, graded_max_level(options.tet_size, field.min_voxel_edge())};
        if (options.tet_spacing == TetSpacing::Graded) vp.spacing = &spacing;
        result.tets = build_volume_mesh(dt, refiner.cache(), field, ip.g_mask.get(), result.surface, vp, st.tets);
        st.seconds["tets"] = seconds_since(t0);
    }
    st.seconds["total"] = seconds_since(t_start);
    st.peak_memory_bytes = peak_memory_bytes();
    return result;
}

} // namespace mesher
} // namespace isodel
