// The blocks' owned triangles joined into one mesh (partitioned_meshing.h): a vertex two blocks
// share is the same point of P in both, with the same coordinates to the bit, so vertices are
// merged by their coordinates, never by a distance tolerance.
#include "surface/partitioned_meshing.h"
#include "surface/surface_extraction.h"

#include <algorithm>
#include <map>
#include <utility>

namespace isodel::mesher {

bool assemble_surface(const std::vector<BlockSurface>& parts, SurfaceMesh& mesh)
{
    mesh = SurfaceMesh();
    {
        // Scoped: the map goes before the edge list below is built (the first process holds the
        // whole mesh here, and its peak memory is the run's).
        std::map<std::array<double, 3>, std::int32_t> index;
        const auto vertex = [&](const std::array<double, 3>& p) {
            const auto [it, fresh] = index.emplace(p, std::int32_t(mesh.vertices.size()));
            if (fresh) mesh.vertices.push_back(p);
            return it->second;
        };
        for (const BlockSurface& part : parts)
            for (const WorldTriangle& t : part.triangles)
                mesh.triangles.push_back({vertex(t[0]), vertex(t[1]), vertex(t[2])});
    }

    // Closed and consistently oriented: each directed edge once, and its reverse once.
    std::vector<std::pair<std::int32_t, std::int32_t>> directed;
    directed.reserve(3 * mesh.triangles.size());
    for (const auto& t : mesh.triangles)
        for (int j = 0; j < 3; ++j) directed.emplace_back(t[j], t[(j + 1) % 3]);
    std::sort(directed.begin(), directed.end());
    bool closed = std::adjacent_find(directed.begin(), directed.end()) == directed.end();
    for (std::size_t i = 0; closed && i < directed.size(); ++i)
        closed = std::binary_search(directed.begin(), directed.end(), std::make_pair(directed[i].second, directed[i].first));
    if (!closed) {
        mesh = SurfaceMesh();
        return false;
    }

    sort_triangles(mesh); // the order extract_surface gives
    return true;
}

} // namespace isodel::mesher
