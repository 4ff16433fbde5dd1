#include "refinement/hausdorff_refinement.h"

#include "geometry/closest_on_triangle.h"
#include "refinement/triangle_to_surface.h"
#include "octree/segment_walk.h"

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

struct Tri {
    Vec3d a, b, c;
};

/// An edge by the ids of its vertices (in a FacetKey's order), as one integer to sort by.
std::uint64_t edge_of(std::uint32_t a, std::uint32_t b) { return (std::uint64_t(a) << 32) | b; }

/// The three edges of a facet.
std::array<std::uint64_t, 3> edges_of(const FacetKey& key)
{
    const auto& k = key.v;
    return std::array<std::uint64_t, 3>{edge_of(k[0], k[1]), edge_of(k[0], k[2]), edge_of(k[1], k[2])};
}

/// The edges of the facets to check, sorted, without repeats.
std::vector<std::uint64_t> wanted_edges(const std::vector<const FacetCache::Entry*>& todo)
{
    std::vector<std::uint64_t> wanted;
    wanted.reserve(3 * todo.size());
    for (const auto* e : todo)
        for (const std::uint64_t edge : edges_of(e->key)) wanted.push_back(edge);
    tbb::parallel_sort(wanted.begin(), wanted.end());
    wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
    return wanted;
}

/// Per restricted facet, bit j set when its edge j (edges_of) is wanted.
std::vector<std::uint8_t> wanted_edge_bits(const std::vector<const FacetCache::Entry*>& restricted,
                                           const std::vector<std::uint64_t>& wanted)
{
    // A wanted edge's triangles have both its vertices: a facet with fewer than two marked
    // vertices has no wanted edge. (Later rounds want only a small fraction of the edges, so
    // binary searches for every facet's edges would cost far more than the pairs they find.)
    std::uint32_t top = 0;
    for (const std::uint64_t edge : wanted) top = std::max({top, std::uint32_t(edge >> 32), std::uint32_t(edge)});
    std::vector<char> marked(std::size_t(top) + 1, 0);
    for (const std::uint64_t edge : wanted) marked[std::uint32_t(edge >> 32)] = marked[std::uint32_t(edge)] = 1;
    const auto is_marked = [&](std::uint32_t id) { return id < marked.size() && marked[id]; };
    std::vector<std::uint8_t> hits(restricted.size(), 0); // bit j: edge j is wanted
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, restricted.size(), 4096), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const auto& k = restricted[i]->key.v;
            if (int(is_marked(k[0])) + int(is_marked(k[1])) + int(is_marked(k[2])) < 2) continue;
            const auto edges = edges_of(restricted[i]->key);
            for (int j = 0; j < 3; ++j)
                if (std::binary_search(wanted.begin(), wanted.end(), edges[j])) hits[i] |= std::uint8_t(1u << j);
        }
    });
    return hits;
}

} // namespace

/// A restricted triangle and one of its edges that a facet to check has too.
struct HausdorffRefinement::EdgeTriangle {
    std::uint64_t edge;
    Tri tri;
};

/// Per facet to check (in the order of the facets to check): whether it fails, and where
/// M -> Sigma fails, the projection of the worst sample (a point of Sigma where the error is),
/// which is inserted instead of p, which may already be a vertex.
struct HausdorffRefinement::Verdicts {
    std::vector<char> bad;
    std::vector<std::optional<Vec3d>> at;
};

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
    const std::vector<const FacetCache::Entry*> todo = facets_to_check(restricted);
    if (todo.empty()) return {};
    // Triangles around each restricted edge, for the Sigma -> M check of p.
    const std::vector<EdgeTriangle> around = triangles_around_edges(restricted, todo);
    Verdicts verdicts = check_facets(todo, around);
    std::vector<FacetKey> passing; // in todo's order: sorted
    std::vector<Candidate> out = refinement_points(todo, verdicts, passing);
    if (!passing.empty()) {
        std::vector<FacetKey> merged;
        merged.reserve(passed_.size() + passing.size());
        std::merge(passed_.begin(), passed_.end(), passing.begin(), passing.end(), std::back_inserter(merged));
        passed_.swap(merged);
    }
    return out;
}

std::vector<const FacetCache::Entry*>
HausdorffRefinement::facets_to_check(const std::vector<const FacetCache::Entry*>& restricted) const
{
    std::vector<const FacetCache::Entry*> todo;
    assert(std::is_sorted(restricted.begin(), restricted.end(),
                          [](const auto* x, const auto* y) { return x->key < y->key; }));
    auto p = passed_.begin(); // both sorted by key
    for (const auto* e : restricted) {
        while (p != passed_.end() && *p < e->key) ++p;
        if (p == passed_.end() || e->key < *p) todo.push_back(e);
    }
    return todo;
}

std::vector<HausdorffRefinement::EdgeTriangle>
HausdorffRefinement::triangles_around_edges(const std::vector<const FacetCache::Entry*>& restricted,
                                            const std::vector<const FacetCache::Entry*>& todo)
{
    // The restricted triangles around each edge of the facets to check: (edge, triangle) pairs
    // sorted by edge, found by binary search. Only those edges are wanted (most rounds check a
    // few hundred of 10^5 facets); the pairs are found and filled in parallel.
    const std::vector<std::uint64_t> wanted = wanted_edges(todo);
    const std::vector<std::uint8_t> hits = wanted_edge_bits(restricted, wanted);
    std::vector<std::size_t> first(restricted.size() + 1, 0);
    for (std::size_t i = 0; i < restricted.size(); ++i)
        first[i + 1] = first[i] + std::size_t((hits[i] & 1) + ((hits[i] >> 1) & 1) + ((hits[i] >> 2) & 1));
    std::vector<EdgeTriangle> around(first.back());
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
    tbb::parallel_sort(around.begin(), around.end(),
                       [](const EdgeTriangle& x, const EdgeTriangle& y) { return x.edge < y.edge; });
    return around;
}

HausdorffRefinement::Verdicts HausdorffRefinement::check_facets(const std::vector<const FacetCache::Entry*>& todo,
                                                                const std::vector<EdgeTriangle>& around) const
{
    const double limit = 0.7 * eps_;
    const double step_cap = 0.5 * field_.min_voxel_edge();
    Verdicts verdicts;
    std::vector<char>& bad = verdicts.bad;
    bad.assign(todo.size(), 0);
    std::vector<std::optional<Vec3d>>& at = verdicts.at;
    at.resize(todo.size());
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
                                           [](const EdgeTriangle& x, std::uint64_t y) { return x.edge < y; });
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
    return verdicts;
}

std::vector<Candidate> HausdorffRefinement::refinement_points(const std::vector<const FacetCache::Entry*>& todo,
                                                              Verdicts& verdicts, std::vector<FacetKey>& passing) const
{
    const std::vector<char>& bad = verdicts.bad;
    std::vector<std::optional<Vec3d>>& at = verdicts.at;
    std::vector<Candidate> out;
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
        out.push_back({x, PointKind::Geometry, spacing, e->key, e->key.v[0]});
    }
    return out;
}

} // namespace isodel::mesher
