// isodel verify --tets can fail: a tetrahedral mesh from isodel mesh --tets of a sphere volume
// passes, and each planted defect (an inverted tet, a missing tet, an unknown region tag, a tet
// moved from inside to outside, a moved surface vertex) is caught by the counter that should
// catch it. The checks use only the two meshes (src/verify/verify_tets.cpp).
#include <catch2/catch.hpp>

#include "support/verify_test_support.h"

#include <isodel/mesh.h>
#include <isodel/verify.h>

using namespace isodel;
using openvdb::Vec3d;

namespace {

MeshResult sphere_with_tets()
{
    const Vec3d c(6.3, 6.6, 6.1);
    auto grid = testing::make_grid(14, 0.5, Vec3d(-1.0, 0.5, 2.0), [&](const Vec3d& x) { return testing::sphere_f(x, c, 2.2); });
    MeshOptions mo;
    mo.isovalue = 0.0;
    mo.inside = Inside::Above;
    mo.tets = TetRegion::Both;
    return mesh_isosurface(*grid, mo);
}

std::size_t first_inside(const TetMesh& t)
{
    for (std::size_t i = 0; i < t.tets.size(); ++i)
        if (t.tet_region[i] == 1) return i;
    return 0;
}

} // namespace

TEST_CASE("verify --tets: isodel's tet mesh passes, planted defects are caught", "[verify][tets]")
{
    const MeshResult res = sphere_with_tets();
    const TetReport ok = verify_tets(res.tets, res.surface);
    INFO("tets " << ok.tets << " inside " << ok.inside_tets << " rel " << ok.volume_rel_error);
    REQUIRE(ok.passed);
    CHECK(ok.inside_tets > 0);
    CHECK(ok.outside_tets > 0);
    CHECK(ok.boundary_faces == res.surface.triangles.size());
    CHECK(ok.volume_rel_error <= 1e-9);

    SECTION("an inverted tet")
    {
        TetMesh t = res.tets;
        auto& q = t.tets[first_inside(t)];
        std::swap(q[0], q[1]);
        const TetReport r = verify_tets(t, res.surface);
        CHECK_FALSE(r.passed);
        CHECK(r.inverted == 1);
    }
    SECTION("a missing inside tet (a hole in the volume)")
    {
        TetMesh t = res.tets;
        const std::size_t i = first_inside(t);
        t.tets.erase(t.tets.begin() + std::ptrdiff_t(i));
        t.tet_region.erase(t.tet_region.begin() + std::ptrdiff_t(i));
        const TetReport r = verify_tets(t, res.surface);
        CHECK_FALSE(r.passed);
        CHECK(r.boundary_not_in_mesh > 0);
        CHECK(r.volume_rel_error > 1e-9);
    }
    SECTION("an unknown region tag")
    {
        TetMesh t = res.tets;
        t.tet_region[first_inside(t)] = 3;
        const TetReport r = verify_tets(t, res.surface);
        CHECK_FALSE(r.passed);
        CHECK(r.unknown_region == 1);
    }
    SECTION("an inside tet tagged outside")
    {
        TetMesh t = res.tets;
        t.tet_region[first_inside(t)] = 2;
        const TetReport r = verify_tets(t, res.surface);
        CHECK_FALSE(r.passed);
        CHECK(r.boundary_not_in_mesh + r.mesh_not_in_boundary > 0);
    }
    SECTION("a surface vertex that is not a tet vertex")
    {
        SurfaceMesh m = res.surface;
        m.vertices[0][0] += 1e-9;
        const TetReport r = verify_tets(res.tets, m);
        CHECK_FALSE(r.passed);
        CHECK(r.unmatched_mesh_vertices == 1);
    }
}
