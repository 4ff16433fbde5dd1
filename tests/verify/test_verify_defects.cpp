// The verifier can fail: a correct mesh of an analytic sphere volume passes every check, and each
// planted defect (wrong genus, shift by more than eps, non-Delaunay edge flip, hole, duplicated
// face) is caught by the check that should catch it.
#include <catch2/catch.hpp>

#include "support/verify_test_support.h"

#include <isodel/verify.h>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <map>
#include <set>

using namespace isodel;
using openvdb::Vec3d;

namespace {

// Sphere of radius 9 voxels in a 28^3 grid, voxel 0.5 world units, origin offset: so world and
// voxel units differ and the transform is exercised.
struct SphereCase {
    openvdb::FloatGrid::Ptr grid;
    SurfaceMesh mesh;
    VerifyOptions opt;
    SphereCase()
    {
        const Vec3d c(13.3, 13.6, 13.1);
        grid = testing::make_grid(28, 0.5, Vec3d(-3.0, 1.0, 2.0), [&](const Vec3d& x) { return testing::sphere_f(x, c, 9.0); });
        mesh = testing::star_hull_mesh(*grid, c, 1200, 0.004);
        opt.isovalue = 0.0;
        opt.inside = Inside::Above;
        opt.eps_voxels = 0.25;
    }
};

using Edge = std::pair<std::int32_t, std::int32_t>;

std::map<Edge, std::vector<std::size_t>> edge_triangles(const SurfaceMesh& m)
{
    std::map<Edge, std::vector<std::size_t>> e;
    for (std::size_t f = 0; f < m.triangles.size(); ++f)
        for (int q = 0; q < 3; ++q) {
            auto a = m.triangles[f][std::size_t(q)], b = m.triangles[f][std::size_t((q + 1) % 3)];
            e[{std::min(a, b), std::max(a, b)}].push_back(f);
        }
    return e;
}

} // namespace

TEST_CASE("verify: a correct sphere mesh passes every check", "[verify]")
{
    SphereCase s;
    const VerifyReport r = verify_surface(*s.grid, s.mesh, s.opt);
    INFO(r.summary());
    CHECK(r.reference.determined);
    REQUIRE(r.reference.components.size() == 1);
    CHECK(r.reference.components[0].genus == 0);
    CHECK(r.mesh.closed);
    CHECK(r.mesh.manifold);
    CHECK(r.mesh.oriented);
    CHECK(r.mesh.outward);
    CHECK(r.mesh.self_intersecting_pairs == 0);
    CHECK(r.topology_verdict == TopologyVerdict::Pass);
    CHECK(r.hausdorff.passed);
    CHECK(r.hausdorff.mesh_to_surface.max_voxels < 0.1);
    CHECK(r.hausdorff.surface_to_mesh.max_voxels < 0.1);
    CHECK(r.delaunay.passed);
    CHECK(r.delaunay.dt_facets == s.mesh.triangles.size());
    CHECK(r.passed());
    // The JSON report carries the verdicts.
    const testing::Json json = testing::Json::parse(r.to_json());
    CHECK(json.at("passed").get<bool>());
    CHECK(json.at("topology").at("verdict").get<std::string>() == "pass");
}

TEST_CASE("verify: inward normals are caught", "[verify]")
{
    SphereCase s;
    for (auto& t : s.mesh.triangles) std::swap(t[1], t[2]);
    const VerifyReport r = verify_surface(*s.grid, s.mesh, s.opt);
    CHECK(r.mesh.oriented);
    CHECK_FALSE(r.mesh.outward);
    CHECK_FALSE(r.passed());
}

TEST_CASE("verify: a mesh shifted by more than eps fails Hausdorff", "[verify]")
{
    SphereCase s;
    const double shift = 0.4 * 0.5; // 0.4 voxel > eps = 0.25 voxel
    for (auto& v : s.mesh.vertices) v[0] += shift;
    const VerifyReport r = verify_surface(*s.grid, s.mesh, s.opt);
    INFO(r.summary());
    CHECK(r.topology_verdict == TopologyVerdict::Pass);
    CHECK_FALSE(r.hausdorff.passed);
    CHECK(r.hausdorff.mesh_to_surface.max_voxels > 0.3);
    CHECK(r.hausdorff.surface_to_mesh.max_voxels > 0.3);
    CHECK_FALSE(r.passed());
}

TEST_CASE("verify: a hole is caught", "[verify]")
{
    SphereCase s;
    s.mesh.triangles.erase(s.mesh.triangles.begin() + 17);
    const VerifyReport r = verify_surface(*s.grid, s.mesh, s.opt);
    CHECK_FALSE(r.mesh.closed);
    CHECK(r.mesh.boundary_edges == 3);
    CHECK(r.topology_verdict == TopologyVerdict::Fail);
    CHECK_FALSE(r.passed());
}

TEST_CASE("verify: a duplicated face is caught", "[verify]")
{
    SphereCase s;
    s.mesh.triangles.push_back(s.mesh.triangles[5]);
    const VerifyReport r = verify_surface(*s.grid, s.mesh, s.opt);
    CHECK(r.mesh.duplicate_triangles == 1);
    CHECK_FALSE(r.mesh.manifold);
    CHECK_FALSE(r.passed());
}

