#include "mesher/hausdorff_refinement.h"

#include "octree/cell_function.h"

#include "geometry/closest_on_triangle.h"
#include "geometry/triangle_corner_reach.h"

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
#include <cstdint>
#include <iterator>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace isodel::mesher {
namespace {

using Vec3d = openvdb::Vec3d;

/// The last cell Newton read, with its F': Newton's steps are short and the samples of one
/// triangle lie in a cell or two, so most projections start in the cell the previous one read.
struct LastCell {
    openvdb::Coord cell{std::numeric_limits<int>::min()};
    octree::CellFunction f;
};

/// Newton projection of a world point onto Sigma along the world gradient of phi. Returns false
/// when it does not converge (flat phi): the caller then has no bound from it.
bool project(const octree::SampleField::Reader& reader, LastCell& last, const openvdb::math::Mat3d& to_index,
             double step_cap, const Vec3d& w0, Vec3d& out)
{
    const auto& field = reader.field();
    Vec3d x = field.world_to_index(w0);
    const octree::CellFunction& f = last.f;
    const openvdb::math::Mat3d to_index_t = to_index.transpose();
    for (int it = 0; it < 30; ++it) {
        const openvdb::Coord c(int(std::floor(x[0])), int(std::floor(x[1])), int(std::floor(x[2])));
        if (c != last.cell) {
            last.f = octree::cell_function(reader, c);
            last.cell = c;
        }
        const Vec3d l = x - c.asVec3d();
        const double phi = f(l[0], l[1], l[2]);
        const Vec3d gw = to_index_t * f.gradient(l[0], l[1], l[2]); // world gradient
        const double g2 = gw.lengthSqr();
        if (!(g2 > 0)) return false;
        Vec3d dw = gw * (-phi / g2);
        const double len = dw.length();
        if (len > step_cap) dw *= step_cap / len;
        x += to_index * dw;
        if (len < 1e-10 * step_cap) {
            out = field.index_to_world(x);
            return true;
        }
    }
    return false;
}

/// The crossing of Sigma nearest to s on the segment s -/+ reach along n (Newton's fallback
/// where phi is flat).
bool along_normal(const octree::SampleField::Reader& reader, const Vec3d& s, Vec3d n, double reach, Vec3d& out)
{
    const double len = n.length();
    if (!(len > 0)) return false;
    n *= reach / len;
    const auto& field = reader.field();
    const Vec3d a = field.world_to_index(s - n), b = field.world_to_index(s + n);
    const auto sc = octree::segment_crossings(reader, a, b, 256);
    if (sc.overflow || sc.t.empty()) return false;
    double best = sc.t.front();
    for (double t : sc.t)
        if (std::abs(t - 0.5) < std::abs(best - 0.5)) best = t;
    out = field.index_to_world(a + best * (b - a));
    return true;
}

/// M -> Sigma on one triangle, as a bound: d(x, Sigma) <= d(s, Sigma) + |x - s|, and every point
/// of a triangle is within its corner reach r of a corner (geometry::triangle_corner_reach: the
/// circumradius, or half the longest edge L when not acute; r <= L / sqrt(3)). A sub-triangle
/// passes when the largest bound at its corners plus r is at most `pass`; otherwise it is split
/// in four at its edge midpoints, down to edges of `leaf`, where each corner must be within
/// `limit` of Sigma. That is the rule of a barycentric sample grid of spacing `leaf`
/// (pass = limit + leaf / sqrt(3) bounds the same distance) without projecting every grid
/// sample: a triangle lying on Sigma within a few hundredths of eps passes after a dozen Newton
/// projections instead of ~200. Splitting stops after kMaxDepth halvings: a sub-triangle still
/// longer than `leaf` there must pass the covering bound itself, so every pass is certified by
/// pass <= eps whatever the triangle's size.
/// A sample is projected once per triangle: the midpoint of an edge shared by two sub-triangles
/// is reached from both, so projections are remembered by the sample's position on the
/// triangle's finest sample grid (kMaxDepth halvings).
class TriangleToSurface {
public:
    TriangleToSurface(const octree::SampleField::Reader& reader, const openvdb::math::Mat3d& to_index, double step_cap,
                      double limit, double leaf, double reach)
        : reader_(reader), to_index_(to_index), step_cap_(step_cap), limit_(limit), leaf_(leaf),
          pass_(limit + leaf / std::sqrt(3.0)), reach_(reach), memo_(std::size_t(kGrid + 1) * (kGrid + 1))
    {
    }

