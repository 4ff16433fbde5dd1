// Check 2 (combinatorics of M): closed, 2-manifold, consistently oriented, components and genus.
// Everything is decided on indices except "degenerate", which uses CGAL's exact collinearity test.
#include "verify/checks.h"

#include <isodel/errors.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <numeric>
#include <tuple>

namespace isodel::verify {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

struct HalfEdge {
    std::int32_t lo, hi; // undirected edge (lo < hi)
    bool forward;        // the triangle traverses lo -> hi
    bool operator<(const HalfEdge& o) const { return std::tie(lo, hi) < std::tie(o.lo, o.hi); }
};

std::int32_t find(std::vector<std::int32_t>& p, std::int32_t x)
{
    while (p[std::size_t(x)] != x) x = p[std::size_t(x)] = p[std::size_t(p[std::size_t(x)])];
    return x;
}

/// Is the link of a vertex (its incident triangles' opposite edges) one cycle?
bool link_is_cycle(std::vector<std::pair<std::int32_t, std::int32_t>>& link)
{
    if (link.size() < 3) return false;
    // Every link vertex must have degree 2 ...
    std::vector<std::int32_t> ends;
    for (auto& e : link) {
        ends.push_back(e.first);
        ends.push_back(e.second);
    }
    std::sort(ends.begin(), ends.end());
    for (std::size_t i = 0; i < ends.size(); i += 2)
        if (ends[i] != ends[i + 1] || (i + 2 < ends.size() && ends[i + 2] == ends[i])) return false;
    // ... and the edges must form one cycle: walk it.
    std::size_t steps = 1;
    std::int32_t start = link[0].first, cur = link[0].second;
    std::vector<bool> used(link.size(), false);
    used[0] = true;
    while (cur != start) {
        bool moved = false;
        for (std::size_t i = 0; i < link.size(); ++i) {
            if (used[i]) continue;
            if (link[i].first == cur || link[i].second == cur) {
                cur = link[i].first == cur ? link[i].second : link[i].first;
                used[i] = true;
                moved = true;
                ++steps;
                break;
            }
        }
        if (!moved) return false;
    }
    return steps == link.size();
}

} // namespace