TEST_CASE("verify: a non-Delaunay edge flip is caught", "[verify]")
{
    SphereCase s;
    // An edge ab with opposite vertices c, d such that cd is not an edge of Del(V): after the flip
    // the triangles (c,a,d), (d,b,c) have no empty ball (the points are in general position).
    using K = CGAL::Exact_predicates_inexact_constructions_kernel;
    using Vb = CGAL::Triangulation_vertex_base_with_info_3<std::int32_t, K>;
    using DT = CGAL::Delaunay_triangulation_3<K, CGAL::Triangulation_data_structure_3<Vb>>;
    std::vector<std::pair<K::Point_3, std::int32_t>> pts;
    for (std::size_t i = 0; i < s.mesh.vertices.size(); ++i)
        pts.emplace_back(K::Point_3(s.mesh.vertices[i][0], s.mesh.vertices[i][1], s.mesh.vertices[i][2]), std::int32_t(i));
    DT dt(pts.begin(), pts.end());
    std::vector<DT::Vertex_handle> h(pts.size());
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) h[std::size_t(v->info())] = v;
    const auto edges = edge_triangles(s.mesh);
    bool flipped = false;
    for (const auto& edge_and_triangles : edges) {
        // Not a structured binding: C++17 lambdas cannot capture those (Clang refuses).
        const auto& e = edge_and_triangles.first;
        const auto& tris = edge_and_triangles.second;
        if (tris.size() != 2) continue;
        auto opposite = [&](std::size_t f) {
            for (auto v : s.mesh.triangles[f])
                if (v != e.first && v != e.second) return v;
            return -1;
        };
        const std::int32_t c = opposite(tris[0]), d = opposite(tris[1]);
        DT::Cell_handle ch;
        int i, j;
        if (edges.count({std::min(c, d), std::max(c, d)}) || dt.is_edge(h[std::size_t(c)], h[std::size_t(d)], ch, i, j)) continue;
        // Orientation: the triangle holding a->b is (a,b,c); the other is (b,a,d).
        auto t0 = s.mesh.triangles[tris[0]];
        std::int32_t a = e.first, b = e.second;
        const bool ab_in_t0 = (t0[0] == a && t0[1] == b) || (t0[1] == a && t0[2] == b) || (t0[2] == a && t0[0] == b);
        std::int32_t cc = c, dd = d;
        if (!ab_in_t0) std::swap(cc, dd); // then (a,b,d') holds a->b
        s.mesh.triangles[tris[0]] = {cc, a, dd};
        s.mesh.triangles[tris[1]] = {dd, b, cc};
        flipped = true;
        break;
    }
    REQUIRE(flipped);
    const VerifyReport r = verify_surface(*s.grid, s.mesh, s.opt);
    INFO(r.summary());
    CHECK(r.mesh.manifold);
    CHECK(r.mesh.oriented);
    CHECK_FALSE(r.delaunay.passed);
    CHECK(r.delaunay.non_delaunay == 2);
    CHECK_FALSE(r.passed());
}

TEST_CASE("verify: a mesh of the wrong genus is caught", "[verify]")
{
    SphereCase s;
    // Plant a handle: remove two nearby triangles whose vertices are not adjacent and join their
    // boundaries by a 6-triangle tube (orientation consistent, so M stays an oriented manifold).
    auto& T = s.mesh.triangles;
    const auto edges = edge_triangles(s.mesh);
    auto adjacent = [&](std::int32_t u, std::int32_t v) { return u == v || edges.count({std::min(u, v), std::max(u, v)}) > 0; };
    auto centroid = [&](std::size_t f) {
        Vec3d c(0.0);
        for (auto v : T[f]) c += Vec3d(s.mesh.vertices[std::size_t(v)][0], s.mesh.vertices[std::size_t(v)][1], s.mesh.vertices[std::size_t(v)][2]);
        return c / 3.0;
    };
    const std::size_t f1 = 0;
    std::size_t f2 = T.size();
    double best = 1e300;
    for (std::size_t f = 1; f < T.size(); ++f) {
        bool ok = true;
        for (auto u : T[f1])
            for (auto v : T[f]) ok = ok && !adjacent(u, v);
        const double d = (centroid(f) - centroid(f1)).length();
        if (ok && d < best) {
            best = d;
            f2 = f;
        }
    }
    REQUIRE(f2 < T.size());
    const auto [a, b, c] = T[f1];
    const auto [d, e, f] = T[f2];
    T.erase(T.begin() + std::ptrdiff_t(f2));
    T.erase(T.begin() + std::ptrdiff_t(f1));
    for (auto tri : {std::array<std::int32_t, 3>{a, b, d}, {a, d, e}, {b, c, f}, {b, f, d}, {c, a, e}, {c, e, f}}) T.push_back(tri);
    const VerifyReport r = verify_surface(*s.grid, s.mesh, s.opt);
    INFO(r.summary());
    CHECK(r.mesh.manifold);
    CHECK(r.mesh.oriented);
    REQUIRE(r.mesh.components.size() == 1);
    CHECK(r.mesh.components[0].genus == 1);
    CHECK(r.topology_verdict == TopologyVerdict::Fail);
    CHECK_FALSE(r.passed());
}
