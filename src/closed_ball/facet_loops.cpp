#include "closed_ball/facet_loops.h"

#include "closed_ball/facet_extrema.h"
#include "closed_ball/monotone_in_plane.h"

#include "delaunay/circumcenter.h"
#include "delaunay/vertex_star.h"
#include "octree/box_sign.h"
#include "octree/segment_walk.h"

#include <boost/container/small_vector.hpp>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <tuple>
#include <vector>

namespace isodel::mesher {
namespace {

using octree::Vec3d;
using detail::grid_edge_points;
using detail::grid_face_extrema;
using detail::Polygon;
using detail::Small;

struct EdgeJob {
    Delaunay::Edge edge;
    std::uint32_t a, b;  // vertex ids, a < b
    std::uint32_t order; // when it was found: the first found of an edge's duplicates is kept
};

/// The vertex ids of a cell, sorted: the key that picks the cell a facet's circulation starts at.
std::array<std::uint32_t, 4> sorted_vertex_ids(const Cell_handle& c)
{
    std::array<std::uint32_t, 4> k;
    for (int i = 0; i < 4; ++i) k[i] = c->vertex(i)->info().id;
    std::sort(k.begin(), k.end());
    return k;
}

/// The Voronoi facet dual to the job's edge, into \p P: the circumcentres of the cells around
/// the edge, in circulation order, in index space. False when the facet is unbounded.
bool voronoi_facet(const Delaunay& dt, const EdgeJob& job, const octree::SampleField& field, Small<Vec3d>& P)
{
    // Canonical order (determinism: the same facet gives bit-identical points whichever cell
    // represents its edge): circulate around the edge oriented from the lower id to the higher,
    // starting at the cell with the smallest sorted vertex ids.
    const Cell_handle c0 = job.edge.first;
    Vertex_handle va = c0->vertex(job.edge.second), vb = c0->vertex(job.edge.third);
    if (va->info().id > vb->info().id) std::swap(va, vb);
    Small<Cell_handle> ring;
    auto cc = dt.incident_cells(Delaunay::Edge(c0, c0->index(va), c0->index(vb))), done = cc;
    do {
        if (dt.is_infinite(cc)) return false; // unbounded: the voxel-bound repair's business
        ring.push_back(cc);
    } while (++cc != done);
    std::size_t first = 0;
    auto first_key = sorted_vertex_ids(ring[0]);
    for (std::size_t i = 1; i < ring.size(); ++i) {
        const auto k = sorted_vertex_ids(ring[i]);
        if (k < first_key) {
            first = i;
            first_key = k;
        }
    }
    std::rotate(ring.begin(), ring.begin() + std::ptrdiff_t(first), ring.end());
    for (const auto& c : ring) {
        const Point w = robust_circumcenter(c);
        P.push_back(field.world_to_index({w.x(), w.y(), w.z()}));
    }
    return true;
}

/// A Voronoi facet's plane and extent (index space).
struct FacetFrame {
    Vec3d N;      ///< Newell's normal, oriented by the vertices' order
    Vec3d lo, hi; ///< bounding box, padded
};

/// The frame of the facet with vertices \p P; none when the facet has no normal (degenerate) or
/// its box spans more than the voxel bound \p max_cells allows.
std::optional<FacetFrame> facet_frame(const Small<Vec3d>& P, int max_cells)
{
    Vec3d N(0, 0, 0), lo = P[0], hi = P[0];
    for (std::size_t i = 0; i < P.size(); ++i) {
        const Vec3d& p = P[i];
        const Vec3d& q = P[(i + 1) % P.size()];
        N += Vec3d((p.y() - q.y()) * (p.z() + q.z()), (p.z() - q.z()) * (p.x() + q.x()),
                   (p.x() - q.x()) * (p.y() + q.y())); // Newell's normal
        lo = openvdb::math::minComponent(lo, p);
        hi = openvdb::math::maxComponent(hi, p);
    }
    if (N.lengthSqr() == 0) return std::nullopt;
    const Vec3d span = hi - lo;
    if ((span.x() + 1) * (span.y() + 1) * (span.z() + 1) > 8.0 * max_cells) return std::nullopt;
    // The box only prunes the scans below (strictly_inside decides). A facet perpendicular to an
    // axis (two sites on an axis-parallel line: common next to tie samples) has a box of zero
    // thickness there, and a point solved onto its plane may round just outside it: pad it.
    // (Unpadded, a needle of Sigma along a grid edge can pierce such a facet unseen, and M loses
    // the needle's middle: tests/closed_ball/test_degenerate_voronoi_facets.cpp.)
    const double pad = 1e-9 * (1.0 + std::max({std::abs(lo[0]), std::abs(lo[1]), std::abs(lo[2]), std::abs(hi[0]),
                                               std::abs(hi[1]), std::abs(hi[2])}));
    lo -= Vec3d(pad);
    hi += Vec3d(pad);
    return FacetFrame{N, lo, hi};
}

/// The signs of F' at a facet's Voronoi vertices: one sign, or an arc (mixed) that the
/// edge-count test already checks; and the island test they answer.
struct BoundarySigns {
    const octree::SampleField::Reader& reader;
    const Small<Vec3d>& P;
    int max_cells;
    bool inside;          ///< P[0]'s sign, evaluated by the caller
    Small<char> P_inside; ///< every vertex's sign
    bool mixed = false;

