// Resampling an adaptive grid to the finest lattice (resample.h): exact for trilinear.
#include "support/adaptive_random.h"

#include "octree/interpolant.h"
#include "octree/resample.h"
#include "octree/sample_field.h"

#include <isodel/adaptive.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace isodel::octree;

TEST_CASE("resample of a uniform grid is the grid", "[octree][resample]")
{
    auto s = isodel::octree::testing::random_samples(10, 4);
    const AdaptiveGrid g(s, 1);
    auto d = resample_dense(g);
    auto a = d->getConstAccessor();
    auto b = s->getConstAccessor();
    for (auto it = g.domain().begin(); it; ++it) CHECK(a.getValue(*it) == b.getValue(*it));
    CHECK(d->evalActiveVoxelBoundingBox() == s->evalActiveVoxelBoundingBox());
}

TEST_CASE("the dense trilinear interpolant of the resampled grid equals the adaptive F", "[octree][resample]")
{
    std::mt19937 rng(8);
    std::uniform_real_distribution<double> u(-1, 18);
    for (unsigned seed = 1; seed <= 6; ++seed) {
        auto g = isodel::octree::testing::random_adaptive(400 + seed, 1 + seed % 3, 18, 4);
        auto dense = resample_dense(*g);
        const AdaptiveGrid dg(dense, 1);
        CHECK(dg.domain() == g->domain()); // same domain rule
        InterpolantReader ia(*g), id(dg);
        double worst = 0;
        for (int i = 0; i < 2000; ++i) {
            const Vec3d p(u(rng), u(rng), u(rng));
            const auto fa = ia.eval(p), fd = id.eval(p);
            REQUIRE(fa);
            REQUIRE(fd);
            worst = std::max(worst, std::abs(*fa - *fd));
        }
        // Exact up to storing F at the nodes as float.
        CHECK(worst <= 1e-6);
    }
}

TEST_CASE("resample_dense: the active box's extreme nodes keep their values when they lie in a tile",
          "[octree][resample]")
{
    // Two voxels in one internal node but different leaves: the box's lowest corner (0, 0, 20)
    // is an unallocated tile slot of that node. Reading its value by reference and writing it
    // back allocates the leaf over the reference (the bug this pins: pointer bits as a value).
    auto grid = openvdb::FloatGrid::create(-1.0f);
    grid->tree().setValue(openvdb::Coord(0, 20, 20), 2.0f);
    grid->tree().setValue(openvdb::Coord(20, 0, 24), 3.0f);
    const AdaptiveGrid g(grid, 1);
    const auto dense = resample_dense(g);
    const openvdb::Coord lo(0, 0, 20), hi(20, 20, 24);
    CHECK(dense->tree().getValue(lo) == -1.0f);
    CHECK(dense->tree().getValue(hi) == -1.0f);
    CHECK(dense->evalActiveVoxelBoundingBox() == grid->evalActiveVoxelBoundingBox());
}
