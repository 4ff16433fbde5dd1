// Extended level sets (octree/extended_level_set.h): the corner source of coarse cells keeps the
// narrow band's values and active voxels, and beyond the band holds distances, not the clamp.
#include "octree/extended_level_set.h"

#include <openvdb/tools/LevelSetSphere.h>

#include <catch2/catch.hpp>

#include <cmath>

TEST_CASE("extend_level_set: the band is unchanged, new voxels are inactive distances", "[octree][adaptive]")
{
    const openvdb::Vec3f centre(0.3f, -0.2f, 0.1f);
    const float radius = 20.f;
    const auto sphere = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(radius, centre, 1.0f, 3.0f);
    const auto ext = isodel::octree::extend_level_set(*sphere, 6);
    REQUIRE(ext);
    CHECK(ext->evalActiveVoxelBoundingBox() == sphere->evalActiveVoxelBoundingBox());
    CHECK(ext->activeVoxelCount() == sphere->activeVoxelCount());
    auto in = sphere->getConstAccessor();
    auto out = ext->getConstAccessor();
    for (auto it = sphere->cbeginValueOn(); it; ++it) CHECK(out.getValue(it.getCoord()) == *it);
    // Beyond the band (distance 4 to 8 voxels from Sigma): within a voxel of the true distance
    // (OpenVDB's dilation is approximate; the certificate checks what it gives), where the input
    // holds its clamp of +-3, up to 5 voxels off.
    double worst = 0;
    int beyond = 0;
    for (int x = -30; x <= 30; ++x) {
        const openvdb::Coord c(x, 0, 0);
        const double d = std::abs(x - centre.x()) - radius; // along the axis through the centre
        if (std::abs(d) < 4 || std::abs(d) > 8) continue;
        ++beyond;
        CHECK(std::abs(in.getValue(c)) == Approx(3.0));
        CHECK_FALSE(out.isValueOn(c));
        worst = std::max(worst, std::abs(out.getValue(c) - d));
    }
    CHECK(beyond >= 8);
    INFO("worst error beyond the band " << worst);
    CHECK(worst < 1.0);
}

TEST_CASE("extend_level_set: refuses what is not a level set", "[octree][adaptive]")
{
    auto fog = openvdb::FloatGrid::create(0.f);
    fog->tree().setValue(openvdb::Coord(0), 1.f);
    CHECK_FALSE(isodel::octree::extend_level_set(*fog, 4));
    const auto sphere = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(5.f, openvdb::Vec3f(0.f), 1.f);
    CHECK_FALSE(isodel::octree::extend_level_set(*sphere, 0));
}

TEST_CASE("extend_level_set: a level set stored densely has no band to extend", "[octree][adaptive]")
{
    // Every voxel of the active box active (an analytic distance sampled on a box): nothing
    // inside the box is missing, so no copy is made; drop one voxel and there is a gap to fill.
    auto dense = openvdb::FloatGrid::create(10.f);
    dense->setGridClass(openvdb::GRID_LEVEL_SET);
    auto acc = dense->getAccessor();
    for (int k = 0; k < 20; ++k)
        for (int j = 0; j < 20; ++j)
            for (int i = 0; i < 20; ++i)
                acc.setValueOn(openvdb::Coord(i, j, k),
                               float(std::sqrt((i - 9.7) * (i - 9.7) + (j - 10.2) * (j - 10.2) + (k - 9.9) * (k - 9.9)) - 6));
    CHECK_FALSE(isodel::octree::extend_level_set(*dense, 8));
    acc.setValueOff(openvdb::Coord(0, 0, 0));
    CHECK(isodel::octree::extend_level_set(*dense, 8));
}
