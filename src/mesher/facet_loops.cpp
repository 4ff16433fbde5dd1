#include "mesher/facet_loops.h"

#include "mesher/circumcenter.h"
#include "mesher/vertex_star.h"
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
// Per-facet scratch lists: a facet has a handful of Voronoi vertices and piece planes, and the
// first scan of a 128^3 protein looks at 1.6 M facets; heap lists cost an allocation each.
template <class T>
using Small = boost::container::small_vector<T, 16>;

struct EdgeJob {
    Delaunay::Edge edge;
    std::uint32_t a, b;  // vertex ids, a < b
    std::uint32_t order; // when it was found: the first found of an edge's duplicates is kept
};

/// A Voronoi facet: its vertices in order, the normal from that order, and the squared length
/// below which an edge is rounding noise. Cospherical sites give Voronoi vertices that coincide
/// up to rounding: an edge 1e-16 long has no direction, and the sign it gives is noise.
/// (Quantized property seed 1275: such an edge hid the neck through a face saddle at exactly v,
/// and M lost a handle.)
struct Polygon {
    const Small<Vec3d>& P;
    Vec3d N;
    double noise_edge2;

    Polygon(const Small<Vec3d>& points, const Vec3d& normal) : P(points), N(normal), noise_edge2(0)
    {
        for (std::size_t i = 0; i < P.size(); ++i)
            noise_edge2 = std::max(noise_edge2, (P[(i + 1) % P.size()] - P[i]).lengthSqr());
        noise_edge2 *= 1e-20;
    }

    /// q (on the facet's plane) strictly inside the convex polygon.
    bool strictly_inside(const Vec3d& q) const
    {
        for (std::size_t i = 0; i < P.size(); ++i) {
            const Vec3d e = P[(i + 1) % P.size()] - P[i];
            if (e.lengthSqr() <= noise_edge2) continue; // coincident Voronoi vertices
            if (e.cross(q - P[i]).dot(N) <= 0) return false;
        }
        return true;
    }
};

/// The planes where F' (octree/face_slabs.h) changes its trilinear piece, on one axis, in
/// [lo, hi]: the grid planes c, or with slabs of half-width h their boundaries c - h and c + h.
Small<double> piece_planes(double lo, double hi, double h)
{
    Small<double> out;
    for (int c = int(std::floor(lo)) - 1; c <= int(std::ceil(hi)) + 1; ++c) {
        const double planes[2] = {c - h, c + h};
        for (int i = h == 0 ? 1 : 0; i < 2; ++i)
            if (planes[i] >= lo && planes[i] <= hi) out.push_back(planes[i]);
    }
    return out;
}

/// Points where the facet's plane meets grid edges inside the facet, with phi there. With
/// slabs, the lines where two slab boundaries meet (F' there is F on the grid edge).
template <class Visit>
void grid_edge_points(const Polygon& poly, const Vec3d& lo, const Vec3d& hi, double h, Visit&& visit)
{
    const auto& P = poly.P;
    const Vec3d& N = poly.N;
    const double c = N.dot(P[0]);
    for (int d = 0; d < 3; ++d) {
        const int e1 = (d + 1) % 3, e2 = (d + 2) % 3;
        if (std::abs(N[d]) < 1e-9 * N.length()) continue; // plane parallel to these edges
        const Small<double> us = piece_planes(lo[e1], hi[e1], h), vs = piece_planes(lo[e2], hi[e2], h);
        for (const double u : us)
            for (const double v : vs) {
                Vec3d q;
                q[e1] = u;
                q[e2] = v;
                q[d] = (c - N[e1] * u - N[e2] * v) / N[d];
                if (q[d] < lo[d] || q[d] > hi[d]) continue;
                if (poly.strictly_inside(q)) visit(d, q);
            }
    }
}

