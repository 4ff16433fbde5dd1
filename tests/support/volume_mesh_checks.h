#pragma once
// Checks of a DELVOLMESH result (paper Section 4.1) shared by the unit and corpus tests:
// positive orientation, inside volume == volume enclosed by M, boundary of the inside region ==
// M triangle for triangle (with orientation), M's vertices first, region tags.
#include <isodel/mesh.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>
#include <string>

namespace isodel::testing {

inline double tet_volume(const std::array<double, 3>& a, const std::array<double, 3>& b,
                         const std::array<double, 3>& c, const std::array<double, 3>& d)
{
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
            u[2] * (v[0] * w[1] - v[1] * w[0])) / 6.0;
}

/// The triangle rotated so its smallest index comes first (orientation kept).
inline std::array<std::int32_t, 3> rotate_min_first(std::array<std::int32_t, 3> t)
{
    while (t[0] > t[1] || t[0] > t[2]) t = {t[1], t[2], t[0]};
    return t;
}

struct VolumeCheck {
    std::size_t non_positive = 0;
    double volume_inside = 0, volume_outside = 0, enclosed = 0;
    bool prefix_ok = false, triangles_ok = false, boundary_ok = false, tags_ok = false;
};

inline VolumeCheck check_volume_mesh(const MeshResult& r, TetRegion region)
{
    VolumeCheck c;
    const TetMesh& t = r.tets;
    c.prefix_ok = t.vertices.size() >= r.surface.vertices.size() &&
                  std::equal(r.surface.vertices.begin(), r.surface.vertices.end(), t.vertices.begin());
    c.triangles_ok = t.triangles == r.surface.triangles;
    c.tags_ok = t.tet_region.size() == t.tets.size();
    // Outward faces of a positively oriented tet (0,1,2,3).
    static constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    // Faces of inside tets as (sorted key, outward oriented); a face seen once is on the boundary.
    std::vector<std::pair<std::array<std::int32_t, 3>, std::array<std::int32_t, 3>>> faces;
    for (std::size_t i = 0; i < t.tets.size(); ++i) {
        const auto& q = t.tets[i];
        const double v = tet_volume(t.vertices[q[0]], t.vertices[q[1]], t.vertices[q[2]], t.vertices[q[3]]);
        if (!(v > 0)) ++c.non_positive;
        const int reg = t.tet_region[i];
        if (reg == 1) c.volume_inside += v;
        else c.volume_outside += v;
        if (reg == 1 && region == TetRegion::Outside) c.tags_ok = false;
        if (reg == 2 && region == TetRegion::Inside) c.tags_ok = false;
        if (reg != 1 && reg != 2) c.tags_ok = false;
        if (reg != 1) continue;
        for (const auto& f : kFaces) {
            std::array<std::int32_t, 3> o{q[f[0]], q[f[1]], q[f[2]]}, k = o;
            std::sort(k.begin(), k.end());
            faces.emplace_back(k, o);
        }
    }
    std::sort(faces.begin(), faces.end());
    std::vector<std::array<std::int32_t, 3>> boundary, surface;
    for (std::size_t i = 0; i < faces.size();) {
        std::size_t j = i;
        while (j < faces.size() && faces[j].first == faces[i].first) ++j;
        if (j - i == 1) boundary.push_back(rotate_min_first(faces[i].second));
        i = j;
    }
    for (const auto& tri : r.surface.triangles) surface.push_back(rotate_min_first(tri));
    std::sort(boundary.begin(), boundary.end());
    std::sort(surface.begin(), surface.end());
    c.boundary_ok = region == TetRegion::Outside || boundary == surface;
    // Divergence theorem on M, cones from the first vertex.
    if (!r.surface.vertices.empty())
        for (const auto& tri : r.surface.triangles)
            c.enclosed += tet_volume(r.surface.vertices[0], r.surface.vertices[tri[0]], r.surface.vertices[tri[1]],
                                     r.surface.vertices[tri[2]]);
    return c;
}

/// REQUIREs every acceptance property; \p what names the case in messages.
inline void require_volume_mesh(const MeshResult& r, TetRegion region, const std::string& what)
{
    const VolumeCheck c = check_volume_mesh(r, region);
    INFO(what << ": " << r.tets.tets.size() << " tets, inside volume " << c.volume_inside << ", enclosed by M "
              << c.enclosed << ", dihedral " << r.stats.tets.min_dihedral_deg << ".."
              << r.stats.tets.max_dihedral_deg);
    CHECK(!r.tets.tets.empty());
    CHECK(c.non_positive == 0);
    CHECK(c.prefix_ok);
    CHECK(c.triangles_ok);
    CHECK(c.tags_ok);
    CHECK(c.boundary_ok);
    if (region != TetRegion::Outside) CHECK(std::abs(c.volume_inside - c.enclosed) <= 1e-9 * std::abs(c.enclosed));
    CHECK(std::abs(r.stats.tets.volume_inside - c.volume_inside) <= 1e-9 * (1 + c.volume_inside));
}

} // namespace isodel::testing
