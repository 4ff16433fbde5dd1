// Results do not depend on the thread count: the same volume and options give the same vertices
// and triangles, bit for bit, with 1 and 2 threads (random volumes exercise every refinement
// phase; the torus a smooth surface; a larger torus with --snap fills E and G, less the snapped
// E points, over several parallel chunks).
#include <catch2/catch.hpp>

#include "support/mesher_test_support.h"


using namespace isodel;

namespace {

MeshResult check_same(const openvdb::FloatGrid& grid, double eps_voxels, bool snap = false)
{
    MeshOptions mo;
    mo.snap = snap;
    mo.isovalue = 0.0;
    mo.inside = Inside::Above;
    mo.eps_voxels = eps_voxels;
    mo.threads = 1;
    const MeshResult a = mesh_isosurface(grid, mo);
    mo.threads = 2;
    const MeshResult b = mesh_isosurface(grid, mo);
    REQUIRE(a.surface.vertices.size() == b.surface.vertices.size());
    REQUIRE(a.surface.triangles.size() == b.surface.triangles.size());
    const bool same_vertices = a.surface.vertices == b.surface.vertices;
    const bool same_triangles = a.surface.triangles == b.surface.triangles;
    CHECK(same_vertices);
    CHECK(same_triangles);
    return b;
}

} // namespace

TEST_CASE("same mesh with 1 and 2 threads", "[mesher][determinism]")
{
    for (unsigned seed : {3u, 11u, 19u}) {
        INFO("random volume seed " << seed);
        check_same(*testing::random_volume(6, seed, false), 0.25);
    }
    auto torus = testing::make_grid(32, 1.0, openvdb::Vec3d(0.0), [](const openvdb::Vec3d& x) {
        return testing::torus_f(x, openvdb::Vec3d(15.5, 15.3, 15.7), 8.0, 3.0);
    });
    check_same(*torus, 0.1);
}

TEST_CASE("same mesh with 1 and 2 threads when E points snap to samples", "[mesher][determinism][snap]")
{
    auto torus = testing::make_grid(72, 1.0, openvdb::Vec3d(0.0), [](const openvdb::Vec3d& x) {
        return testing::torus_f(x, openvdb::Vec3d(35.5, 35.3, 35.7), 22.0, 9.0);
    });
    const MeshResult r = check_same(*torus, 0.5, true);
    CHECK(r.stats.snapped > 0);
    CHECK(r.stats.e_points > 2 * 4096); // several chunks of the parallel fill
}