/// Extrema of F along the lines where the facet's plane crosses grid faces, inside the facet.
/// On a face F is bilinear, so along such a line it is a quadratic per face square: three
/// values give it exactly. A tube of Sigma lying in a grid face (e.g. two blobs joined at a face
/// saddle) has the extremum of its cross-section there, not on a grid edge.
template <class Visit>
void grid_face_extrema(const octree::SampleField::Reader& reader, const Polygon& poly, const Vec3d& lo,
                       const Vec3d& hi, Visit&& visit)
{
    const double h = reader.field().face_slabs().h;
    const auto& P = poly.P;
    const Vec3d& N = poly.N;
    const double c = N.dot(P[0]);
    for (int d = 0; d < 3; ++d) {
        const int e1 = (d + 1) % 3, e2 = (d + 2) % 3;
        Vec3d ed(0, 0, 0);
        ed[d] = 1;
        const Vec3d D = N.cross(ed); // the line's direction: in both planes
        if (D.lengthSqr() < 1e-18 * N.lengthSqr()) continue; // facet parallel to these faces
        for (const double u : piece_planes(lo[d], hi[d], h)) {
            // A point of the line: x_d = u, and the facet plane, solved along the larger of e1, e2.
            Vec3d P0(0, 0, 0);
            P0[d] = u;
            const int k = std::abs(N[e1]) >= std::abs(N[e2]) ? e1 : e2;
            const int m = k == e1 ? e2 : e1;
            P0[m] = 0.5 * (lo[m] + hi[m]);
            P0[k] = (c - N[d] * u - N[m] * P0[m]) / N[k];
            // Clip to the bounding box in e1, e2; breakpoints where the line crosses grid lines.
            double t0 = -1e300, t1 = 1e300;
            for (int a : {e1, e2}) {
                if (D[a] == 0) {
                    if (P0[a] < lo[a] || P0[a] > hi[a]) t0 = 1e300;
                    continue;
                }
                const double ta = (lo[a] - P0[a]) / D[a], tb = (hi[a] - P0[a]) / D[a];
                t0 = std::max(t0, std::min(ta, tb));
                t1 = std::min(t1, std::max(ta, tb));
            }
            if (!(t0 < t1)) continue;
            Small<double> ts{t0, t1};
            for (int a : {e1, e2}) {
                if (D[a] == 0) continue;
                const double xa = P0[a] + t0 * D[a], xb = P0[a] + t1 * D[a];
                for (const double g : piece_planes(std::min(xa, xb), std::max(xa, xb), h))
                    ts.push_back((g - P0[a]) / D[a]);
            }
            std::sort(ts.begin(), ts.end());
            // phi at a breakpoint ends one interval and starts the next: evaluated once.
            std::size_t known = ts.size();
            double f_known = 0;
            for (std::size_t i = 0; i + 1 < ts.size(); ++i) {
                const double half = 0.5 * (ts[i + 1] - ts[i]);
                if (!(half > 1e-12)) continue;
                const double tm = ts[i] + half;
                const Vec3d pm = P0 + tm * D;
                const double f0 = known == i ? f_known : octree::phi_at(reader, P0 + ts[i] * D),
                             fm = octree::phi_at(reader, pm), f1 = octree::phi_at(reader, P0 + ts[i + 1] * D);
                known = i + 1;
                f_known = f1;
                const double alpha = (f0 - 2 * fm + f1) / (2 * half * half), beta = (f1 - f0) / (2 * half);
                if (alpha == 0) continue;
                const double x = -beta / (2 * alpha);
                if (!(std::abs(x) < half)) continue;
                const Vec3d q = pm + x * D;
                if (poly.strictly_inside(q)) visit(q);
            }
        }
    }
}

