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
    case Violation::FacetAngle: return "facet-angle";
    case Violation::Unbounded: return "voxel-bound";
    }
    return "?";
}

void filter_candidates(std::vector<Candidate>& candidates, const CandidateFilter& keep)
{
    if (!keep) return;
    candidates.erase(std::remove_if(candidates.begin(), candidates.end(), [&](const Candidate& c) { return !keep(c.p); }),
                     candidates.end());
}

std::vector<Candidate> facet_angle_violations(const std::vector<const FacetCache::Entry*>& restricted,
                                              double min_angle_deg, const CandidateFilter& keep)
{
    // sin^2 of the smallest angle from the law of sines: the smallest angle faces the shortest
    // edge, sin = 2 area / (product of the two other edges).
    const double s = std::sin(min_angle_deg * 3.14159265358979323846 / 180.0);
    std::vector<Candidate> out;
    for (const auto* e : restricted) {
        const auto vs = facet_vertices(e->facet);
        const Point &a = vs[0]->point(), &b = vs[1]->point(), &c = vs[2]->point();
        double l2[3] = {CGAL::squared_distance(b, c), CGAL::squared_distance(c, a), CGAL::squared_distance(a, b)};
        std::sort(l2, l2 + 3);
        const double area2 = CGAL::squared_area(a, b, c); // area^2
        // sin^2(min angle) = 4 area^2 / (l1^2 l2^2) with l1, l2 the two longer edges.
        if (4 * area2 < s * s * l2[1] * l2[2]) out.push_back(candidate_of(*e, PointKind::Geometry));
    }
    filter_candidates(out, keep);
    return out;
}

std::vector<Candidate> voronoi_edge_violations(const std::vector<FacetCache::Entry>& entries, const CandidateFilter& keep)
{
    std::vector<Candidate> out;
    for (const auto& e : entries) {
        if (e.overflow) return {};
        if (e.crossings > 1) out.push_back(candidate_of(e, PointKind::Topology));
    }
    filter_candidates(out, keep);
    return out;
}

