// eps at both ends of its range, 10^-3 to 10^4 voxels. A coarse eps must cost no more than a
// fine one: the crease check (hausdorff_creases.cpp) once bucketed M's triangles by the cells
// within the threshold 0.7 eps of them, a number of cells growing as eps cubed, and at
// eps = 100 voxels on a 32^3 volume it never finished; past a few cells it now measures with an
// AABB tree of M. Pinned down here:
//  - eps from 1 to 10^4 voxels gives a certified mesh (topology, eps, Delaunay conformity);
//  - once eps is far above every feature of Sigma, M no longer depends on it: at 10^2, 10^3 and
//    10^4 voxels the face slabs are at their widest and no eps criterion can fire, so the three
//    meshes must be the same, vertex for vertex;
//  - at 10^-3 voxel a small ball is certified within the point bound.
#include <catch2/catch.hpp>

#include "support/mesher_test_support.h"

#include <isodel/volume.h>

#include <cmath>

using namespace isodel;

namespace {

Volume two_blobs() { return read_volume(std::string(ISODEL_TEST_DATA) + "/two_blobs.mrc", ReadOptions()); }

} // namespace

TEST_CASE("coarse eps: certified meshes from 1 to 10^4 voxels", "[refinement][eps]")
{
    const Volume vol = two_blobs();
    std::vector<SurfaceMesh> coarse;
    for (const double eps : {1.0, 8.0, 32.0, 100.0, 1e3, 1e4}) {
        INFO("two_blobs.mrc at iso 0.5, eps " << eps << " voxels");
        testing::MeshAndVerify r;
        REQUIRE_NOTHROW(r = testing::mesh_and_verify(*vol.grid, 0.5, Inside::Above, eps));
        INFO(r.report.summary());
        CHECK(r.report.passed());
        CHECK(r.genera == std::vector<int>{0, 0});
        if (eps >= 100) coarse.push_back(r.mesh.surface);
    }
    REQUIRE(coarse.size() == 3);
    CHECK(coarse[0].vertices == coarse[1].vertices);
    CHECK(coarse[0].triangles == coarse[1].triangles);
    CHECK(coarse[1].vertices == coarse[2].vertices);
    CHECK(coarse[1].triangles == coarse[2].triangles);
}

TEST_CASE("coarse eps: a random volume's crease check at eps 50 voxels", "[refinement][eps]")
{
    // Many small components and creases in every crossed cell: the tree path settles all of them.
    const auto grid = testing::random_volume(8, 3, false);
    const auto r = testing::mesh_and_verify(*grid, 0.0, Inside::Above, 50.0);
    INFO(r.report.summary());
    CHECK(r.report.passed());
}

TEST_CASE("fine eps: a small ball at 10^-3 voxel is certified", "[refinement][eps]")
{
    // The other end of the range: refinement to a thousandth of a voxel stays within its point
    // bound on a small ball (the cost follows the area over eps, not a runaway search).
    auto grid = openvdb::FloatGrid::create(-1.f);
    auto acc = grid->getAccessor();
    for (int z = -4; z <= 4; ++z)
        for (int y = -4; y <= 4; ++y)
            for (int x = -4; x <= 4; ++x)
                acc.setValueOn(openvdb::Coord(x, y, z), float(2.6 - std::sqrt(double(x * x + y * y + z * z))));
    const auto r = testing::mesh_and_verify(*grid, 0.0, Inside::Above, 1e-3);
    INFO(r.report.summary());
    CHECK(r.report.passed());
    CHECK(r.genera == std::vector<int>{0});
}