std::optional<Candidate> check_facet(const Delaunay& dt, const EdgeJob& job, const octree::SampleField& field,
                                     const octree::SampleField::Reader& reader, int max_cells)
{
    // The Voronoi facet: circumcentres of the cells around the edge, in circulation order.
    // Canonical order (determinism: the same facet gives bit-identical points whichever cell
    // represents its edge): circulate around the edge oriented from the lower id to the higher,
    // starting at the cell with the smallest sorted vertex ids.
    const Cell_handle c0 = job.edge.first;
    Vertex_handle va = c0->vertex(job.edge.second), vb = c0->vertex(job.edge.third);
    if (va->info().id > vb->info().id) std::swap(va, vb);
    Small<Cell_handle> ring;
    auto cc = dt.incident_cells(Delaunay::Edge(c0, c0->index(va), c0->index(vb))), done = cc;
    do {
        if (dt.is_infinite(cc)) return std::nullopt; // unbounded: the voxel-bound repair's business
        ring.push_back(cc);
    } while (++cc != done);
    auto key = [](const Cell_handle& c) {
        std::array<std::uint32_t, 4> k;
        for (int i = 0; i < 4; ++i) k[i] = c->vertex(i)->info().id;
        std::sort(k.begin(), k.end());
        return k;
    };
    std::size_t first = 0;
    auto first_key = key(ring[0]);
    for (std::size_t i = 1; i < ring.size(); ++i) {
        const auto k = key(ring[i]);
        if (k < first_key) {
            first = i;
            first_key = k;
        }
    }
    std::rotate(ring.begin(), ring.begin() + std::ptrdiff_t(first), ring.end());
    Small<Vec3d> P;
    for (const auto& c : ring) {
        const Point w = robust_circumcenter(c);
        P.push_back(field.world_to_index({w.x(), w.y(), w.z()}));
    }

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
    // (Unpadded, the needle along the grid edge of a 2x2x3 crop of quantized property seed 910
    // pierced such a facet at x = 1.266639 unseen, and M lost the needle's middle.)
    const double pad = 1e-9 * (1.0 + std::max({std::abs(lo[0]), std::abs(lo[1]), std::abs(lo[2]), std::abs(hi[0]),
                                               std::abs(hi[1]), std::abs(hi[2])}));
    lo -= Vec3d(pad);
    hi += Vec3d(pad);
    // Every point scanned below lies in the box: where F' keeps one sign on all of it, no point
    // can have the other. The Voronoi vertices lie in the box too, so P[0]'s sign is the one to
    // ask for, and a certified box has a boundary of that one sign: the other vertices need no
    // evaluation. (0.91 M of the 1.59 M facets of the first scan of a 128^3 protein end here.)
    const bool inside = octree::phi_at(reader, P[0]) >= 0;
    if (octree::one_sign_on_box(reader, lo, hi, inside)) return std::nullopt;

    // The boundary's signs: one sign, or an arc (mixed) that the edge-count test already checks.
    Small<char> P_inside(P.size());
    bool mixed = false;
    P_inside[0] = inside;
    for (std::size_t i = 1; i < P.size(); ++i) {
        P_inside[i] = octree::phi_at(reader, P[i]) >= 0;
        mixed |= P_inside[i] != inside;
    }
    const Polygon polygon(P, N);

    // Is q cut off from the boundary part of its own sign? With one boundary sign: iff q has the
    // other sign. With an arc: when no straight path in the facet leads from q to a Voronoi
    // vertex of its sign without crossing Sigma (an island; a strongly curved arc can also cause
    // this, and then the inserted point is still a point of Sigma in the facet, far from
    // the edge, which the refinement accepts).
    auto island = [&](const Vec3d& q, bool q_inside) {
        if (!mixed) return q_inside != inside;
        for (std::size_t i = 0; i < P.size(); ++i)
            if (bool(P_inside[i]) == q_inside && octree::segment_crossings(reader, q, P[i], max_cells).t.empty())
                return false;
        return true;
    };

    // The deepest point of an island.
    std::optional<Vec3d> witness;
    double depth = 0;
    grid_edge_points(polygon, lo, hi, field.face_slabs().h, [&](int, const Vec3d& q) {
        const double phi = octree::phi_at(reader, q);
        const bool q_inside = phi >= 0;
        if (std::abs(phi) <= depth) return;
        if (!island(q, q_inside)) return;
        depth = std::abs(phi);
        witness = q;
    });
    grid_face_extrema(reader, polygon, lo, hi, [&](const Vec3d& q) {
        const double phi = octree::phi_at(reader, q);
        if (std::abs(phi) <= depth || !island(q, phi >= 0)) return;
        depth = std::abs(phi);
        witness = q;
    });
    if (!witness) return std::nullopt;

    // Sigma on the way from the witness to each Voronoi vertex: take the crossing farthest from
    // the Delaunay edge (paper, CBP_VF).
    const Point pa = job.edge.first->vertex(job.edge.second)->point();
    const Point pb = job.edge.first->vertex(job.edge.third)->point();
    const K::Segment_3 ab(pa, pb);
    std::optional<Candidate> best;
    double best_d = -1;
    for (const auto& p : P) {
        const auto x = octree::segment_crossings(reader, *witness, p, max_cells);
        if (x.t.empty()) continue;
        const Vec3d s = *witness + x.t.front() * (p - *witness);
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
        from.swap(touched_);
    }
    first_ = false;
    touched_.clear();
    const auto by_edge_then_order = [](const EdgeJob& x, const EdgeJob& y) {
        return std::tie(x.a, x.b, x.order) < std::tie(y.a, y.b, y.order);
    };
    const auto same_edge = [](const EdgeJob& x, const EdgeJob& y) { return x.a == y.a && x.b == y.b; };
    // The edges of a star to check, one job per edge (the first found represents it).
    const auto star_edges = [&](Vertex_handle v, const std::vector<Cell_handle>& cells, std::vector<EdgeJob>& out) {
        out.clear();
        for (const Cell_handle& c : cells)
            for (int i = 0; i < 4; ++i)
                for (int j = i + 1; j < 4; ++j) {
                    const auto va = c->vertex(i), vb = c->vertex(j);
                    if (first && va != v && vb != v) continue; // only the edges at v
                    if (dt.is_infinite(va) || dt.is_infinite(vb)) continue;
                    if (!va->info().on_surface() && !vb->info().on_surface()) continue;
                    const auto ia = va->info().id, ib = vb->info().id;
                    if (first && va->info().on_surface() && vb->info().on_surface() && v->info().id != std::min(ia, ib))
                        continue; // found from its other end
                    // order: when it was found, so the first found of each edge sorts first
                    // (a stable sort by edge, without stable_sort's buffer per vertex).
                    out.push_back({Delaunay::Edge(c, i, j), std::min(ia, ib), std::max(ia, ib), std::uint32_t(out.size())});
                }
        std::sort(out.begin(), out.end(), by_edge_then_order);
        out.erase(std::unique(out.begin(), out.end(), same_edge), out.end());
    };
    struct Found {
        EdgeJob job;
        Candidate candidate;
    };
    std::vector<Found> found;
    // A chunk of vertices at a time: an edge is seen from every cell around it, and the raw
    // lists of all the E/N vertices of a 250 x 212 x 289 protein would be gigabytes.
    constexpr std::size_t kChunk = std::size_t(1) << 15;
    if (first) {
        // The first scan finds each edge from exactly one vertex (the filter above), so a
        // vertex's list is all its edges' jobs: each is checked right away, while the star's
        // cells are at hand, with no list of all 1.6 M jobs of a 128^3 protein to sort.
        // (Nothing is flagged before the first scan.)
        std::vector<std::vector<Found>> per_vertex;
        tbb::enumerable_thread_specific<std::vector<EdgeJob>> lists;
        tbb::enumerable_thread_specific<octree::SampleField::Reader> readers([&] { return octree::SampleField::Reader(field); });
        for (std::size_t begin = 0; begin < from.size(); begin += kChunk) {
            const std::size_t end = std::min(begin + kChunk, from.size());
            per_vertex.assign(end - begin, {});
            for_each_star(from, begin, end, [&](std::size_t k, const std::vector<Cell_handle>& cells) {
                auto& jobs = lists.local();
                star_edges(from[k], cells, jobs);
                const auto& reader = readers.local();
                for (const EdgeJob& job : jobs)
                    if (auto c = check_facet(dt, job, field, reader, max_cells)) per_vertex[k - begin].push_back({job, *c});
            });
            for (auto& list : per_vertex) found.insert(found.end(), list.begin(), list.end());
        }
    } else {
        std::vector<EdgeJob> jobs;
        std::vector<std::vector<EdgeJob>> per_vertex;
        for (std::size_t begin = 0; begin < from.size(); begin += kChunk) {
            const std::size_t end = std::min(begin + kChunk, from.size());
            per_vertex.assign(end - begin, {});
            for_each_star(from, begin, end, [&](std::size_t k, const std::vector<Cell_handle>& cells) {
                per_vertex[k - begin].reserve(6 * cells.size());
                star_edges(from[k], cells, per_vertex[k - begin]);
            });
            for (auto& list : per_vertex) {
                for (EdgeJob& job : list) {
                    job.order = std::uint32_t(jobs.size());
                    jobs.push_back(job);
                }
                list = {};
            }
        }
        for (const auto& [va, vb] : flagged_) {
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
    }
    flagged_.clear();
    // In id order of the edges (the first scan found them by vertex).
    std::sort(found.begin(), found.end(),
              [](const Found& x, const Found& y) { return std::tie(x.job.a, x.job.b) < std::tie(y.job.a, y.job.b); });
    std::vector<Candidate> out;
    for (const Found& f : found) {
        out.push_back(f.candidate);
        const auto& e = f.job.edge;
        flagged_.push_back({e.first->vertex(e.second), e.first->vertex(e.third)});
    }
    return out;
}

} // namespace isodel::mesher
