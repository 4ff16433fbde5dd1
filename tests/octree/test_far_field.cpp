// Far-field leaves (octree/far_field.h): where a sparse grid stores nothing, a cell is a leaf as
// coarse as max_level when its span touches no allocated leaf node and reads one strict sign;
// with them the seed octree of a narrow-band level set coarsens at Sigma past the band's width.
#include "octree/balance.h"
#include "octree/far_field.h"
#include "octree/seed_octree.h"

#include <catch2/catch.hpp>

#include <openvdb/tools/LevelSetSphere.h>

namespace {

using isodel::Inside;
using isodel::octree::AdaptiveGrid;
using isodel::octree::CellId;
using isodel::octree::Coord;
using isodel::octree::CoordBBox;
using isodel::octree::SampleField;

openvdb::FloatGrid::Ptr band_sphere(float radius)
{
    openvdb::initialize();
    return openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(radius, openvdb::Vec3f(0.3f, -0.2f, 0.1f), 1.0f,
                                                                    3.0f);
}

} // namespace

TEST_CASE("far field: a span reads stored samples, one sign or both", "[octree][far_field]")
{
    auto grid = openvdb::FloatGrid::create(1.0f);
    grid->tree().addTile(1, Coord(0, 0, 0), -2.0f, false);  // an 8^3 tile inside
    grid->tree().addTile(1, Coord(16, 0, 0), -2.0f, false); // another one
    grid->tree().setValueOn(Coord(40, 0, 0), 0.5f);         // an allocated leaf node at 40..47
    grid->tree().setValueOn(Coord(-30, -30, -30), 1.0f);    // spreads the active box
    grid->tree().setValueOn(Coord(60, 30, 30), 1.0f);
    const SampleField f(grid, 0.0, Inside::Below); // phi > 0 below 0: the tiles
    auto acc = grid->getConstAccessor();
    const auto read = [&](Coord lo, Coord hi) { return isodel::octree::read_span(f, acc, CoordBBox(lo, hi)); };

    const auto in_tile = read(Coord(1, 1, 1), Coord(7, 7, 7));
    CHECK(in_tile.one_sign());
    CHECK(in_tile.positive);
    const auto background = read(Coord(-20, -20, -20), Coord(-10, -10, -10));
    CHECK(background.one_sign());
    CHECK(background.negative);
    // Closed spans: [0, 8] reaches the background at x = 8.
    const auto across = read(Coord(0, 0, 0), Coord(8, 4, 4));
    CHECK_FALSE(across.one_sign());
    CHECK((across.positive && across.negative));
    const auto stored = read(Coord(24, 0, 0), Coord(40, 4, 4));
    CHECK(stored.stored);
    CHECK_FALSE(stored.one_sign());
    CHECK(read(Coord(24, 0, 0), Coord(39, 4, 4)).one_sign()); // stops one short of the leaf node
}

TEST_CASE("far field: leaves off the band, of one sign, balanced after; the band sphere coarsens at Sigma",
          "[octree][far_field]")
{
    const auto grid = band_sphere(30.0f);
    const SampleField f(grid, 0.0, Inside::Below);
    AdaptiveGrid g(grid, 1);
    const std::size_t set = isodel::octree::coarsen_far_field(g, f, 4);
    CHECK(set > 0);
    CHECK_THROWS(isodel::octree::coarsen_far_field(g, f, 4)); // only on a uniform grid
    auto acc = grid->getConstAccessor();
    std::size_t coarsest = 0;
    for (int l = 1; l <= g.max_level(); ++l)
        for (const CellId& c : g.leaves(l)) {
            const auto r = isodel::octree::read_span(f, acc, c.nodes());
            CHECK(r.one_sign());
            CHECK(g.inside(c));
            coarsest += l >= 3;
        }
    CHECK(coarsest > 0); // 8-voxel leaves inside the band (a 16-voxel one would reach it)

    // The seed octree with and without the far field: leaves at Sigma reach past level 2 only
    // with it (a level-0 far field 3 voxels from Sigma caps them, balance.h).
    isodel::octree::SeedOctreeOptions so;
    so.k = 1;
    so.max_level = 5;
    const AdaptiveGrid seeded = isodel::octree::seed_octree(f, so);
    CHECK(isodel::octree::max_level_difference(seeded) <= 1);
    const AdaptiveGrid::Reader r(seeded);
    int coarsest_at_sigma = 0;
    for (auto it = grid->tree().cbeginValueOn(); it; ++it)
        if (std::abs(*it) < 0.5f) coarsest_at_sigma = std::max(coarsest_at_sigma, r.leaf_level(it.getCoord()));
    CHECK(coarsest_at_sigma >= 3);
}
