#include "mesher/closed_ball.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace isodel::mesher {
namespace {

double nearest_vertex_distance(const Facet& f, const Point& p)
{
    double d = INFINITY;
    for (const auto& v : facet_vertices(f)) d = std::min(d, std::sqrt(CGAL::squared_distance(p, v->point())));
    return d;
}

Candidate candidate_of(const FacetCache::Entry& e, PointKind kind)
{
    return {e.record->surface_point, kind, nearest_vertex_distance(e.facet, e.record->surface_point), e.key};
}

struct Incidence {
    std::uint32_t a, b; // vertex id(s); b unused for vertex incidences
    std::uint32_t other; // the third vertex (edges) / unused
    std::size_t facet;   // index into the restricted list
    bool operator<(const Incidence& o) const
    {
        return std::tie(a, b, facet) < std::tie(o.a, o.b, o.facet);
    }
};

int find_root(std::vector<int>& parent, int i)
{
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
}

} // namespace

const char* to_string(Violation v)
{
    switch (v) {
    case Violation::None: return "none";
    case Violation::GridCell: return "grid-cell";
    case Violation::VoronoiEdge: return "CBP_VE";
    case Violation::GridVertex: return "grid-vertex";
    case Violation::VoronoiFacet: return "CBP_VF";
    case Violation::FacetLoop: return "CBP_VF-loop";
    case Violation::VoronoiCell: return "CBP_VC";
    case Violation::Epsilon: return "epsilon";
    case Violation::Hausdorff: return "hausdorff";
    case Violation::Unbounded: return "voxel-bound";
    }
    return "?";
}