    BoundarySigns(const octree::SampleField::Reader& field_reader, const Small<Vec3d>& points, bool first_inside,
                  int cell_bound)
        : reader(field_reader), P(points), max_cells(cell_bound), inside(first_inside), P_inside(points.size())
    {
        P_inside[0] = inside;
        for (std::size_t i = 1; i < P.size(); ++i) {
            P_inside[i] = octree::phi_at(reader, P[i]) >= 0;
            mixed |= P_inside[i] != inside;
        }
    }

    /// Is q cut off from the boundary part of its own sign? With one boundary sign: iff q has
    /// the other sign. With an arc: when no straight path in the facet leads from q to a Voronoi
    /// vertex of its sign without crossing Sigma (an island; a strongly curved arc can also cause
    /// this, and then the inserted point is still a point of Sigma in the facet, far from
    /// the edge, which the refinement accepts).
    bool island(const Vec3d& q, bool q_inside) const
    {
        if (!mixed) return q_inside != inside;
        for (std::size_t i = 0; i < P.size(); ++i)
            if (bool(P_inside[i]) == q_inside && octree::segment_crossings(reader, q, P[i], max_cells).t.empty())
                return false;
        return true;
    }
};

/// The deepest point (largest |phi|) of an island among the facet's grid-edge points and
/// grid-face extrema (facet_extrema.h): a witness that Sigma meets the facet away from its
/// boundary. None when no such point is cut off.
std::optional<Vec3d> deepest_island_point(const octree::SampleField& field, const octree::SampleField::Reader& reader,
                                          const Polygon& polygon, const FacetFrame& frame, const BoundarySigns& boundary)
{
    std::optional<Vec3d> witness;
    double depth = 0;
    grid_edge_points(polygon, frame.lo, frame.hi, field.face_slabs().h, [&](int, const Vec3d& q) {
        const double phi = octree::phi_at(reader, q);
        const bool q_inside = phi >= 0;
        if (std::abs(phi) <= depth) return;
        if (!boundary.island(q, q_inside)) return;
        depth = std::abs(phi);
        witness = q;
    });
    grid_face_extrema(reader, polygon, frame.lo, frame.hi, [&](const Vec3d& q) {
        const double phi = octree::phi_at(reader, q);
        if (std::abs(phi) <= depth || !boundary.island(q, phi >= 0)) return;
        depth = std::abs(phi);
        witness = q;
    });
    return witness;
}

/// Sigma on the way from the witness to each Voronoi vertex: the crossing farthest from the
/// Delaunay edge (paper, CBP_VF), as the candidate to insert.
std::optional<Candidate> farthest_crossing(const EdgeJob& job, const octree::SampleField& field,
                                           const octree::SampleField::Reader& reader, const Small<Vec3d>& P,
                                           const Vec3d& witness, int max_cells)
{
    const Point pa = job.edge.first->vertex(job.edge.second)->point();
    const Point pb = job.edge.first->vertex(job.edge.third)->point();
    const K::Segment_3 ab(pa, pb);
    std::optional<Candidate> best;
    double best_d = -1;
    for (const auto& p : P) {
        const auto x = octree::segment_crossings(reader, witness, p, max_cells);
        if (x.t.empty()) continue;
        const Vec3d s = witness + x.t.front() * (p - witness);
        const Vec3d w = field.index_to_world(s);
        const Point pw(w[0], w[1], w[2]);
        const double d = CGAL::squared_distance(pw, ab);
        if (d > best_d) {
            best_d = d;
            const double spacing = std::sqrt(std::min(CGAL::squared_distance(pw, pa), CGAL::squared_distance(pw, pb)));
            best = Candidate{pw, PointKind::Topology, spacing,
                             FacetKey{{job.a, job.b, std::numeric_limits<std::uint32_t>::max()}}, job.a};
        }
    }
    return best;
}

/// The candidate of the Voronoi facet dual to the job's edge when Sigma meets the facet in a
/// closed loop (CBP_VF's second clause, facet_loops.h); none when it does not, or when the
/// facet is unbounded or larger than the voxel bound allows.
std::optional<Candidate> check_facet(const Delaunay& dt, const EdgeJob& job, const octree::SampleField& field,
                                     const octree::SampleField::Reader& reader, int max_cells)
{
    Small<Vec3d> P;
    if (!voronoi_facet(dt, job, field, P)) return std::nullopt;
    const std::optional<FacetFrame> frame = facet_frame(P, max_cells);
    if (!frame) return std::nullopt;
    // Every point scanned below lies in the box: where F' keeps one sign on all of it, no point
    // can have the other. The Voronoi vertices lie in the box too, so P[0]'s sign is the one to
    // ask for, and a certified box has a boundary of that one sign: the other vertices need no
    // evaluation. (Most facets of a first scan lie away from Sigma's sign changes and end here.)
    const bool inside = octree::phi_at(reader, P[0]) >= 0;
    if (octree::one_sign_on_box(reader, frame->lo, frame->hi, inside)) return std::nullopt;
    // A direction in the facet's plane along which F' never decreases rules a loop out
    // (monotone_in_plane.h): most facets dual to Delaunay edges along Sigma end here.
    if (monotone_direction_in_plane(reader, frame->lo, frame->hi, frame->N)) return std::nullopt;
    const BoundarySigns boundary(reader, P, inside, max_cells);
    const Polygon polygon(P, frame->N);
    const std::optional<Vec3d> witness = deepest_island_point(field, reader, polygon, *frame, boundary);
    if (!witness) return std::nullopt;
    return farthest_crossing(job, field, reader, P, *witness, max_cells);
}

/// A facet found violated: its edge and the point to insert.
struct Found {
    EdgeJob job;
    Candidate candidate;
};

// Stars are gathered a chunk of vertices at a time: an edge is seen from every cell around it,
// so the raw lists of all the E/N vertices of a large volume would take gigabytes.
constexpr std::size_t kChunk = std::size_t(1) << 15;

const auto by_edge_then_order = [](const EdgeJob& x, const EdgeJob& y) {
    return std::tie(x.a, x.b, x.order) < std::tie(y.a, y.b, y.order);
};
const auto same_edge = [](const EdgeJob& x, const EdgeJob& y) { return x.a == y.a && x.b == y.b; };

/// The vertices whose stars hold the edges to check: on the \p first scan every E/N vertex,
/// later the touched ones (taken out of \p touched).
std::vector<Vertex_handle> vertices_to_scan(const Delaunay& dt, bool first, std::vector<Vertex_handle>& touched)
{
    std::vector<Vertex_handle> from;
    if (first) {
        for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
            if (v->info().on_surface()) from.push_back(v);
        // In id order, so the candidates are found in an order that does not depend on where
        // the triangulation stores its vertices. An edge is represented by the first cell that
        // shows it in its vertex's star (gather_star's order depends only on the connectivity):
        // check_facet circulates from a canonical cell, but takes the edge's two points in the
        // representative's order, which the candidate's distance to the edge may round by.
        std::sort(from.begin(), from.end(), [](Vertex_handle x, Vertex_handle y) { return x->info().id < y->info().id; });
    } else {
        from.swap(touched);
    }
    return from;
}

/// The edges to check in the star of \p v (its \p cells), one job per edge (the first found
/// represents it). On the \p first scan only the edges at v, an edge between two E/N vertices
/// taken at its smaller id, so that each edge is found from exactly one vertex.
void star_edges(const Delaunay& dt, bool first, Vertex_handle v, const std::vector<Cell_handle>& cells,
                std::vector<EdgeJob>& out, const std::function<bool(const Point&)>& region)
{
    out.clear();
    for (const Cell_handle& c : cells)
        for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j) {
                const auto va = c->vertex(i), vb = c->vertex(j);
                if (first && va != v && vb != v) continue; // only the edges at v
                if (dt.is_infinite(va) || dt.is_infinite(vb)) continue;
                if (!va->info().on_surface() && !vb->info().on_surface()) continue;
                const auto ia = va->info().id, ib = vb->info().id;
                // Found from its other end, unless that end is outside the region (not scanned).
                const Vertex_handle other = va == v ? vb : va;
                if (first && va->info().on_surface() && vb->info().on_surface() && v->info().id != std::min(ia, ib) &&
                    (!region || region(other->point())))
                    continue;
                // order: when it was found, so the first found of each edge sorts first
                // (a stable sort by edge, without stable_sort's buffer per vertex).
                out.push_back({Delaunay::Edge(c, i, j), std::min(ia, ib), std::max(ia, ib), std::uint32_t(out.size())});
            }
    std::sort(out.begin(), out.end(), by_edge_then_order);
    out.erase(std::unique(out.begin(), out.end(), same_edge), out.end());
}

/// The first scan: the facets of the edges at every E/N vertex of \p from. Each edge is found
/// from exactly one vertex (star_edges), so a vertex's list is all its edges' jobs: each is
/// checked right away, while the star's cells are at hand, with no list of all the jobs
/// (millions on a large volume) to sort. (Nothing is flagged before the first scan.)
std::vector<Found> check_every_star(const Delaunay& dt, const octree::SampleField& field, int max_cells,
                                    const std::vector<Vertex_handle>& from,
                                    const std::function<bool(const Point&)>& region)
{
    std::vector<Found> found;
    std::vector<std::vector<Found>> per_vertex;
    tbb::enumerable_thread_specific<std::vector<EdgeJob>> lists;
    tbb::enumerable_thread_specific<octree::SampleField::Reader> readers([&] { return octree::SampleField::Reader(field); });
    for (std::size_t begin = 0; begin < from.size(); begin += kChunk) {
        const std::size_t end = std::min(begin + kChunk, from.size());
        per_vertex.assign(end - begin, {});
        for_each_star(from, begin, end, [&](std::size_t k, const std::vector<Cell_handle>& cells) {
            auto& jobs = lists.local();
            star_edges(dt, /*first=*/true, from[k], cells, jobs, region);
            const auto& reader = readers.local();
            for (const EdgeJob& job : jobs)
                if (auto c = check_facet(dt, job, field, reader, max_cells)) per_vertex[k - begin].push_back({job, *c});
        });
        for (auto& list : per_vertex) found.insert(found.end(), list.begin(), list.end());
    }
    return found;
}

/// A later scan: the facets of every edge of the cells around the touched vertices \p from,
/// and those \p flagged last time, one job per edge, checked in parallel.
std::vector<Found> check_changed_facets(const Delaunay& dt, const octree::SampleField& field, int max_cells,
                                        const std::vector<Vertex_handle>& from,
                                        const std::vector<std::pair<Vertex_handle, Vertex_handle>>& flagged)
{
    std::vector<Found> found;
    std::vector<EdgeJob> jobs;
    std::vector<std::vector<EdgeJob>> per_vertex;
    for (std::size_t begin = 0; begin < from.size(); begin += kChunk) {
        const std::size_t end = std::min(begin + kChunk, from.size());
        per_vertex.assign(end - begin, {});
        for_each_star(from, begin, end, [&](std::size_t k, const std::vector<Cell_handle>& cells) {
            per_vertex[k - begin].reserve(6 * cells.size());
            star_edges(dt, /*first=*/false, from[k], cells, per_vertex[k - begin], {});
        });
        for (auto& list : per_vertex) {
            for (EdgeJob& job : list) {
                job.order = std::uint32_t(jobs.size());
                jobs.push_back(job);
            }
            list = {};
        }
    }
    for (const auto& [va, vb] : flagged) {
        Cell_handle c;
        int i, j;
        if (dt.is_edge(va, vb, c, i, j))
            jobs.push_back({Delaunay::Edge(c, i, j), std::min(va->info().id, vb->info().id),
                            std::max(va->info().id, vb->info().id), std::uint32_t(jobs.size())});
    }
    // One job per edge (an edge is seen from several cells), in id order; the first found
    // represents it.
    tbb::parallel_sort(jobs.begin(), jobs.end(), by_edge_then_order);
    jobs.erase(std::unique(jobs.begin(), jobs.end(), same_edge), jobs.end());
    std::vector<std::optional<Candidate>> checked(jobs.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, jobs.size(), 256), [&](const auto& r) {
        const octree::SampleField::Reader reader(field);
        for (std::size_t i = r.begin(); i != r.end(); ++i) checked[i] = check_facet(dt, jobs[i], field, reader, max_cells);
    });
    for (std::size_t i = 0; i < jobs.size(); ++i)
        if (checked[i]) found.push_back({jobs[i], *checked[i]});
    return found;
}

} // namespace

