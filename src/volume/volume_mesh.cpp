#include "volume/volume_mesh.h"

#include "volume/crowding_grid_points.h"
#include "closed_ball/grid_cell_check.h"
#include "volume/interior_points.h"
#include "volume/region_labels.h"
#include "surface/surface_extraction.h"
#include "volume/tet_improvement.h"
#include "volume/tet_quality.h"

#include <isodel/errors.h>

#include <CGAL/spatial_sort.h>

#include <tbb/parallel_sort.h>

#include <algorithm>
#include <chrono>
#include <sstream>

namespace isodel::mesher {
namespace {

/// Throws unless re-extracting M after G' gives \p before exactly.
void check_surface_unchanged(const Delaunay& dt, const FacetCache& cache, const SurfaceMesh& before, const char* step)
{
    const SurfaceMesh after = extract_surface(dt, cache);
    if (after.vertices == before.vertices && after.triangles == before.triangles) return;
    std::ostringstream os;
    os << "DELVOLMESH: " << step << " changed the restricted Delaunay surface (" << before.triangles.size()
       << " triangles before, " << after.triangles.size() << " after)";
    throw GuaranteeViolated(os.str());
}

/// Canonical tet order: each tet's indices sorted, its orientation restored with one
/// transposition when the sort was an odd permutation, then the tets sorted. The mesh then
/// depends only on the vertex numbering, not on the triangulation's memory layout.
void canonical_order(TetMesh& mesh)
{
    struct Tet {
        std::array<std::int32_t, 4> v;
        std::int8_t region;
    };
    std::vector<Tet> tets;
    tets.reserve(mesh.tets.size());
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        std::array<std::int32_t, 4> a = mesh.tets[t];
        bool odd = false;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j + 1 < 4 - i; ++j)
                if (a[j] > a[j + 1]) {
                    std::swap(a[j], a[j + 1]);
                    odd = !odd;
                }
        if (odd) std::swap(a[2], a[3]);
        tets.push_back({a, std::int8_t(mesh.tet_region[t])});
    }
    // The tets' vertex sets differ, so the order is total and any sort gives it.
    tbb::parallel_sort(tets.begin(), tets.end(), [](const Tet& x, const Tet& y) { return x.v < y.v; });
    mesh.tets.clear();
    mesh.tet_region.clear();
    for (const auto& t : tets) {
        mesh.tets.push_back(t.v);
        mesh.tet_region.push_back(t.region);
    }
}

/// Wall-clock time per step (TetStats::seconds): lap() charges \p step with the time since the
/// previous lap, or since construction.
class StepTimer {
public:
    explicit StepTimer(TetStats& st) : st_(st), start_(std::chrono::steady_clock::now()) {}
    void lap(const char* step)
    {
        const auto now = std::chrono::steady_clock::now();
        st_.seconds[step] += std::chrono::duration<double>(now - start_).count();
        start_ = now;
    }

private:
    TetStats& st_;
    std::chrono::steady_clock::time_point start_;
};

/// Inserts G' (interior_points.h) into \p dt through \p cache; returns the vertices it added
/// (a point already in \p dt adds none).
std::vector<Vertex_handle> insert_grid_points(Delaunay& dt, FacetCache& cache, const octree::SampleField& field,
                                              const openvdb::MaskGrid& g_mask, const VolumeMeshParams& params,
                                              const InterruptScope& scope)
{
    // In Hilbert order (CGAL's spatial_sort: biased randomised insertion order with a fixed
    // seed, so deterministic). Raster order would be quadratic here: far from Sigma the box is
    // empty, and each point of a raster row conflicts with cells spanning the whole row.
    std::vector<Point> pts;
    {
        const std::vector<openvdb::Coord> gp =
            interior_points(field, g_mask, params.region, params.adaptive, params.spacing);
        pts.reserve(gp.size());
        for (const auto& c : gp) {
            const auto w = field.index_to_world(c.asVec3d());
            pts.emplace_back(w[0], w[1], w[2]);
        }
    }
    CGAL::spatial_sort(pts.begin(), pts.end(), K());
    std::vector<Vertex_handle> added;
    added.reserve(pts.size());
    Cell_handle hint;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        const Vertex_handle v = cache.insert(dt, pts[i], VertexInfo{(*params.next_id)++, PointKind::Grid}, hint);
        if (v == Vertex_handle()) continue;
        hint = v->cell();
        added.push_back(v);
        if ((i & 0xFFFF) == 0) scope.check(int(40 * i / pts.size()));
    }
    return added;
}

