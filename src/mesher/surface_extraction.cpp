#include "mesher/surface_extraction.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <set>

namespace isodel::mesher {

SurfaceMesh extract_surface(const Delaunay& dt, const FacetCache& cache)
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
    std::unordered_map<std::uint32_t, std::int32_t> index;
    for (const auto& [id, v] : used) {
        index[id] = std::int32_t(mesh.vertices.size());
        const Point& p = v->point();
        mesh.vertices.push_back({p.x(), p.y(), p.z()});
    }
    for (const auto& e : cache.active()) {
        if (e.record->crossings != 1) continue;
        auto vs = facet_vertices(e.facet);
        // Orient so the normal agrees with the Voronoi edge's inside -> outside direction.
        const Vector n = CGAL::cross_product(vs[1]->point() - vs[0]->point(), vs[2]->point() - vs[0]->point());
        if (n * e.record->outward < 0) std::swap(vs[1], vs[2]);
        mesh.triangles.push_back({index.at(vs[0]->info().id), index.at(vs[1]->info().id),
                                  index.at(vs[2]->info().id)});
    }
    // Deterministic triangle order, independent of the triangulation's memory layout.
    std::sort(mesh.triangles.begin(), mesh.triangles.end(), [](const auto& a, const auto& b) {
        auto ka = a, kb = b;
        std::sort(ka.begin(), ka.end());
        std::sort(kb.begin(), kb.end());
        return ka < kb;
    });
    return mesh;
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
    std::map<std::size_t, ComponentTopology> comps;
    std::map<std::size_t, std::set<std::pair<int, int>>> edges;
    std::map<std::size_t, std::set<int>> verts;
    for (const auto& t : mesh.triangles) {
        const std::size_t r = find(std::size_t(t[0]));
        comps[r].triangles++;
        for (int j = 0; j < 3; ++j) {
            verts[r].insert(t[j]);
            edges[r].insert(std::minmax(t[j], t[(j + 1) % 3]));
        }
    }
    std::vector<ComponentTopology> out;
    for (auto& [r, c] : comps) {
        c.euler = int(verts[r].size()) - int(edges[r].size()) + int(c.triangles);
        c.genus = (2 - c.euler) / 2;
        out.push_back(c);
    }
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
        return std::tie(a.genus, a.triangles) < std::tie(b.genus, b.triangles);
    });
    return out;
}

} // namespace isodel::mesher
