#include "refinement/surface_slivers.h"

#include "volume/tet_improver.h"

#include <algorithm>
#include <unordered_map>
#include <unordered_set>

namespace isodel::mesher {

std::pair<double, double> dihedral_range_deg(const std::array<double, 3>& a, const std::array<double, 3>& b,
                                             const std::array<double, 3>& c, const std::array<double, 3>& d)
{
    // A quality measure, not a decision about M: the improver's doubles suffice.
    double lowest = 0, highest = 0;
    if (!tet_improver::normal_dots(a, b, c, d, lowest, highest)) return {0.0, 180.0};
    return {tet_improver::degrees(lowest), tet_improver::degrees(highest)};
}

std::vector<Point> surface_sliver_points(const TetMesh& tets, const std::vector<std::uint32_t>& vertex_ids,
                                         const FacetCache& cache, double min_deg, double max_deg)
{
    std::unordered_map<FacetKey, const FacetRecord*, FacetKeyHash> on_m;
    on_m.reserve(2 * tets.triangles.size());
    for (const auto& e : cache.active())
        if (e.crossings == 1) on_m.emplace(e.key, e.record);
    const std::size_t n_surface = vertex_ids.size();
    std::unordered_set<FacetKey, FacetKeyHash> split; // two tets may share a face of M
    std::vector<Point> out;
    for (const auto& t : tets.tets) {
        // A face on M has its three vertices on M, which come first in the numbering.
        int on_surface = 0;
        for (const std::int32_t v : t) on_surface += std::size_t(v) < n_surface ? 1 : 0;
        if (on_surface < 3) continue;
        const auto [lo, hi] = dihedral_range_deg(tets.vertices[std::size_t(t[0])], tets.vertices[std::size_t(t[1])],
                                                 tets.vertices[std::size_t(t[2])], tets.vertices[std::size_t(t[3])]);
        if (lo >= min_deg && hi <= max_deg) continue;
        const FacetRecord* best = nullptr;
        FacetKey best_key{};
        double best_r2 = -1;
        for (int j = 0; j < 4; ++j) {
            FacetKey k;
            bool surface_face = true;
            for (int m = 0; m < 3; ++m) {
                const std::int32_t v = t[std::size_t((j + 1 + m) & 3)];
                surface_face = surface_face && std::size_t(v) < n_surface;
                k.v[std::size_t(m)] = surface_face ? vertex_ids[std::size_t(v)] : 0;
            }
            if (!surface_face) continue;
            std::sort(k.v.begin(), k.v.end());
            const auto it = on_m.find(k);
            if (it == on_m.end()) continue;
            const auto& q = tets.vertices[std::size_t(t[std::size_t((j + 1) & 3)])];
            const Point& c = it->second->surface_point;
            const double r2 = (c.x() - q[0]) * (c.x() - q[0]) + (c.y() - q[1]) * (c.y() - q[1]) +
                              (c.z() - q[2]) * (c.z() - q[2]);
            if (r2 > best_r2 || (r2 == best_r2 && k < best_key)) {
                best = it->second;
                best_key = k;
                best_r2 = r2;
            }
        }
        if (best && split.insert(best_key).second) out.push_back(best->surface_point);
    }
    return out;
}

} // namespace isodel::mesher