/// Throws unless the Voronoi cell of every G' point in \p added stays on its own side of Sigma
/// (Theorem 3), as grid_cell_violations checks it.
void check_grid_cells_off_sigma(const Delaunay& dt, const octree::SampleField& field,
                                const std::vector<Vertex_handle>& added, int max_cells_walk)
{
    // In chunks: grid_cell_violations gathers every pending point's incident cells at once.
    std::size_t bad = 0;
    Point first_bad;
    for (std::size_t i = 0; i < added.size(); i += 65536) {
        std::vector<Vertex_handle> pending(added.begin() + std::ptrdiff_t(i),
                                           added.begin() + std::ptrdiff_t(std::min(added.size(), i + 65536)));
        const std::vector<Candidate> found = grid_cell_violations(dt, field, pending, max_cells_walk);
        if (!found.empty() && bad == 0) first_bad = found.front().p;
        bad += found.size();
    }
    if (bad) {
        std::ostringstream os;
        os << "DELVOLMESH: " << bad << " interior grid points G' have Voronoi cells that meet Sigma "
           << "(Theorem 3), the first near (" << first_bad << ")";
        throw GuaranteeViolated(os.str());
    }
}

/// Removes the grid points that would make slivers next to M (crowding_grid_points.h): those
/// within a quarter voxel of a vertex of M whose Voronoi cell provably misses Sigma. M is
/// exactly unchanged, and checked. Sets st.grid_points_removed.
void remove_crowding_grid_points(Delaunay& dt, FacetCache& cache, const octree::SampleField& field,
                                 const SurfaceMesh& surface, const VolumeMeshParams& params, TetStats& st)
{
    const std::vector<Vertex_handle> crowding = crowding_grid_points(dt, field, 0.25 * field.min_voxel_edge());
    st.grid_points_removed = crowding.size();
    if (!crowding.empty()) {
        cache.remove(dt, crowding);
        cache.update(dt, field, params.max_cells_walk);
        check_surface_unchanged(dt, cache, surface, "removing grid points next to M (certificate unsound)");
    }
}

/// The new index of each vertex id: M's vertices numbered first, in surface.vertices order
/// (extract_surface sorts them by id); -1 for every other id.
std::vector<std::int32_t> number_surface_vertices(const FacetCache& cache, std::uint32_t next_id)
{
    std::vector<std::uint32_t> surface_ids;
    for (const auto& e : cache.active())
        if (e.record->crossings == 1)
            for (const auto& v : facet_vertices(e.facet)) surface_ids.push_back(v->info().id);
    std::sort(surface_ids.begin(), surface_ids.end());
    surface_ids.erase(std::unique(surface_ids.begin(), surface_ids.end()), surface_ids.end());
    // Ids are dense (the mesher's counter): the new numbering is an array by id.
    std::vector<std::int32_t> index(next_id, -1);
    for (std::size_t i = 0; i < surface_ids.size(); ++i) index[surface_ids[i]] = std::int32_t(i);
    return index;
}

/// The labelled cells of params.region as a TetMesh (no triangles yet), in the cells' order.
/// Numbering: M's vertices first (number_surface_vertices), then the other vertices of the kept
/// tetrahedra by id: independent of memory layout.
TetMesh kept_tets(const Delaunay& dt, const FacetCache& cache, const SurfaceMesh& surface,
                  const VolumeMeshParams& params)
{
    std::vector<std::int32_t> index = number_surface_vertices(cache, *params.next_id);
    const bool keep_in = params.region == TetRegion::Inside || params.region == TetRegion::Both;
    const bool keep_out = params.region == TetRegion::Outside || params.region == TetRegion::Both;
    std::vector<Vertex_handle> other(*params.next_id); // the other kept vertices, by id
    std::vector<std::pair<std::array<Vertex_handle, 4>, std::int8_t>> kept;
    for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
        const std::int8_t l = c->region_label();
        if (!(l == 1 ? keep_in : keep_out)) continue;
        kept.push_back({{c->vertex(0), c->vertex(1), c->vertex(2), c->vertex(3)}, l});
        for (int j = 0; j < 4; ++j)
            if (index[c->vertex(j)->info().id] < 0) other[c->vertex(j)->info().id] = c->vertex(j);
    }

    TetMesh mesh;
    mesh.vertices = surface.vertices;
    for (std::uint32_t id = 0; id < other.size(); ++id)
        if (const Vertex_handle v = other[id]; v != Vertex_handle()) {
            index[id] = std::int32_t(mesh.vertices.size());
            mesh.vertices.push_back({v->point().x(), v->point().y(), v->point().z()});
        }
    for (const auto& [vs, l] : kept) {
        mesh.tets.push_back({index[vs[0]->info().id], index[vs[1]->info().id], index[vs[2]->info().id],
                             index[vs[3]->info().id]});
        mesh.tet_region.push_back(l);
    }
    return mesh;
}

