#include "mesher/hausdorff_refinement.h"

#include "geometry/closest_on_triangle.h"
#include "mesher/triangle_to_surface.h"
#include "octree/cell_interpolant.h"
#include "octree/segment_walk.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <optional>
#include <vector>

namespace isodel::mesher {
namespace {

using Vec3d = openvdb::Vec3d;
using detail::TriangleToSurface;

const FacetKey& key_of(const FacetKey& k) { return k; }
const FacetKey& key_of(const FacetCache::Entry* e) { return e->key; }

struct Tri {
    Vec3d a, b, c;
};

} // namespace

HausdorffRefinement::HausdorffRefinement(const octree::SampleField& field, double eps,
                                         std::vector<openvdb::Coord> crossed_cells, double snap_radius)
    : field_(field), eps_(eps), snap_radius_(snap_radius), crossed_cells_(std::move(crossed_cells))
{
    const Vec3d o = field.index_to_world(Vec3d(0.0));
    for (int k = 0; k < 3; ++k) {
        Vec3d e(0.0);
        e[k] = 1;
        const Vec3d col = field.index_to_world(e) - o;
        for (int r = 0; r < 3; ++r) index_to_world_(r, k) = col[r];
    }
    world_to_index_ = index_to_world_.inverse();
}

std::vector<Candidate> HausdorffRefinement::violations(const std::vector<const FacetCache::Entry*>& restricted)
{
    // Triangles around each restricted edge, for the Sigma -> M check of p.
    std::vector<const FacetCache::Entry*> todo;
    {
        assert(std::is_sorted(restricted.begin(), restricted.end(),
                              [](const auto* x, const auto* y) { return x->key < y->key; }));
        auto p = passed_.begin(); // both sorted by key
        for (const auto* e : restricted) {
            while (p != passed_.end() && *p < e->key) ++p;
            if (p == passed_.end() || e->key < *p) todo.push_back(e);
        }
    }
    if (todo.empty()) return {};
    // The restricted triangles around each edge of the facets to check: (edge, triangle) pairs
    // sorted by edge, found by binary search. Only those edges are wanted (most rounds check a
    // few hundred of 10^5 facets); the pairs are found and filled in parallel.
    const auto edge_of = [](std::uint32_t a, std::uint32_t b) { return (std::uint64_t(a) << 32) | b; };
    const auto edges_of = [&](const FacetKey& key) {
        const auto& k = key.v;
        return std::array<std::uint64_t, 3>{edge_of(k[0], k[1]), edge_of(k[0], k[2]), edge_of(k[1], k[2])};
    };
    std::vector<std::uint64_t> wanted;
    wanted.reserve(3 * todo.size());
    for (const auto* e : todo)
        for (const std::uint64_t edge : edges_of(e->key)) wanted.push_back(edge);
    tbb::parallel_sort(wanted.begin(), wanted.end());
    wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
    std::vector<std::uint8_t> hits(restricted.size(), 0); // bit j: edge j is wanted
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, restricted.size(), 4096), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const auto edges = edges_of(restricted[i]->key);
            for (int j = 0; j < 3; ++j)
                if (std::binary_search(wanted.begin(), wanted.end(), edges[j])) hits[i] |= std::uint8_t(1u << j);
        }
    });
    std::vector<std::size_t> first(restricted.size() + 1, 0);
    for (std::size_t i = 0; i < restricted.size(); ++i)
        first[i + 1] = first[i] + std::size_t((hits[i] & 1) + ((hits[i] >> 1) & 1) + ((hits[i] >> 2) & 1));
    struct Around {
        std::uint64_t edge;
        Tri tri;
    };
    std::vector<Around> around(first.back());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, restricted.size(), 4096), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            if (!hits[i]) continue;
            const auto vs = facet_vertices(restricted[i]->facet);
            const Tri t{to_vdb(vs[0]->point()), to_vdb(vs[1]->point()), to_vdb(vs[2]->point())};
            const auto edges = edges_of(restricted[i]->key);
            std::size_t at = first[i];
            for (int j = 0; j < 3; ++j)
                if (hits[i] & (1u << j)) around[at++] = {edges[j], t};
        }
    });
    // By edge only: the triangles of one edge are read for a minimum, in any order.
    tbb::parallel_sort(around.begin(), around.end(), [](const Around& x, const Around& y) { return x.edge < y.edge; });
    const double limit = 0.7 * eps_;
    const double step_cap = 0.5 * field_.min_voxel_edge();
    std::vector<char> bad(todo.size(), 0);
    // Where M -> Sigma fails, the projection of the worst sample (a point of Sigma where the
    // error is) is inserted instead of p, which may already be a vertex.
    std::vector<std::optional<Vec3d>> at(todo.size());
    tbb::enumerable_thread_specific<octree::SampleField::Reader> readers([&] { return octree::SampleField::Reader(field_); });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, todo.size(), 64), [&](const auto& r) {
        auto& reader = readers.local();
        TriangleToSurface to_surface(reader, world_to_index_, step_cap, limit, 0.25 * eps_, 2.0 * eps_);
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const auto* e = todo[i];
            const auto vs = facet_vertices(e->facet);
            const Vec3d a = to_vdb(vs[0]->point()), b = to_vdb(vs[1]->point()), c = to_vdb(vs[2]->point());
            // How far each vertex may be from Sigma: 0, or the snap radius for a snapped one.
            double off[3];
            for (int k = 0; k < 3; ++k) off[k] = vs[k]->info().kind == PointKind::Snapped ? snap_radius_ : 0.0;
            const Vec3d p = to_vdb(e->record->surface_point);
            // Sigma -> M at p.
            double dp = (geometry::closest_on_triangle(p, a, b, c) - p).length();
            for (const std::uint64_t edge : edges_of(e->key)) {
                auto it = std::lower_bound(around.begin(), around.end(), edge,
                                           [](const Around& x, std::uint64_t y) { return x.edge < y; });
                for (; it != around.end() && it->edge == edge; ++it)
                    dp = std::min(dp, (geometry::closest_on_triangle(p, it->tri.a, it->tri.b, it->tri.c) - p).length());
            }
            if (dp > limit) {
                bad[i] = 1;
                continue;
            }
            // M -> Sigma (triangle_to_surface.h).
            if (!to_surface.check(a, b, c, off, p, at[i])) bad[i] = 1;
        }
    });
    std::vector<Candidate> out;
    std::vector<FacetKey> passing; // in todo's order: sorted
    for (std::size_t i = 0; i < todo.size(); ++i) {
        if (!bad[i]) {
            passing.push_back(todo[i]->key);
            continue;
        }
        const auto* e = todo[i];
        double spacing = INFINITY;
        for (const auto& v : facet_vertices(e->facet))
            spacing = std::min(spacing, std::sqrt(CGAL::squared_distance(v->point(), e->record->surface_point)));
        Point x = e->record->surface_point;
        // q only helps when it lies in the facet's surface Delaunay ball (centre p, through its
        // vertices): otherwise inserting it leaves the facet in place.
        const double ball = std::sqrt(CGAL::squared_distance(x, facet_vertices(e->facet)[0]->point()));
        if (at[i] && (*at[i] - to_vdb(x)).length() >= 0.999 * ball) at[i].reset();
        if (at[i]) {
            x = Point((*at[i])[0], (*at[i])[1], (*at[i])[2]);
            spacing = INFINITY;
            for (const auto& v : facet_vertices(e->facet))
                spacing = std::min(spacing, std::sqrt(CGAL::squared_distance(v->point(), x)));
        }
        if (keep_ && !keep_(x)) {
            passing.push_back(e->key); // not ours (set_filter)
            continue;
        }
        out.push_back({x, PointKind::Geometry, spacing, e->key});
    }
    if (!passing.empty()) {
        std::vector<FacetKey> merged;
        merged.reserve(passed_.size() + passing.size());
        std::merge(passed_.begin(), passed_.end(), passing.begin(), passing.end(), std::back_inserter(merged));
        passed_.swap(merged);
    }
    return out;
}

