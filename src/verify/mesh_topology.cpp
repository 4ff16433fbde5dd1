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

/// \throw InvalidInput a triangle of \p mesh names a vertex it does not have.
void check_vertex_indices(const SurfaceMesh& mesh)
{
    const std::size_t nv = mesh.vertices.size();
    for (const auto& t : mesh.triangles)
        for (auto v : t)
            if (v < 0 || std::size_t(v) >= nv)
                throw InvalidInput("verify: mesh triangle references vertex " + std::to_string(v) +
                                   " of " + std::to_string(nv));
}

/// What the per-triangle scan found, for the edge and vertex checks after it.
struct TriangleFlags {
    std::vector<bool> degenerate; ///< per triangle; left out of the edges and links
    std::vector<bool> used;       ///< per vertex: corner of some triangle
};

/// Flags degenerate triangles and used vertices, and counts into \p rep the degenerate and
/// duplicate triangles and the unreferenced vertices.
TriangleFlags scan_triangles(const SurfaceMesh& mesh, MeshTopologyReport& rep)
{
    const std::size_t nv = mesh.vertices.size(), nf = mesh.triangles.size();
    auto point = [&](std::int32_t v) {
        const auto& p = mesh.vertices[std::size_t(v)];
        return K::Point_3(p[0], p[1], p[2]);
    };
    TriangleFlags flags{std::vector<bool>(nf, false), std::vector<bool>(nv, false)};
    std::vector<bool>& degenerate = flags.degenerate;
    std::vector<bool>& used = flags.used;
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
    return flags;
}

/// The half-edges of the non-degenerate triangles, sorted by undirected edge: each edge's
/// half-edges are then a run.
std::vector<HalfEdge> sorted_half_edges(const SurfaceMesh& mesh, const std::vector<bool>& degenerate)
{
    const std::size_t nf = mesh.triangles.size();
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
    return he;
}

/// Counts into \p rep the boundary, non-manifold and misoriented edges of \p he (sorted).
void count_edge_faults(const std::vector<HalfEdge>& he, MeshTopologyReport& rep)
{
    for (std::size_t i = 0; i < he.size();) {
        std::size_t j = i;
        while (j < he.size() && he[j].lo == he[i].lo && he[j].hi == he[i].hi) ++j;
        const std::size_t c = j - i;
        if (c == 1) ++rep.boundary_edges;
        else if (c > 2) ++rep.nonmanifold_edges;
        else if (he[i].forward == he[i + 1].forward) ++rep.misoriented_edges;
        i = j;
    }
}

/// Counts into \p rep the used vertices whose link (over the non-degenerate triangles) is not
/// one cycle.
void count_nonmanifold_vertices(const SurfaceMesh& mesh, const TriangleFlags& flags, MeshTopologyReport& rep)
{
    const std::size_t nv = mesh.vertices.size(), nf = mesh.triangles.size();
    std::vector<std::vector<std::pair<std::int32_t, std::int32_t>>> links(nv);
    for (std::size_t f = 0; f < nf; ++f) {
        if (flags.degenerate[f]) continue;
        const auto& t = mesh.triangles[f];
        for (int q = 0; q < 3; ++q)
            links[std::size_t(t[std::size_t(q)])].emplace_back(t[std::size_t((q + 1) % 3)], t[std::size_t((q + 2) % 3)]);
    }
    for (std::size_t v = 0; v < nv; ++v)
        if (flags.used[v] && !link_is_cycle(links[v])) ++rep.nonmanifold_vertices;
}

/// The connected components of a mesh (union-find of its vertices through its triangles), each
/// with its vertex, edge and triangle counts; numbered in the order comp_of() first meets them.
struct ComponentCounts {
    std::vector<std::int32_t> p; ///< union-find parents
    std::vector<int> root_comp;  ///< component of each root, -1 until comp_of() meets it
    std::vector<std::int64_t> V, E, F;

    explicit ComponentCounts(const SurfaceMesh& mesh) : p(mesh.vertices.size()), root_comp(mesh.vertices.size(), -1)
    {
        std::iota(p.begin(), p.end(), 0);
        for (const auto& t : mesh.triangles) {
            const auto a = find(p, t[0]);
            p[std::size_t(find(p, t[1]))] = a;
            p[std::size_t(find(p, t[2]))] = a;
        }
    }

    int comp_of(std::int32_t v)
    {
        const auto r = std::size_t(find(p, v));
        if (root_comp[r] < 0) {
            root_comp[r] = int(V.size());
            V.push_back(0);
            E.push_back(0);
            F.push_back(0);
        }
        return root_comp[r];
    }
};

/// The components of \p mesh with their Euler characteristic (chi = V - E + F), genus and
/// size, in the order of their first triangle; \p tri_component receives each triangle's.
std::vector<ComponentTopology> count_components(const SurfaceMesh& mesh, const std::vector<bool>& used,
                                              const std::vector<HalfEdge>& he, std::vector<int>& tri_component)
{
    const std::size_t nv = mesh.vertices.size(), nf = mesh.triangles.size();
    ComponentCounts cc(mesh);
    tri_component.assign(nf, 0);
    for (std::size_t f = 0; f < nf; ++f) {
        tri_component[f] = cc.comp_of(mesh.triangles[f][0]);
        ++cc.F[std::size_t(tri_component[f])];
    }
    for (std::size_t v = 0; v < nv; ++v)
        if (used[v]) ++cc.V[std::size_t(cc.comp_of(std::int32_t(v)))];
    for (std::size_t i = 0; i < he.size(); ++i)
        if (i == 0 || he[i].lo != he[i - 1].lo || he[i].hi != he[i - 1].hi) ++cc.E[std::size_t(cc.comp_of(he[i].lo))];

    std::vector<ComponentTopology> comps(cc.V.size());
    for (std::size_t c = 0; c < cc.V.size(); ++c) {
        comps[c].euler = int(cc.V[c] - cc.E[c] + cc.F[c]);
        comps[c].genus = (2 - comps[c].euler) / 2;
        comps[c].triangles = std::size_t(cc.F[c]);
    }
    return comps;
}

/// Appends \p comps to rep.components sorted by genus, then size, and renumbers
/// \p tri_component to match.
void rank_components(const std::vector<ComponentTopology>& comps, MeshTopologyReport& rep,
                     std::vector<int>& tri_component)
{
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
}

} // namespace

MeshTopologyReport mesh_topology(const SurfaceMesh& mesh, std::vector<int>& tri_component)
{
    MeshTopologyReport rep;
    const std::size_t nv = mesh.vertices.size(), nf = mesh.triangles.size();
    rep.vertices = nv;
    rep.triangles = nf;
    check_vertex_indices(mesh);

    const TriangleFlags flags = scan_triangles(mesh, rep);
    // Edges: sort half-edges by undirected edge, then count.
    const std::vector<HalfEdge> he = sorted_half_edges(mesh, flags.degenerate);
    count_edge_faults(he, rep);
    // Vertex links.
    count_nonmanifold_vertices(mesh, flags, rep);

    rep.closed = rep.boundary_edges == 0 && rep.nonmanifold_edges == 0 && nf > 0;
    rep.manifold = rep.closed && rep.nonmanifold_vertices == 0 && rep.degenerate_triangles == 0 &&
                   rep.duplicate_triangles == 0;
    rep.oriented = rep.manifold && rep.misoriented_edges == 0;

    // Components: union-find of vertices through triangles; chi = V - E + F per component.
    const std::vector<ComponentTopology> comps = count_components(mesh, flags.used, he, tri_component);
    rank_components(comps, rep, tri_component);
    return rep;
}

} // namespace isodel::verify