    /// True when triangle abc is within the bound of Sigma. \p p is a point of Sigma (the
    /// facet's surface point), \p off how far each vertex may be from Sigma. On failure \p at is
    /// a point of Sigma near the offending sample when one was found.
    bool check(const Vec3d& a, const Vec3d& b, const Vec3d& c, const double off[3], const Vec3d& p,
               std::optional<Vec3d>& at)
    {
        p_ = p;
        normal_ = (b - a).cross(c - a);
        at_ = &at;
        if (++stamp_ == 0) { // wrapped: forget every stamp
            for (auto& m : memo_) m.stamp = 0;
            stamp_ = 1;
        }
        Corner A{a, off[0], true, {}, kGrid, 0, a}, B{b, off[1], true, {}, 0, kGrid, b},
            C{c, off[2], true, {}, 0, 0, c};
        return passes(A, B, C, 0);
    }

private:
    struct Corner {
        Vec3d s;
        double d;             ///< d(s, Sigma) <= d
        bool exact = false;   ///< d already includes the Newton projection
        std::optional<Vec3d> q; ///< that projection
        int u = 0, v = 0;       ///< barycentric weights of a and b on the finest grid (kGrid)
        Vec3d start;            ///< where Newton starts (a midpoint: between its ends' projections)
    };

    /// A corner's own point of Sigma when it has one: a midpoint's Newton start between the
    /// projections of its ends lies within the chord's sagitta of Sigma, closer than the
    /// midpoint itself, so Newton needs fewer steps; any point of Sigma bounds the distance.
    static const Vec3d& on_sigma(const Corner& x) { return x.q ? *x.q : x.s; }

    /// The projection of one sample of the current triangle (check()'s stamp).
    struct Projected {
        std::uint32_t stamp = 0;
        Vec3d s;                ///< the sample
        std::optional<Vec3d> q; ///< its Newton projection, when it converged
    };

    void tighten(Corner& x)
    {
        if (x.exact) return;
        x.exact = true;
        Projected& m = memo_[std::size_t(x.u) * (kGrid + 1) + std::size_t(x.v)];
        // The same grid position gives the same sample (midpoints are symmetric in their ends);
        // comparing s keeps that an optimisation, not an assumption.
        if (m.stamp != stamp_ || m.s != x.s) {
            m.stamp = stamp_;
            m.s = x.s;
            Vec3d q;
            m.q.reset();
            if (project(reader_, last_cell_, to_index_, step_cap_, x.start, q)) m.q = q;
        }
        if (m.q) {
            x.q = m.q;
            x.d = std::min(x.d, (*m.q - x.s).length());
        }
    }

    /// A point of Sigma near the failing corner x, for the caller to insert instead of p.
    void report(const Corner& x) const
    {
        Vec3d q;
        if (x.q) *at_ = x.q;
        else if (along_normal(reader_, x.s, normal_, reach_, q)) *at_ = q;
    }

    Corner midpoint(const Corner& x, const Corner& y) const
    {
        Corner m{0.5 * (x.s + y.s), 0.0, false, {}, (x.u + y.u) / 2, (x.v + y.v) / 2,
                 0.5 * (on_sigma(x) + on_sigma(y))};
        const double h = 0.5 * (x.s - y.s).length();
        m.d = std::min({x.d + h, y.d + h, (m.s - p_).length()});
        return m;
    }

    bool passes(Corner& A, Corner& B, Corner& C, int depth)
    {
        const double L = std::max({(B.s - A.s).length(), (C.s - B.s).length(), (A.s - C.s).length()});
        const double reach = geometry::triangle_corner_reach(A.s, B.s, C.s);
        const auto covered = [&] { return std::max({A.d, B.d, C.d}) + reach <= pass_; };
        if (covered()) return true;
        if (L <= leaf_) {
            for (Corner* x : {&A, &B, &C}) {
                if (x->d <= limit_) continue;
                tighten(*x);
                if (x->d <= limit_) continue;
                report(*x);
                return false;
            }
            return true;
        }
        tighten(A);
        tighten(B);
        tighten(C);
        if (covered()) return true;
        if (depth >= kMaxDepth) {
            // Edges still longer than `leaf` (a triangle over 32 leaves long): corners within
            // `limit` would not bound the points between them, so only the covering bound
            // passes; otherwise the triangle fails and its surface point p is inserted (or a
            // point of Sigma near a corner that is itself too far).
            for (const Corner* x : {&A, &B, &C})
                if (x->d > limit_) {
                    report(*x);
                    break;
                }
            return false;
        }
        Corner ab = midpoint(A, B), bc = midpoint(B, C), ca = midpoint(C, A);
        return passes(A, ab, ca, depth + 1) && passes(ab, B, bc, depth + 1) && passes(ca, bc, C, depth + 1) &&
               passes(ab, bc, ca, depth + 1);
    }

    static constexpr int kMaxDepth = 5; // 32 sub-edges per edge (the sample grid had at most 24)
    static constexpr int kGrid = 1 << kMaxDepth;
    const octree::SampleField::Reader& reader_;
    const openvdb::math::Mat3d& to_index_;
    double step_cap_, limit_, leaf_, pass_, reach_;
    Vec3d p_, normal_;
    std::optional<Vec3d>* at_ = nullptr;
    std::vector<Projected> memo_; ///< by (u, v) of the finest grid
    std::uint32_t stamp_ = 0;
    LastCell last_cell_;
};

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
            // M -> Sigma (TriangleToSurface above).
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
    std::vector<FacetKey> merged;
    merged.reserve(passed_.size() + passing.size());
    std::merge(passed_.begin(), passed_.end(), passing.begin(), passing.end(), std::back_inserter(merged));
    passed_.swap(merged);
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