ViolationReport find_violations(const Delaunay& dt, const FacetCache& cache, double eps)
{
    (void)dt;
    ViolationReport rep;
    const auto& active = cache.active();

    // Unbounded Voronoi edges of surface facets mean a hole in G; the driver repairs it.
    for (const auto& e : active)
        if (e.record->overflow) rep.candidates.push_back({Point(), PointKind::Grid, 0, e.key});
    if (!rep.candidates.empty()) {
        rep.kind = Violation::Unbounded;
        return rep;
    }

    // CBP_VE: insert the crossing farthest from the dual triangle.
    for (const auto& e : active)
        if (e.record->crossings > 1) rep.candidates.push_back(candidate_of(e, PointKind::Topology));
    if (!rep.candidates.empty()) {
        rep.kind = Violation::VoronoiEdge;
        return rep;
    }

    std::vector<const FacetCache::Entry*> restricted;
    for (const auto& e : active)
        if (e.record->crossings == 1) restricted.push_back(&e);
    rep.restricted_facets = restricted.size();

    // Facets with a grid vertex: M's vertices must be samples of Sigma.
    for (const auto* e : restricted) {
        const auto vs = facet_vertices(e->facet);
        if (!vs[0]->info().on_surface() || !vs[1]->info().on_surface() || !vs[2]->info().on_surface())
            rep.candidates.push_back(candidate_of(*e, PointKind::Topology));
    }
    if (!rep.candidates.empty()) {
        rep.kind = Violation::GridVertex;
        return rep;
    }

    // CBP_VF: the Voronoi facet dual to edge (a,b) meets Sigma in one arc iff exactly two
    // Voronoi edges on its boundary cross Sigma (Section 4.3, no interior loops); otherwise
    // insert the surface point farthest from the edge.
    std::vector<Incidence> edges;
    edges.reserve(restricted.size() * 3);
    for (std::size_t i = 0; i < restricted.size(); ++i) {
        const FacetKey& k = restricted[i]->key;
        edges.push_back({k.v[0], k.v[1], k.v[2], i});
        edges.push_back({k.v[0], k.v[2], k.v[1], i});
        edges.push_back({k.v[1], k.v[2], k.v[0], i});
    }
    std::sort(edges.begin(), edges.end());
    std::vector<std::size_t> bad_edge_facets;
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i;
        while (j < edges.size() && edges[j].a == edges[i].a && edges[j].b == edges[i].b) ++j;
        if (j - i != 2) {
            // Farthest surface point from the Delaunay edge.
            const Facet& f0 = restricted[edges[i].facet]->facet;
            Point pa, pb;
            for (const auto& v : facet_vertices(f0)) {
                if (v->info().id == edges[i].a) pa = v->point();
                if (v->info().id == edges[i].b) pb = v->point();
            }
            const K::Segment_3 seg(pa, pb);
            std::size_t best = edges[i].facet;
            double bd = -1;
            for (std::size_t m = i; m < j; ++m) {
                const double d = CGAL::squared_distance(restricted[edges[m].facet]->record->surface_point, seg);
                if (d > bd) {
                    bd = d;
                    best = edges[m].facet;
                }
            }
            bad_edge_facets.push_back(best);
        }
        i = j;
    }
    if (!bad_edge_facets.empty()) {
        std::sort(bad_edge_facets.begin(), bad_edge_facets.end());
        bad_edge_facets.erase(std::unique(bad_edge_facets.begin(), bad_edge_facets.end()), bad_edge_facets.end());
        for (std::size_t i : bad_edge_facets) rep.candidates.push_back(candidate_of(*restricted[i], PointKind::Topology));
        rep.kind = Violation::VoronoiFacet;
        return rep;
    }

    // CBP_VC: with every Voronoi edge and facet a closed ball, Vor(p) meets Sigma in a disk iff
    // the boundary of Vor(p) n Sigma is one curve (Theorem 4 rules out components inside a cell,
    // Theorem 5 positive genus on cubic grids): the restricted facets around p form one cycle.
    std::vector<Incidence> around;
    around.reserve(restricted.size() * 3);
    for (std::size_t i = 0; i < restricted.size(); ++i) {
        const FacetKey& k = restricted[i]->key;
        for (int j = 0; j < 3; ++j) around.push_back({k.v[j], 0, 0, i});
    }
    std::sort(around.begin(), around.end());
    std::vector<std::size_t> bad_vertex_facets;
    std::vector<int> parent;
    for (std::size_t i = 0; i < around.size();) {
        std::size_t j = i;
        while (j < around.size() && around[j].a == around[i].a) ++j;
        const std::uint32_t p = around[i].a;
        // Union facets that share an edge (p, w).
        const std::size_t n = j - i;
        parent.resize(n);
        std::iota(parent.begin(), parent.end(), 0);
        std::vector<std::pair<std::uint32_t, int>> spokes;
        for (std::size_t m = 0; m < n; ++m) {
            const FacetKey& k = restricted[around[i + m].facet]->key;
            for (int q = 0; q < 3; ++q)
                if (k.v[q] != p) spokes.push_back({k.v[q], int(m)});
        }
        std::sort(spokes.begin(), spokes.end());
        for (std::size_t s = 1; s < spokes.size(); ++s)
            if (spokes[s].first == spokes[s - 1].first)
                parent[find_root(parent, spokes[s].second)] = find_root(parent, spokes[s - 1].second);
        int roots = 0;
        for (std::size_t m = 0; m < n; ++m) roots += (find_root(parent, int(m)) == int(m));
        if (roots > 1) {
            // Insert the surface point farthest from p.
            Point pp;
            for (const auto& v : facet_vertices(restricted[around[i].facet]->facet))
                if (v->info().id == p) pp = v->point();
            std::size_t best = around[i].facet;
            double bd = -1;
            for (std::size_t m = i; m < j; ++m) {
                const double d = CGAL::squared_distance(restricted[around[m].facet]->record->surface_point, pp);
                if (d > bd) {
                    bd = d;
                    best = around[m].facet;
                }
            }
            bad_vertex_facets.push_back(best);
        }
        i = j;
    }
    if (!bad_vertex_facets.empty()) {
        std::sort(bad_vertex_facets.begin(), bad_vertex_facets.end());
        bad_vertex_facets.erase(std::unique(bad_vertex_facets.begin(), bad_vertex_facets.end()), bad_vertex_facets.end());
        for (std::size_t i : bad_vertex_facets) rep.candidates.push_back(candidate_of(*restricted[i], PointKind::Topology));
        rep.kind = Violation::VoronoiCell;
        return rep;
    }

    // Step 5: geometric refinement.
    for (const auto* e : restricted)
        if (e->record->distance > eps) rep.candidates.push_back(candidate_of(*e, PointKind::Geometry));
    if (!rep.candidates.empty()) rep.kind = Violation::Epsilon;
    return rep;
}

} // namespace isodel::mesher