MeshTopologyReport mesh_topology(const SurfaceMesh& mesh, std::vector<int>& tri_component)
{
    MeshTopologyReport rep;
    const std::size_t nv = mesh.vertices.size(), nf = mesh.triangles.size();
    rep.vertices = nv;
    rep.triangles = nf;
    for (const auto& t : mesh.triangles)
        for (auto v : t)
            if (v < 0 || std::size_t(v) >= nv)
                throw InvalidInput("verify: mesh triangle references vertex " + std::to_string(v) +
                                   " of " + std::to_string(nv));

    auto point = [&](std::int32_t v) {
        const auto& p = mesh.vertices[std::size_t(v)];
        return K::Point_3(p[0], p[1], p[2]);
    };
    std::vector<bool> degenerate(nf, false), used(nv, false);
    std::vector<std::array<std::int32_t, 3>> sorted(nf);
    for (std::size_t f = 0; f < nf; ++f) {
        const auto& t = mesh.triangles[f];
        for (auto v : t) used[std::size_t(v)] = true;
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] ||
            CGAL::collinear(point(t[0]), point(t[1]), point(t[2])))
            degenerate[f] = true;
        rep.degenerate_triangles += degenerate[f];
        sorted[f] = t;
        std::sort(sorted[f].begin(), sorted[f].end());
    }
    rep.unreferenced_vertices = std::size_t(std::count(used.begin(), used.end(), false));
    {
        auto s = sorted;
        std::sort(s.begin(), s.end());
        for (std::size_t i = 1; i < s.size(); ++i) rep.duplicate_triangles += s[i] == s[i - 1];
    }

    // Edges: sort half-edges by undirected edge, then count.
    std::vector<HalfEdge> he;
    he.reserve(3 * nf);
    for (std::size_t f = 0; f < nf; ++f) {
        if (degenerate[f]) continue;
        const auto& t = mesh.triangles[f];
        for (int q = 0; q < 3; ++q) {
            const std::int32_t a = t[std::size_t(q)], b = t[std::size_t((q + 1) % 3)];
            he.push_back({std::min(a, b), std::max(a, b), a < b});
        }
    }
    std::sort(he.begin(), he.end());
    std::size_t n_edges = 0;
    for (std::size_t i = 0; i < he.size();) {
        std::size_t j = i;
        while (j < he.size() && he[j].lo == he[i].lo && he[j].hi == he[i].hi) ++j;
        ++n_edges;
        const std::size_t c = j - i;
        if (c == 1) ++rep.boundary_edges;
        else if (c > 2) ++rep.nonmanifold_edges;
        else if (he[i].forward == he[i + 1].forward) ++rep.misoriented_edges;
        i = j;
    }

    // Vertex links.
    std::vector<std::vector<std::pair<std::int32_t, std::int32_t>>> links(nv);
    for (std::size_t f = 0; f < nf; ++f) {
        if (degenerate[f]) continue;
        const auto& t = mesh.triangles[f];
        for (int q = 0; q < 3; ++q)
            links[std::size_t(t[std::size_t(q)])].emplace_back(t[std::size_t((q + 1) % 3)], t[std::size_t((q + 2) % 3)]);
    }
    for (std::size_t v = 0; v < nv; ++v)
        if (used[v] && !link_is_cycle(links[v])) ++rep.nonmanifold_vertices;

    rep.closed = rep.boundary_edges == 0 && rep.nonmanifold_edges == 0 && nf > 0;
    rep.manifold = rep.closed && rep.nonmanifold_vertices == 0 && rep.degenerate_triangles == 0 &&
                   rep.duplicate_triangles == 0;
    rep.oriented = rep.manifold && rep.misoriented_edges == 0;

    // Components: union-find of vertices through triangles; chi = V - E + F per component.
    std::vector<std::int32_t> p(nv);
    std::iota(p.begin(), p.end(), 0);
    for (const auto& t : mesh.triangles) {
        const auto a = find(p, t[0]);
        p[std::size_t(find(p, t[1]))] = a;
        p[std::size_t(find(p, t[2]))] = a;
    }
    std::vector<int> root_comp(nv, -1);
    std::vector<std::int64_t> V, E, F;
    auto comp_of = [&](std::int32_t v) {
        const auto r = std::size_t(find(p, v));
        if (root_comp[r] < 0) {
            root_comp[r] = int(V.size());
            V.push_back(0);
            E.push_back(0);
            F.push_back(0);
        }
        return root_comp[r];
    };
    tri_component.assign(nf, 0);
    for (std::size_t f = 0; f < nf; ++f) {
        tri_component[f] = comp_of(mesh.triangles[f][0]);
        ++F[std::size_t(tri_component[f])];
    }
    for (std::size_t v = 0; v < nv; ++v)
        if (used[v]) ++V[std::size_t(comp_of(std::int32_t(v)))];
    for (std::size_t i = 0; i < he.size(); ++i)
        if (i == 0 || he[i].lo != he[i - 1].lo || he[i].hi != he[i - 1].hi) ++E[std::size_t(comp_of(he[i].lo))];

    std::vector<VerifyComponent> comps(V.size());
    for (std::size_t c = 0; c < V.size(); ++c) {
        comps[c].euler = int(V[c] - E[c] + F[c]);
        comps[c].genus = (2 - comps[c].euler) / 2;
        comps[c].triangles = std::size_t(F[c]);
    }
    std::vector<int> order(comps.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) {
        const auto& x = comps[std::size_t(a)];
        const auto& y = comps[std::size_t(b)];
        return x.genus != y.genus ? x.genus < y.genus : x.triangles < y.triangles;
    });
    std::vector<int> rank(comps.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
        rank[std::size_t(order[i])] = int(i);
        rep.components.push_back(comps[std::size_t(order[i])]);
    }
    for (auto& c : tri_component) c = rank[std::size_t(c)];
    (void)n_edges;
    return rep;
}

} // namespace isodel::verify
