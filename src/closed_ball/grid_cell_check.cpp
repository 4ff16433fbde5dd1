#include "closed_ball/grid_cell_check.h"

#include "delaunay/circumcenter.h"
#include "delaunay/vertex_star.h"
#include "octree/segment_walk.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace isodel::mesher {
namespace {

/// A grid point's best candidate so far: the crossing farthest from it, ties to the smaller
/// point, so the choice does not depend on the order the cells are seen in.
struct Best {
    double d = -1;
    std::optional<Candidate> c;
    void offer(double dd, const Point& p, const Vertex_handle& g)
    {
        if (dd > d || (dd == d && p < c->p)) {
            d = dd;
            c = Candidate{p, PointKind::Topology, std::sqrt(dd), FacetKey{{g->info().id, 0, 0}}, g->info().id};
        }
    }
};

/// The crossing farthest from g on the segments from g to those of its Voronoi vertices (the
/// circumcentres of the finite cells of \p cells) that lie on the other side of Sigma.
void check_one(const Delaunay& dt, const octree::SampleField::Reader& reader, Vertex_handle g,
               const std::vector<Cell_handle>& cells, int max_cells, Best& best)
{
    const auto& field = reader.field();
    const auto gi = field.world_to_index(to_vdb(g->point()));
    const bool g_inside = octree::phi_at(reader, gi) >= 0;
    for (const Cell_handle& c : cells) {
        if (dt.is_infinite(c)) continue;
        const auto ci = field.world_to_index(to_vdb(robust_circumcenter(c)));
        if ((octree::phi_at(reader, ci) >= 0) == g_inside) continue;
        const auto sc = octree::segment_crossings(reader, gi, ci, max_cells);
        if (sc.overflow || sc.t.empty()) continue;
        const auto w = field.index_to_world(gi + sc.t.back() * (ci - gi));
        const Point p(w[0], w[1], w[2]);
        best.offer(CGAL::squared_distance(p, g->point()), p, g);
    }
}

/// The same answers as check_one on every star, found cell by cell: each Voronoi vertex is
/// computed and classified once instead of once per grid point around it (up to four). For
/// the first check, when \p pending is all of G, star by star would visit most cells several
/// times, since nearly every cell has more than one grid vertex.
void check_all_cells(const Delaunay& dt, const octree::SampleField& field, const std::vector<Vertex_handle>& pending,
                     int max_cells, std::vector<Best>& best)
{
    std::uint32_t top = 0;
    for (const Vertex_handle& g : pending) top = std::max(top, g->info().id);
    std::vector<std::int32_t> slot(std::size_t(top) + 1, -1); // vertex id -> index in pending
    for (std::size_t i = 0; i < pending.size(); ++i) slot[pending[i]->info().id] = std::int32_t(i);
    std::vector<openvdb::Vec3d> gi(pending.size());
    std::vector<char> inside(pending.size());
    tbb::enumerable_thread_specific<octree::SampleField::Reader> readers([&] { return octree::SampleField::Reader(field); });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pending.size(), 1024), [&](const auto& r) {
        auto& reader = readers.local();
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            gi[i] = field.world_to_index(to_vdb(pending[i]->point()));
            inside[i] = octree::phi_at(reader, gi[i]) >= 0;
        }
    });
    struct Hit {
        std::uint32_t slot;
        double d;
        Point p;
    };
    // Runs of cells, each folded into `best` before the next: the handle and hit lists stay
    // bounded on large volumes (the choice in `best` does not depend on the order).
    constexpr std::size_t kCells = std::size_t(1) << 20;
    std::vector<Cell_handle> cells;
    cells.reserve(std::min<std::size_t>(kCells, dt.number_of_cells()));
    tbb::enumerable_thread_specific<std::vector<Hit>> hits;
    auto flush = [&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.size(), 2048), [&](const auto& r) {
            auto& reader = readers.local();
            auto& out = hits.local();
            for (std::size_t k = r.begin(); k != r.end(); ++k) {
                const Cell_handle& c = cells[k];
                int at[4], n = 0;
                for (int j = 0; j < 4; ++j) {
                    const std::uint32_t id = c->vertex(j)->info().id;
                    if (id <= top && slot[id] >= 0) at[n++] = slot[id];
                }
                if (n == 0) continue;
                const auto ci = field.world_to_index(to_vdb(robust_circumcenter(c)));
                const bool c_inside = octree::phi_at(reader, ci) >= 0;
                for (int m = 0; m < n; ++m) {
                    const std::size_t s = std::size_t(at[m]);
                    if (c_inside == bool(inside[s])) continue;
                    const auto sc = octree::segment_crossings(reader, gi[s], ci, max_cells);
                    if (sc.overflow || sc.t.empty()) continue;
                    const auto w = field.index_to_world(gi[s] + sc.t.back() * (ci - gi[s]));
                    const Point p(w[0], w[1], w[2]);
                    out.push_back({std::uint32_t(s), CGAL::squared_distance(p, pending[s]->point()), p});
                }
            }
        });
        cells.clear();
        for (auto& list : hits) {
            for (const Hit& h : list) best[h.slot].offer(h.d, h.p, pending[h.slot]);
            list.clear();
        }
    };
    for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
        cells.push_back(c);
        if (cells.size() == kCells) flush();
    }
    flush();
}

} // namespace

std::vector<Candidate> grid_cell_violations(const Delaunay& dt, const octree::SampleField& field,
                                            std::vector<Vertex_handle>& pending, int max_cells)
{
    std::vector<Best> best(pending.size());
    // Cell by cell when the pending points are a quarter or more of all vertices: the first
    // check, of all of G (the protective layer outnumbers E: a block of cells around every
    // crossed cell, Theorem 2), where nearly every cell has one.
    if (dt.dimension() == 3 && 4 * pending.size() >= dt.number_of_vertices()) {
        check_all_cells(dt, field, pending, max_cells, best);
    } else {
        tbb::enumerable_thread_specific<octree::SampleField::Reader> readers(
            [&] { return octree::SampleField::Reader(field); });
        // Stars by gather_star, not CGAL's incident_cells: its visit marks are shared.
        for_each_star(pending, 0, pending.size(), [&](std::size_t i, const std::vector<Cell_handle>& cells) {
            check_one(dt, readers.local(), pending[i], cells, max_cells, best[i]);
        });
    }
    std::vector<Candidate> out;
    std::vector<Vertex_handle> still;
    for (std::size_t i = 0; i < pending.size(); ++i)
        if (best[i].c) {
            out.push_back(*best[i].c);
            still.push_back(pending[i]);
        }
    pending.swap(still);
    return out;
}

} // namespace isodel::mesher