ViolationReport find_violations(const Delaunay& dt, const FacetCache& cache, double eps, const CandidateFilter& keep)
{
    (void)dt;
    ViolationReport rep;
    const auto& active = cache.active();

    // Unbounded Voronoi edges of surface facets mean a hole in G; the driver repairs it.
    for (const auto& e : active)
        if (e.overflow) rep.candidates.push_back({Point(), PointKind::Grid, 0, e.key});
    if (!rep.candidates.empty()) {
        rep.kind = Violation::Unbounded;
        return rep;
    }

    // CBP_VE: insert the crossing farthest from the dual triangle.
    for (const auto& e : active)
        if (e.crossings > 1) rep.candidates.push_back(candidate_of(e, PointKind::Topology));
    filter_candidates(rep.candidates, keep);
    if (!rep.candidates.empty()) {
        rep.kind = Violation::VoronoiEdge;
        return rep;
    }

    std::vector<const FacetCache::Entry*> restricted;
    for (const auto& e : active)
        if (e.crossings == 1) restricted.push_back(&e);
    rep.restricted_facets = restricted.size();

    // Facets with a grid vertex: M's vertices must be samples of Sigma.
    for (const auto* e : restricted)
        if (!e->all_on_surface) rep.candidates.push_back(candidate_of(*e, PointKind::Topology));
    filter_candidates(rep.candidates, keep);
    if (!rep.candidates.empty()) {
        rep.kind = Violation::GridVertex;
        return rep;
    }

    // CBP_VF and CBP_VC from one pass over the restricted facets around each vertex. Vertex ids
    // are dense, so a counting sort groups them in O(n) (a comparison sort of the 3n incidences
    // took a third of the run time); within a vertex, facets stay in key order.
    std::uint32_t max_id = 0;
    for (const auto* e : restricted) max_id = std::max(max_id, e->key.v[2]);
    std::vector<std::uint32_t> first(restricted.empty() ? 1 : std::size_t(max_id) + 2, 0);
    for (const auto* e : restricted)
        for (int j = 0; j < 3; ++j) ++first[e->key.v[j] + 1];
    for (std::size_t i = 1; i < first.size(); ++i) first[i] += first[i - 1];
    std::vector<std::uint32_t> around(restricted.size() * 3);
    {
        std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
        for (std::size_t i = 0; i < restricted.size(); ++i)
            for (int j = 0; j < 3; ++j) around[fill[restricted[i]->key.v[j]]++] = std::uint32_t(i);
    }
    auto point_of = [&](std::uint32_t facet, std::uint32_t id) {
        for (const auto& v : facet_vertices(restricted[facet]->facet))
            if (v->info().id == id) return v->point();
        return Point();
    };
    std::vector<std::size_t> bad_edge_facets, bad_vertex_facets;
    std::vector<int> parent;
    std::vector<std::pair<std::uint32_t, int>> spokes;
    for (std::uint32_t p = 0; p + 1 < first.size(); ++p) {
        const std::uint32_t* fs = around.data() + first[p];
        const std::size_t n = first[p + 1] - first[p];
        if (n == 0) continue;
        spokes.clear();
        for (std::size_t m = 0; m < n; ++m) {
            const FacetKey& k = restricted[fs[m]]->key;
            for (int q = 0; q < 3; ++q)
                if (k.v[q] != p) spokes.push_back({k.v[q], int(m)});
        }
        std::sort(spokes.begin(), spokes.end());
        // CBP_VF (Section 4.3, no interior loops): the Voronoi facet dual to edge (p, w) meets
        // Sigma in one arc iff exactly two of its boundary Voronoi edges cross Sigma; otherwise
        // insert the surface point farthest from the edge. Each edge is judged at p < w.
        for (std::size_t s = 0; s < spokes.size();) {
            std::size_t t = s;
            while (t < spokes.size() && spokes[t].first == spokes[s].first) ++t;
            const std::uint32_t w = spokes[s].first;
            if (w > p && t - s != 2) {
                const std::uint32_t f0 = fs[spokes[s].second];
                const K::Segment_3 seg(point_of(f0, p), point_of(f0, w));
                std::size_t best = f0;
                double bd = -1;
                for (std::size_t m = s; m < t; ++m) {
                    const std::uint32_t f = fs[spokes[m].second];
                    const double d = CGAL::squared_distance(restricted[f]->record->surface_point, seg);
                    if (d > bd) {
                        bd = d;
                        best = f;
                    }
                }
                bad_edge_facets.push_back(best);
            }
            s = t;
        }
        if (!bad_edge_facets.empty()) continue; // CBP_VF first: CBP_VC is not looked at then
        // CBP_VC: with every Voronoi edge and facet a closed ball, Vor(p) meets Sigma in a disk
        // iff the boundary of Vor(p) n Sigma is one curve (Theorem 4 rules out components inside
        // a cell, Theorem 5 positive genus on cubic grids): the restricted facets around p form
        // one cycle. Union facets that share an edge (p, w).
        parent.resize(n);
        std::iota(parent.begin(), parent.end(), 0);
        for (std::size_t s = 1; s < spokes.size(); ++s)
            if (spokes[s].first == spokes[s - 1].first)
                parent[find_root(parent, spokes[s].second)] = find_root(parent, spokes[s - 1].second);
        int roots = 0;
        for (std::size_t m = 0; m < n; ++m) roots += (find_root(parent, int(m)) == int(m));
        if (roots > 1) {
            // Insert the surface point farthest from p.
            const Point pp = point_of(fs[0], p);
            std::size_t best = fs[0];
            double bd = -1;
            for (std::size_t m = 0; m < n; ++m) {
                const double d = CGAL::squared_distance(restricted[fs[m]]->record->surface_point, pp);
                if (d > bd) {
                    bd = d;
                    best = fs[m];
                }
            }
            bad_vertex_facets.push_back(best);
        }
    }
    for (auto* bad : {&bad_edge_facets, &bad_vertex_facets}) {
        if (bad->empty()) continue;
        std::sort(bad->begin(), bad->end());
        bad->erase(std::unique(bad->begin(), bad->end()), bad->end());
        for (std::size_t i : *bad) rep.candidates.push_back(candidate_of(*restricted[i], PointKind::Topology));
        filter_candidates(rep.candidates, keep);
        if (rep.candidates.empty()) continue;
        rep.kind = bad == &bad_edge_facets ? Violation::VoronoiFacet : Violation::VoronoiCell;
        return rep;
    }

    // Step 5: geometric refinement.
    for (const auto* e : restricted)
        if (e->record->distance > eps) rep.candidates.push_back(candidate_of(*e, PointKind::Geometry));
    filter_candidates(rep.candidates, keep);
    if (!rep.candidates.empty()) rep.kind = Violation::Epsilon;
    return rep;
}

} // namespace isodel::mesher
