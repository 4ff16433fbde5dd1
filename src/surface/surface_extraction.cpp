#include "surface/surface_extraction.h"

#include <algorithm>
#include <array>
#include <numeric>

namespace isodel::mesher {

SurfaceMesh extract_surface(const Delaunay& dt, const FacetCache& cache, std::vector<std::uint32_t>* vertex_ids)
{
    (void)dt;
    SurfaceMesh mesh;
    std::vector<std::pair<std::uint32_t, Vertex_handle>> used;
    for (const auto& e : cache.active())
        if (e.record->crossings == 1)
            for (const auto& v : facet_vertices(e.facet)) used.emplace_back(v->info().id, v);
    std::sort(used.begin(), used.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    used.erase(std::unique(used.begin(), used.end(),
                           [](const auto& a, const auto& b) { return a.first == b.first; }),
               used.end());
    // Vertex ids are dense (0 .. number of points): an array maps them to mesh indices.
    std::vector<std::int32_t> index(used.empty() ? 0 : std::size_t(used.back().first) + 1, -1);
    for (const auto& [id, v] : used) {
        index[id] = std::int32_t(mesh.vertices.size());
        const Point& p = v->point();
        mesh.vertices.push_back({p.x(), p.y(), p.z()});
        if (vertex_ids) vertex_ids->push_back(id);
    }
    for (const auto& e : cache.active()) {
        if (e.record->crossings != 1) continue;
        auto vs = facet_vertices(e.facet);
        // Orient so the normal agrees with the Voronoi edge's inside -> outside direction.
        const Vector n = CGAL::cross_product(vs[1]->point() - vs[0]->point(), vs[2]->point() - vs[0]->point());
        if (n * e.record->outward < 0) std::swap(vs[1], vs[2]);
        mesh.triangles.push_back({index[vs[0]->info().id], index[vs[1]->info().id], index[vs[2]->info().id]});
    }
    sort_triangles(mesh);
    return mesh;
}

void sort_triangles(SurfaceMesh& mesh)
{
    using Tri = std::array<std::int32_t, 3>;
    std::vector<std::pair<Tri, Tri>> keyed(mesh.triangles.size());
    for (std::size_t i = 0; i < keyed.size(); ++i) {
        keyed[i] = {mesh.triangles[i], mesh.triangles[i]};
        std::sort(keyed[i].first.begin(), keyed[i].first.end());
    }
    std::sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t i = 0; i < keyed.size(); ++i) mesh.triangles[i] = keyed[i].second;
}

std::vector<ComponentTopology> surface_topology(const SurfaceMesh& mesh)
{
    const std::size_t nv = mesh.vertices.size();
    std::vector<std::size_t> parent(nv);
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](std::size_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    for (const auto& t : mesh.triangles) {
        parent[find(std::size_t(t[1]))] = find(std::size_t(t[0]));
        parent[find(std::size_t(t[2]))] = find(std::size_t(t[0]));
    }
    // Per component (by its root, in root order): V - E + F from one sorted list of the edges
    // and a mark per vertex.
    std::vector<ComponentTopology> by_root(nv);
    std::vector<int> vertices(nv, 0), edges(nv, 0);
    std::vector<char> seen(nv, 0);
    std::vector<std::pair<std::int32_t, std::int32_t>> all_edges;
    all_edges.reserve(3 * mesh.triangles.size());
    for (const auto& t : mesh.triangles) {
        const std::size_t r = find(std::size_t(t[0]));
        by_root[r].triangles++;
        for (int j = 0; j < 3; ++j) {
            if (!seen[std::size_t(t[j])]) {
                seen[std::size_t(t[j])] = 1;
                ++vertices[r];
            }
            all_edges.push_back(std::minmax(t[j], t[(j + 1) % 3]));
        }
    }
    std::sort(all_edges.begin(), all_edges.end());
    all_edges.erase(std::unique(all_edges.begin(), all_edges.end()), all_edges.end());
    for (const auto& e : all_edges) ++edges[find(std::size_t(e.first))];
    std::vector<ComponentTopology> out;
    for (std::size_t r = 0; r < nv; ++r) {
        if (by_root[r].triangles == 0) continue; // not a root, or a vertex in no triangle
        ComponentTopology c = by_root[r];
        c.euler = vertices[r] - edges[r] + int(c.triangles);
        c.genus = (2 - c.euler) / 2;
        out.push_back(c);
    }
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
        return std::tie(a.genus, a.triangles) < std::tie(b.genus, b.triangles);
    });
    return out;
}

} // namespace isodel::mesher
