#include "refinement/surface_slivers.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

namespace isodel::mesher {
namespace {

constexpr double kDegPerRad = 180.0 / 3.14159265358979323846;

using Vec = std::array<double, 3>;

Vec minus(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec cross(const Vec& a, const Vec& b)
{
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

} // namespace

std::pair<double, double> dihedral_range_deg(const Vec& a, const Vec& b, const Vec& c, const Vec& d)
{
    // The dihedral angle at an edge is pi minus the angle between the outward normals of the
    // two faces through it. A quality measure, not a decision about M: doubles suffice.
    const std::array<Vec, 4> p{a, b, c, d};
    std::array<Vec, 4> n;
    for (int i = 0; i < 4; ++i) {
        const Vec& x = p[(i + 1) & 3];
        Vec m = cross(minus(p[(i + 2) & 3], x), minus(p[(i + 3) & 3], x));
        const double s = dot(m, minus(p[i], x)) > 0 ? -1.0 : 1.0;
        const double len = std::sqrt(std::max(dot(m, m), 1e-300));
        for (double& v : m) v *= s / len;
        n[i] = m;
    }
    double lo = 180, hi = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
            const double angle = 180.0 - kDegPerRad * std::acos(std::clamp(dot(n[i], n[j]), -1.0, 1.0));
            lo = std::min(lo, angle);
            hi = std::max(hi, angle);
        }
    return {lo, hi};
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
