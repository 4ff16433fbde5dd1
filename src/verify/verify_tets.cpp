// isodel verify --tets: what `isodel mesh --tets` (DELVOLMESH, paper Section 4.1) promises of a
// tetrahedral mesh, checked from the files alone
// (independent of the mesher): positive orientation by CGAL's exact orientation predicate, the
// inside region bounded exactly by M (same triangles, same orientation, vertices matched by exact
// position), its volume equal to the volume M encloses, and the dihedral angles.
#include <isodel/verify.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace isodel {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vec = std::array<double, 3>;

Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec cross(const Vec& a, const Vec& b)
{
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const Vec& a) { return std::sqrt(dot(a, a)); }

/// A triangle as a cyclic triple starting at its smallest index (orientation kept).
std::array<std::int32_t, 3> canonical(std::int32_t a, std::int32_t b, std::int32_t c)
{
    if (b < a && b < c) return {b, c, a};
    if (c < a && c < b) return {c, a, b};
    return {a, b, c};
}

} // namespace

TetReport verify_tets(const TetMesh& tm, const SurfaceMesh& mesh)
{
    TetReport r;
    r.checked = true;
    r.vertices = tm.vertices.size();
    r.tets = tm.tets.size();
    const auto P = [&](std::int32_t i) {
        const auto& v = tm.vertices[std::size_t(i)];
        return K::Point_3(v[0], v[1], v[2]);
    };

    // Orientation, regions, volumes, dihedral angles.
    std::map<std::array<std::int32_t, 3>, int> inside_faces; // face -> times seen (outward)
    r.min_dihedral_deg = 180;
    r.max_dihedral_deg = 0;
    for (std::size_t t = 0; t < tm.tets.size(); ++t) {
        const auto& q = tm.tets[t];
        const auto o = CGAL::orientation(P(q[0]), P(q[1]), P(q[2]), P(q[3]));
        if (o == CGAL::NEGATIVE) ++r.inverted;
        if (o == CGAL::ZERO) ++r.degenerate;
        const Vec a = tm.vertices[q[0]], b = tm.vertices[q[1]], c = tm.vertices[q[2]], d = tm.vertices[q[3]];
        const double vol = dot(sub(b, a), cross(sub(c, a), sub(d, a))) / 6.0;
        const int region = t < tm.tet_region.size() ? tm.tet_region[t] : 0;
        if (region == 1) {
            ++r.inside_tets;
            r.inside_volume += vol;
            // Outward faces of a positively oriented tet (0,1,2,3).
            for (const auto& f : {canonical(q[1], q[2], q[3]), canonical(q[0], q[3], q[2]), canonical(q[0], q[1], q[3]),
                                  canonical(q[0], q[2], q[1])}) {
                // The same face seen reversed from a neighbour cancels it.
                const auto rev = canonical(f[0], f[2], f[1]);
                auto it = inside_faces.find(rev);
                if (it != inside_faces.end()) inside_faces.erase(it);
                else ++inside_faces[f];
            }
        } else if (region == 2) {
            ++r.outside_tets;
            r.outside_volume += vol;
        } else {
            ++r.unknown_region;
        }
        const std::array<Vec, 4> p{a, b, c, d};
        static constexpr int E[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}, {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
        for (const auto& e : E) {
            const Vec axis = sub(p[e[1]], p[e[0]]);
            const Vec n1 = cross(axis, sub(p[e[2]], p[e[0]])), n2 = cross(axis, sub(p[e[3]], p[e[0]]));
            const double ang = std::atan2(norm(cross(n1, n2)), dot(n1, n2)) * 180.0 / M_PI;
            r.min_dihedral_deg = std::min(r.min_dihedral_deg, ang);
            r.max_dihedral_deg = std::max(r.max_dihedral_deg, ang);
            ++r.dihedral_histogram[std::min<std::size_t>(17, std::size_t(ang / 10.0))];
        }
    }

    // M's vertices in the tet mesh, by exact position.
    std::map<Vec, std::int32_t> where;
    for (std::size_t i = 0; i < tm.vertices.size(); ++i) where.emplace(tm.vertices[i], std::int32_t(i));
    std::vector<std::int32_t> to_tet(mesh.vertices.size(), -1);
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
        const auto it = where.find(mesh.vertices[i]);
        if (it == where.end()) ++r.unmatched_mesh_vertices;
        else to_tet[i] = it->second;
    }
    std::set<std::array<std::int32_t, 3>> m_faces;
    for (const auto& t : mesh.triangles) {
        if (to_tet[t[0]] < 0 || to_tet[t[1]] < 0 || to_tet[t[2]] < 0) continue;
        m_faces.insert(canonical(to_tet[t[0]], to_tet[t[1]], to_tet[t[2]]));
    }
    for (const auto& [f, n] : inside_faces) {
        r.boundary_faces += std::size_t(n);
        if (n != 1 || !m_faces.count(f)) r.boundary_not_in_mesh += std::size_t(n);
    }
    for (const auto& f : m_faces)
        if (!inside_faces.count(f)) ++r.mesh_not_in_boundary;
    r.mesh_not_in_boundary += mesh.triangles.size() - m_faces.size(); // unmatched or duplicated

    // Volume enclosed by M (divergence theorem about its first vertex, for accuracy).
    if (!mesh.vertices.empty()) {
        const Vec o = mesh.vertices[0];
        for (const auto& t : mesh.triangles) {
            const Vec a = sub(mesh.vertices[t[0]], o), b = sub(mesh.vertices[t[1]], o), c = sub(mesh.vertices[t[2]], o);
            r.enclosed_volume += dot(a, cross(b, c)) / 6.0;
        }
    }
    r.volume_rel_error = r.enclosed_volume != 0 ? std::abs(r.inside_volume - r.enclosed_volume) / std::abs(r.enclosed_volume)
                                                : (r.inside_volume == 0 ? 0.0 : 1.0);
    r.passed = r.tets > 0 && r.inverted == 0 && r.degenerate == 0 && r.unknown_region == 0 && r.inside_tets > 0 &&
               r.unmatched_mesh_vertices == 0 && r.boundary_not_in_mesh == 0 && r.mesh_not_in_boundary == 0 &&
               r.volume_rel_error <= 1e-9;
    return r;
}

} // namespace isodel
