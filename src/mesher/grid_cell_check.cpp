#include "mesher/grid_cell_check.h"

#include "mesher/circumcenter.h"
#include "mesher/vertex_star.h"
#include "octree/segment_walk.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <optional>

namespace isodel::mesher {
namespace {

/// The crossing farthest from g on the segments from g to those of its Voronoi vertices (the
/// circumcentres of the finite cells of \p cells) that lie on the other side of Sigma.
std::optional<Candidate> check_one(const Delaunay& dt, const octree::SampleField::Reader& reader, Vertex_handle g,
                                   const std::vector<Cell_handle>& cells, int max_cells)
{
    const auto& field = reader.field();
    const auto gi = field.world_to_index(to_vdb(g->point()));
    const bool g_inside = octree::phi_at(reader, gi) >= 0;
    std::optional<Candidate> best;
    double best_d = -1;
    for (const Cell_handle& c : cells) {
        if (dt.is_infinite(c)) continue;
        const auto ci = field.world_to_index(to_vdb(robust_circumcenter(c)));
        if ((octree::phi_at(reader, ci) >= 0) == g_inside) continue;
        const auto sc = octree::segment_crossings(reader, gi, ci, max_cells);
        if (sc.overflow || sc.t.empty()) continue;
        const auto w = field.index_to_world(gi + sc.t.back() * (ci - gi));
        const Point p(w[0], w[1], w[2]);
        const double d = CGAL::squared_distance(p, g->point());
        // Ties go to the smaller point: the star's order depends on how the triangulation was
        // built (initial_delaunay.h), the choice must not.
        if (d > best_d || (d == best_d && p < best->p)) {
            best_d = d;
            best = Candidate{p, PointKind::Topology, std::sqrt(d), FacetKey{{g->info().id, 0, 0}}};
        }
    }
    return best;
}

} // namespace

std::vector<Candidate> grid_cell_violations(const Delaunay& dt, const octree::SampleField& field,
                                            std::vector<Vertex_handle>& pending, int max_cells)
{
    std::vector<std::optional<Candidate>> found(pending.size());
    tbb::enumerable_thread_specific<octree::SampleField::Reader> readers([&] { return octree::SampleField::Reader(field); });
    // Stars by gather_star, not CGAL's incident_cells: its visit marks are shared.
    for_each_star(pending, 0, pending.size(), [&](std::size_t i, const std::vector<Cell_handle>& cells) {
        found[i] = check_one(dt, readers.local(), pending[i], cells, max_cells);
    });
    std::vector<Candidate> out;
    std::vector<Vertex_handle> still;
    for (std::size_t i = 0; i < pending.size(); ++i)
        if (found[i]) {
            out.push_back(*found[i]);
            still.push_back(pending[i]);
        }
    pending.swap(still);
    return out;
}

} // namespace isodel::mesher
