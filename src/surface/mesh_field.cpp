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

#include "surface/refiner.h"
#include "surface/surface_pipeline.h"
#include "surface/surface_extraction.h"
#include "refinement/surface_slivers.h"
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

} // namespace

namespace mesher {

std::size_t peak_memory_bytes()
{
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    return std::size_t(ru.ru_maxrss) * 1024;
}

Inside inside_side(const openvdb::FloatGrid& grid, const MeshOptions& options)
{
    if (options.inside) return *options.inside;
    return default_inside(grid);
}

namespace {

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

namespace {

/// Runs of the pipeline after the first against the bad tets M pins down: each frees the tets
/// of the previous one and may pin others (MeshStats::tet_sliver_stop).
constexpr int kMaxSliverRuns = 3;

/// One run of the pipeline. With tets and a dihedral range, \p next_seeds receives the seeds of
/// the next run when M pins bad tets down (refinement/surface_slivers.h): every N point of this
/// run and the surface points that free them. Empty when there are none.
MeshResult mesh_field_once(const FieldRun& run, const MeshOptions& options, Interrupter* interrupter,
                           std::vector<SeedPoint>& next_seeds, std::size_t& fresh)
{
    const auto t_start = Clock::now();
    MeshResult result;
    MeshStats& st = result.stats;
    st.effective_isovalue = run.field->effective_isovalue();

    // Steps 1-3: E, G, Del(E u G) (surface_pipeline.h).
    SurfacePipeline pipeline(run, options, CandidateFilter(), CandidateFilter(), st, interrupter);
    if (pipeline.empty()) throw InvalidInput("the level set is empty: no grid edge crosses the isovalue");
    Delaunay& dt = pipeline.dt();
    const octree::SampleField& field = pipeline.field();

    // Steps 4-5: the closed ball property, then eps refinement (refiner.h).
    Refiner& refiner = pipeline.refiner();
    auto t0 = Clock::now();
    refiner.measure_voxel_bound();
    st.seconds["voxel_bound"] = seconds_since(t0);
    const std::size_t n_before_loops = st.n_topology + st.n_geometry;
    refiner.run();
    if (!run.seeds.empty()) st.partition.seam_points = st.n_topology + st.n_geometry - n_before_loops;

    // Step 6: M, the restricted Delaunay surface.
    const auto t_extract = Clock::now();
    std::vector<std::uint32_t> surface_ids;
    result.surface = extract_surface(dt, refiner.cache(), &surface_ids);
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
        vp.adaptive = pipeline.leaves();
        vp.improve = options.improve_tets;
        GradedSpacing spacing{options.tet_grading, graded_max_level(options.tet_size, field.min_voxel_edge())};
        if (options.tet_spacing == TetSpacing::Graded) vp.spacing = &spacing;
        result.tets = build_volume_mesh(dt, refiner.cache(), field, pipeline.g_mask().get(), result.surface, vp, st.tets);
        st.seconds["tets"] = seconds_since(t0);
        if (options.tet_min_dihedral_deg > 0 || options.tet_max_dihedral_deg < 180) {
            const std::vector<Point> free = surface_sliver_points(result.tets, surface_ids, refiner.cache(),
                                                                  options.tet_min_dihedral_deg,
                                                                  options.tet_max_dihedral_deg);
            fresh = free.size();
            if (!free.empty()) {
                // This run's seeds, then the points its loop inserted (ids from first_inserted():
                // the tube and shoulder points before them come back with E and G).
                next_seeds = run.seeds;
                std::vector<std::pair<std::uint32_t, SeedPoint>> n_points;
                for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
                    if (v->info().id >= pipeline.first_inserted() &&
                        (v->info().kind == PointKind::Topology || v->info().kind == PointKind::Geometry))
                        n_points.push_back({v->info().id, {{v->point().x(), v->point().y(), v->point().z()}, v->info().kind}});
                std::sort(n_points.begin(), n_points.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
                for (const auto& [id, seed] : n_points) next_seeds.push_back(seed);
                for (const Point& p : free) next_seeds.push_back({{p.x(), p.y(), p.z()}, PointKind::Geometry});
            }
        }
    }
    st.seconds["total"] = seconds_since(t_start);
    st.peak_memory_bytes = peak_memory_bytes();
    return result;
}

} // namespace

MeshResult mesh_field(const FieldRun& run, const MeshOptions& options, Interrupter* interrupter)
{
    check_mesh_options(options);
    const ThreadLimit threads(options.threads);
    std::vector<SeedPoint> next_seeds;
    std::size_t fresh = 0;
    MeshResult result = mesh_field_once(run, options, interrupter, next_seeds, fresh);
    if (options.tets == TetRegion::None || (options.tet_min_dihedral_deg <= 0 && options.tet_max_dihedral_deg >= 180))
        return result;
    // The bad tets M pins down (refinement/surface_slivers.h): the pipeline again with the
    // points that free them, every guarantee checked again, up to kMaxSliverRuns more runs.
    std::size_t inserted = 0, facet_angle_points = 0, seam_points = 0;
    double earlier_seconds = 0;
    int runs = 0;
    while (!next_seeds.empty() && runs < kMaxSliverRuns) {
        ++runs;
        inserted += fresh;
        // A run's points are the next run's seeds: what each run added is summed.
        facet_angle_points += result.stats.n_facet_angle;
        seam_points += result.stats.partition.seam_points;
        earlier_seconds += result.stats.seconds["total"];
        FieldRun again = run;
        again.seeds = std::move(next_seeds);
        next_seeds.clear();
        result = mesh_field_once(again, options, interrupter, next_seeds, fresh);
    }
    MeshStats& st = result.stats;
    st.n_facet_angle += facet_angle_points;
    st.partition.seam_points += seam_points;
    st.n_tet_sliver = inserted;
    st.tet_sliver_runs = runs;
    st.tet_sliver_stop = next_seeds.empty() ? TetSliverStop::Met : TetSliverStop::RunBound;
    st.seconds["tet_sliver_runs"] = earlier_seconds;
    st.seconds["total"] += earlier_seconds;
    return result;
}

} // namespace mesher
} // namespace isodel