std::vector<Candidate> HausdorffRefinement::crease_violations(const std::vector<const FacetCache::Entry*>& restricted)
{
    // Distances only (no combinatorial decision): a plain double kernel is enough here.
    using KD = CGAL::Simple_cartesian<double>;
    using Tree = CGAL::AABB_tree<CGAL::AABB_traits<KD, CGAL::AABB_triangle_primitive<KD, std::vector<KD::Triangle_3>::const_iterator>>>;
    std::vector<KD::Triangle_3> tris(restricted.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, restricted.size(), 4096), [&](const auto& r) {
        auto kp = [](const Point& p) { return KD::Point_3(p.x(), p.y(), p.z()); };
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const auto vs = facet_vertices(restricted[i]->facet);
            tris[i] = KD::Triangle_3(kp(vs[0]->point()), kp(vs[1]->point()), kp(vs[2]->point()));
        }
    });
    if (tris.empty()) return {};
    // A cell that passed before still passes while the triangles nearest to its samples are in
    // M: d(s, M) <= d(s, T) for every T in M. Only the other cells are sampled again.
    // `restricted` is in key order (FacetCache::active()): membership is a binary search.
    const auto in_m = [&](const FacetKey& k) {
        return std::binary_search(restricted.begin(), restricted.end(), k,
                                  [](const auto& x, const auto& y) { return key_of(x) < key_of(y); });
    };
    crease_state_.resize(crossed_cells_.size(), CreaseState::Unknown);
    crease_witness_.resize(crossed_cells_.size());
    std::vector<char> recheck(crossed_cells_.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, crossed_cells_.size(), 1024), [&](const auto& r) {
        for (std::size_t ci = r.begin(); ci != r.end(); ++ci)
            recheck[ci] = crease_state_[ci] == CreaseState::Unknown ||
                          (crease_state_[ci] == CreaseState::Passed &&
                           !std::all_of(crease_witness_[ci].begin(), crease_witness_[ci].end(), in_m));
    });
    std::vector<std::size_t> todo;
    for (std::size_t ci = 0; ci < crossed_cells_.size(); ++ci)
        if (recheck[ci]) todo.push_back(ci);
    if (todo.empty()) return {};
    const double limit = 0.7 * eps_;
    // The tree holds only the triangles that can be within `limit` of a sample of a cell to
    // check (the samples lie in their cells): after the first call a few hundred cells of 10^5
    // are checked, and building a tree of all of M (sequential in CGAL) cost more than the
    // queries. A sample farther than `limit` from these is farther from all of M too.
    std::vector<std::size_t> near(tris.size());
    std::size_t n_near = 0;
    if (4 * todo.size() >= crossed_cells_.size()) {
        for (std::size_t i = 0; i < tris.size(); ++i) near[i] = i;
        n_near = tris.size();
    } else {
        std::vector<openvdb::Coord> cells(todo.size());
        for (std::size_t ti = 0; ti < todo.size(); ++ti) cells[ti] = crossed_cells_[todo[ti]];
        std::sort(cells.begin(), cells.end());
        // World distance r is at most r |world_to_index|_F index units along any axis.
        double frob = 0;
        for (int r = 0; r < 3; ++r)
            for (int k = 0; k < 3; ++k) frob += world_to_index_(r, k) * world_to_index_(r, k);
        const double margin = limit * std::sqrt(frob) * (1 + 1e-9);
        std::vector<char> keep(tris.size(), 0);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tris.size(), 4096), [&](const auto& r) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) {
                Vec3d lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
                for (int k = 0; k < 3; ++k) {
                    const Vec3d x = field_.world_to_index(Vec3d(tris[i][k].x(), tris[i][k].y(), tris[i][k].z()));
                    lo = openvdb::math::minComponent(lo, x);
                    hi = openvdb::math::maxComponent(hi, x);
                }
                // Cells [c, c + 1] meeting the box [lo - margin, hi + margin].
                const openvdb::Coord a(int(std::ceil(lo[0] - margin)) - 1, int(std::ceil(lo[1] - margin)) - 1,
                                       int(std::ceil(lo[2] - margin)) - 1);
                const openvdb::Coord b(int(std::floor(hi[0] + margin)), int(std::floor(hi[1] + margin)),
                                       int(std::floor(hi[2] + margin)));
                for (int x = a[0]; x <= b[0] && !keep[i]; ++x)
                    for (int y = a[1]; y <= b[1] && !keep[i]; ++y)
                        for (int z = a[2]; z <= b[2] && !keep[i]; ++z)
                            if (std::binary_search(cells.begin(), cells.end(), openvdb::Coord(x, y, z))) keep[i] = 1;
            }
        });
        for (std::size_t i = 0; i < tris.size(); ++i)
            if (keep[i]) near[n_near++] = i;
    }
    near.resize(n_near);
    std::vector<KD::Triangle_3> near_tris(near.size());
    for (std::size_t k = 0; k < near.size(); ++k) near_tris[k] = tris[near[k]];
    // No triangle near the cells to check: every sample is farther than `limit` from M and
    // fails; any one triangle keeps the tree non-empty (its distances exceed `limit` too).
    if (near_tris.empty()) {
        near_tris.push_back(tris.front());
        near.push_back(0);
    }
    Tree tree(near_tris.cbegin(), near_tris.cend());
    tree.accelerate_distance_queries();
    // Lines every eps/2 (world) on each face; R lines per unit of index.
    const int R = std::clamp(int(std::ceil(2.0 * field_.min_voxel_edge() / eps_)), 2, 64);
    const octree::FaceSlabs& slabs = field_.face_slabs();
    std::vector<std::vector<Candidate>> found(todo.size());
    tbb::enumerable_thread_specific<octree::SampleField::Reader> readers([&] { return octree::SampleField::Reader(field_); });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, todo.size(), 16), [&](const auto& r) {
        auto& reader = readers.local();
        for (std::size_t ti = r.begin(); ti != r.end(); ++ti) {
            const std::size_t ci = todo[ti];
            const openvdb::Coord c = crossed_cells_[ci];
            double corner[8];
            reader.cell_corners(c, corner);
            const auto f = octree::Trilinear::from_corners(corner);
            double worst = limit;
            Vec3d worst_at;
            bool any = false;
            std::vector<FacetKey> witness;
            auto last = near_tris.cend();
            // Faces x = 0, 1; y = 0, 1; z = 0, 1 of the cell; on each, lines along the two other axes.
            for (int axis = 0; axis < 3; ++axis)
                for (int side = 0; side < 2; ++side)
                    for (int dir = 0; dir < 3; ++dir) {
                        if (dir == axis) continue;
                        const int other = 3 - axis - dir;
                        for (int i = 1; i < R; ++i) {
                            Vec3d p0(0.0);
                            p0[axis] = side;
                            p0[other] = double(i) / R;
                            Vec3d p1 = p0;
                            p1[dir] = 1;
                            const double v0 = f(p0[0], p0[1], p0[2]), v1 = f(p1[0], p1[1], p1[2]);
                            if ((v0 >= 0) == (v1 >= 0)) continue;
                            any = true;
                            const Vec3d l = p0 + (p1 - p0) * (v0 / (v0 - v1)); // F is linear here
                            // Sigma' (face_slabs.h) has this crease at the slab's boundary on
                            // the cell's side: the same curve, mapped, h inside the cell.
                            Vec3d m = slabs.from_sample(c.asVec3d() + l);
                            m[axis] += side == 0 ? slabs.h : -slabs.h;
                            const Vec3d w = field_.index_to_world(m);
                            const KD::Point_3 q(w[0], w[1], w[2]);
                            // d(q, M) <= d(q, T) for T in M: the triangle nearest to the previous
                            // sample (eps/2 away along the crease) usually passes q too, without a
                            // tree query; the tree is asked only otherwise.
                            if (last != near_tris.cend()) {
                                const KD::Triangle_3& t = *last;
                                const Vec3d cl = geometry::closest_on_triangle(
                                    w, Vec3d(t[0].x(), t[0].y(), t[0].z()), Vec3d(t[1].x(), t[1].y(), t[1].z()),
                                    Vec3d(t[2].x(), t[2].y(), t[2].z()));
                                if ((cl - w).length() <= limit) {
                                    witness.push_back(restricted[near[std::size_t(last - near_tris.cbegin())]]->key);
                                    continue;
                                }
                            }
                            const auto cp = tree.closest_point_and_primitive(q);
                            const double d = std::sqrt(CGAL::squared_distance(q, cp.first));
                            last = cp.second;
                            witness.push_back(restricted[near[std::size_t(cp.second - near_tris.cbegin())]]->key);
                            if (d > worst) {
                                worst = d;
                                worst_at = w;
                            }
                        }
                    }
            if (!any) {
                crease_state_[ci] = CreaseState::NoCrease;
            } else if (worst > limit) {
                crease_state_[ci] = CreaseState::Unknown;
                found[ti].push_back({Point(worst_at[0], worst_at[1], worst_at[2]), PointKind::Geometry, worst,
                                     FacetKey{{std::uint32_t(ci), 0xffffffffu, 0}}});
            } else {
                std::sort(witness.begin(), witness.end());
                witness.erase(std::unique(witness.begin(), witness.end()), witness.end());
                crease_state_[ci] = CreaseState::Passed;
                crease_witness_[ci] = std::move(witness);
            }
        }
    });
    std::vector<Candidate> out;
    for (auto& v : found)
        for (const Candidate& c : v) {
            if (keep_ && !keep_(c.p)) crease_state_[c.origin.v[0]] = CreaseState::NoCrease; // not ours (set_filter)
            else out.push_back(c);
        }
    return out;
}

} // namespace isodel::mesher