std::vector<Candidate> FacetLoopScanner::scan(const Delaunay& dt, const octree::SampleField& field, int max_cells)
{
    // Sigma meets only Voronoi cells of E/N points (Theorem 3, checked by grid_cell_check), so
    // only facets dual to edges with such an endpoint can hold a loop.
    // The edges to check, gathered from vertex stars in parallel (gather_star: no shared visit
    // marks): on the first scan the edges at every E/N vertex (an edge between two of them taken
    // at its smaller id), later every edge of the cells around the touched vertices, since a
    // Voronoi facet changes only when a cell around its edge does. Plus the facets violated last
    // time (their point may have been skipped as too close to another one of the batch).
    const bool first = first_;
    std::vector<Vertex_handle> from = vertices_to_scan(dt, first, touched_);
    if (region_) {
        // The first scan starts from the region's vertices (star_edges takes the edges leaving
        // it at their inner end); later scans start from every touched vertex, since a point
        // inserted just outside changes the facets of edges inside.
        if (first)
            from.erase(std::remove_if(from.begin(), from.end(), [&](const Vertex_handle& v) { return !region_(v->point()); }),
                   from.end());
        flagged_.erase(std::remove_if(flagged_.begin(), flagged_.end(),
                                      [&](const auto& e) { return !region_(e.first->point()) && !region_(e.second->point()); }),
                       flagged_.end());
    }
    first_ = false;
    touched_.clear();
    std::vector<Found> found = first ? check_every_star(dt, field, max_cells, from, region_)
                                     : check_changed_facets(dt, field, max_cells, from, flagged_);
    flagged_.clear();
    // In id order of the edges (the first scan found them by vertex).
    std::sort(found.begin(), found.end(),
              [](const Found& x, const Found& y) { return std::tie(x.job.a, x.job.b) < std::tie(y.job.a, y.job.b); });
    std::vector<Candidate> out;
    for (const Found& f : found) {
        if (keep_ && !keep_(f.candidate.p)) continue;
        out.push_back(f.candidate);
        const auto& e = f.job.edge;
        flagged_.push_back({e.first->vertex(e.second), e.first->vertex(e.third)});
    }
    return out;
}

} // namespace isodel::mesher
