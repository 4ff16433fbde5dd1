// Check 2: no self-intersections, with CGAL's exact-predicate test (PMP::self_intersections).
// M is first turned into a halfedge mesh through the polygon soup functions so that the test also
// runs on meshes that are not manifold (then non-manifold vertices are duplicated, which does not
// hide an intersection: coincident or crossing triangles still intersect).
#include "verify/checks.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <utility>

namespace isodel::verify {

void check_self_intersections(const SurfaceMesh& mesh, MeshTopologyReport& rep)
{
    using K = CGAL::Exact_predicates_inexact_constructions_kernel;
    using SM = CGAL::Surface_mesh<K::Point_3>;
    namespace PMP = CGAL::Polygon_mesh_processing;

    std::vector<K::Point_3> points;
    points.reserve(mesh.vertices.size());
    for (const auto& v : mesh.vertices) points.emplace_back(v[0], v[1], v[2]);
    std::vector<std::vector<std::size_t>> polys;
    polys.reserve(mesh.triangles.size());
    for (const auto& t : mesh.triangles) {
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue; // counted as degenerate
        polys.push_back({std::size_t(t[0]), std::size_t(t[1]), std::size_t(t[2])});
    }
    SM sm;
    if (rep.oriented) {
        PMP::polygon_soup_to_polygon_mesh(points, polys, sm);
    } else {
        PMP::orient_polygon_soup(points, polys);
        PMP::polygon_soup_to_polygon_mesh(points, polys, sm);
    }
    std::vector<std::pair<SM::Face_index, SM::Face_index>> pairs;
    PMP::self_intersections(faces(sm), sm, std::back_inserter(pairs));
    rep.self_intersecting_pairs = pairs.size();
    rep.self_intersection_checked = true;
}

} // namespace isodel::verify