/// Improves the worst tets of \p mesh (tet_improvement.h) and records what it did in \p st.
void improve_tet_quality(TetMesh& mesh, const octree::SampleField& field, std::size_t surface_vertices, TetStats& st)
{
    const auto t0 = std::chrono::steady_clock::now();
    // Blocks of 16 voxels: ~500 on a 128^3 volume, enough to keep every thread busy, and
    // large enough that few bad tets sit on a block's boundary in both sweeps.
    TetImprovementParams ip;
    ip.block_size = 16 * field.min_voxel_edge();
    const TetImprovementStats imp = improve_tets(mesh, surface_vertices, ip);
    st.min_dihedral_deg_delaunay = imp.min_dihedral_before_deg;
    st.vertices_moved = imp.vertices_moved;
    st.vertices_removed = imp.vertices_removed;
    st.vertices_inserted = imp.vertices_inserted;
    st.flips = imp.flips_23 + imp.edges_removed;
    st.improvement_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

} // namespace

TetMesh build_volume_mesh(Delaunay& dt, FacetCache& cache, const octree::SampleField& field,
                          const openvdb::MaskGrid& g_mask, const SurfaceMesh& surface,
                          const VolumeMeshParams& params, TetStats& st)
{
    InterruptScope scope(params.interrupter, "tets");
    // Where the time goes, step by step (TetStats::seconds).
    StepTimer timer(st);
    // 1. G' inserted into the triangulation, in Hilbert order (DELVOLMESH, paper Section 4.1).
    const std::vector<Vertex_handle> added = insert_grid_points(dt, cache, field, g_mask, params, scope);
    st.g_prime = added.size();
    timer.lap("insert_g_prime");

    // 2. Conformity, checked rather than assumed: M recomputed from the new triangulation, and
    // Theorem 3 for every G' point (its Voronoi cell stays on its own side of Sigma).
    cache.update(dt, field, params.max_cells_walk);
    check_surface_unchanged(dt, cache, surface,
                            "inserting the interior grid points G' (the protective layer did not keep them off Sigma, Theorem 3)");
    scope.check(60);
    check_grid_cells_off_sigma(dt, field, added, params.max_cells_walk);
    scope.check(70);
    timer.lap("conformity_checks");

    // 3. Slivers next to M: crowding grid points removed, M unchanged.
    remove_crowding_grid_points(dt, cache, field, surface, params, st);
    scope.check(75);
    timer.lap("crowding_points");

    // 4. Inside/outside labels consistent with M (region_labels.h).
    label_regions(dt, cache);
    timer.lap("region_labels");

    // 5. The tetrahedra of params.region, numbered independently of memory layout.
    TetMesh mesh = kept_tets(dt, cache, surface, params);
    scope.check(85);

    // 6. Canonical order, then quality (tet_improvement.h): smoothing, collapses and flips away
    // from M; M, the regions and their volumes stay. Block by block, each block's tets in
    // canonical order and the blocks merged in a fixed order (tet_improvement_blocks.cpp), so
    // the result does not depend on the thread count.
    canonical_order(mesh);
    timer.lap("numbering");
    if (params.improve) improve_tet_quality(mesh, field, surface.vertices.size(), st);
    scope.check(95);
    timer.lap("improvement");

    canonical_order(mesh);
    mesh.triangles = surface.triangles;
    measure_tet_quality(mesh, surface.vertices.size(), st);
    st.volume_enclosed_by_surface = enclosed_volume(surface);
    timer.lap("quality");
    return mesh;
}

} // namespace isodel::mesher
