// How partitioned meshing cuts the domain (src/surface/block_partition.h): a count of blocks of
// about equal work is factored so that the cut faces are smallest and cut where the grid-edge
// crossings split evenly; every partition's cores tile the domain once; each block's neighbours
// are exactly the blocks whose boxes meet its own region; a block's work counts the crossings
// in its box. Partitions are checked against brute force over every pair of blocks and every
// crossing.
#include <catch2/catch.hpp>

#include "octree/edge_crossings.h"
#include "surface/block_partition.h"
#include "surface/partitioned_meshing.h"
#include "support/mesher_test_support.h"

#include <isodel/errors.h>
#include <isodel/mesh.h>

#include <algorithm>
#include <map>
#include <set>

using namespace isodel;
using namespace isodel::mesher;

namespace {

/// A torus off-centre in a box of nx x ny x nz samples, so that the crossings are not spread
/// evenly along any axis.
openvdb::FloatGrid::Ptr box_torus(int nx, int ny, int nz)
{
    auto grid = openvdb::FloatGrid::create(-1.0f);
    auto acc = grid->getAccessor();
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i)
                acc.setValueOn(openvdb::Coord(i, j, k),
                               float(testing::torus_f(openvdb::Vec3d(i, j, k), openvdb::Vec3d(0.3 * nx, 0.5 * ny, 0.5 * nz),
                                                      0.3 * ny, 0.15 * ny)));
    return grid;
}

/// Does the box of \p j meet the own region of \p i (own_lo <= q < own_hi)?
bool meets(const BlockSpec& j, const BlockSpec& i)
{
    for (int a = 0; a < 3; ++a)
        if (!(j.box.min()[a] < i.own_hi[a] && j.box.max()[a] >= i.own_lo[a])) return false;
    return true;
}

void check_tiles_and_neighbours(const octree::SampleField& field, const std::vector<BlockSpec>& blocks)
{
    const openvdb::CoordBBox cells(field.domain().min(), field.domain().max().offsetBy(-1));
    std::map<openvdb::Coord, int> owners;
    for (const auto& b : blocks)
        for (auto it = b.core.beginZYX(); it; ++it)
            if (cells.isInside(*it)) ++owners[*it];
    CHECK(owners.size() == cells.volume());
    for (const auto& [c, n] : owners) REQUIRE(n == 1);
    for (std::size_t i = 0; i < blocks.size(); ++i) {
        std::vector<std::size_t> brute;
        for (std::size_t j = 0; j < blocks.size(); ++j)
            if (j != i && meets(blocks[j], blocks[i])) brute.push_back(j);
        REQUIRE(neighbours(blocks, i) == brute);
    }
}

} // namespace

TEST_CASE("a block count is cut where the crossings split evenly, on the longest axes", "[mesher][partition]")
{
    const auto grid = box_torus(60, 30, 20);
    openvdb::FloatGrid::ConstPtr g = grid;
    const octree::SampleField field(g, 0.0, Inside::Above);
    const std::vector<octree::EdgePoint> e = octree::edge_crossings(field).points;
    REQUIRE(e.size() > 1000);
    const openvdb::Coord o = field.domain().min();
    // The crossings per x slice, for checking the cuts.
    std::map<int, long> slice;
    for (const auto& p : e) ++slice[std::clamp(p.lower[0], o[0], field.domain().max()[0] - 1)];
    for (int count : {2, 3, 5}) {
        INFO(count << " blocks");
        const BlockCuts c = balanced_cuts(field, count, e);
        // A prime count, or two: slabs of the longest axis (x), whose cut faces are smallest.
        CHECK(c.at[0].size() == std::size_t(count) + 1);
        CHECK(c.at[1].size() == 2);
        CHECK(c.at[2].size() == 2);
        // Each cut k is the first slice at which the crossings before it reach k / count of all.
        const long total = long(e.size());
        for (int k = 1; k < count; ++k) {
            const int at = c.at[0][std::size_t(k)];
            long before = 0, before_last = 0;
            for (const auto& [x, n] : slice) {
                if (x < at) before += n;
                if (x < at - 1) before_last += n;
            }
            CHECK(before * count >= long(k) * total);
            CHECK(before_last * count < long(k) * total);
            CHECK(at - c.at[0][std::size_t(k) - 1] >= kMinBlockVoxels);
        }
        check_tiles_and_neighbours(field, blocks_of(c, collar_voxels(field)));
    }
    // Eight blocks: four slabs of x halved along y cut less than eight slabs of x or halving
    // every axis.
    const BlockCuts eight = balanced_cuts(field, 8, e);
    CHECK(eight.at[0].size() == 5);
    CHECK(eight.at[1].size() == 3);
    CHECK(eight.at[2].size() == 2);
    check_tiles_and_neighbours(field, blocks_of(eight, collar_voxels(field)));
    // No crossings: even slabs.
    const BlockCuts even = balanced_cuts(field, 3, {});
    const int cells_x = field.domain().max()[0] - o[0];
    CHECK(even.at[0] == std::vector<int>{o[0], o[0] + cells_x / 3, o[0] + 2 * cells_x / 3, o[0] + cells_x});
    // Blocks narrower than kMinBlockVoxels on every factoring are refused, as are bad counts.
    CHECK_THROWS_AS(balanced_cuts(field, 997, e), InvalidInput);
    CHECK_THROWS_AS(balanced_cuts(field, 0, e), InvalidInput);
}

TEST_CASE("cubes and counts: neighbours and work against brute force", "[mesher][partition]")
{
    const auto grid = box_torus(40, 26, 18);
    openvdb::FloatGrid::ConstPtr g = grid;
    const octree::SampleField field(g, 0.0, Inside::Above);
    const std::vector<octree::EdgePoint> e = octree::edge_crossings(field).points;
    for (const auto& [name, cuts] : {std::pair<const char*, BlockCuts>{"cubes of 4", cubic_cuts(field, 4)},
                                     {"cubes of 9", cubic_cuts(field, 9)},
                                     {"6 balanced", balanced_cuts(field, 6, e)}}) {
        INFO(name);
        for (int grow : {0, 4}) {
            std::array<int, 3> collar = collar_voxels(field);
            for (int& c : collar) c += grow;
            const std::vector<BlockSpec> blocks = blocks_of(cuts, collar);
            check_tiles_and_neighbours(field, blocks);
            std::vector<double> brute(blocks.size(), 1.0);
            for (const auto& p : e)
                for (std::size_t j = 0; j < blocks.size(); ++j)
                    if (blocks[j].box.isInside(p.lower)) brute[j] += 1;
            REQUIRE(block_work(blocks, e) == brute);
        }
    }
    // Cubes are the old lattice: every B cells from the domain's corner.
    const BlockCuts c9 = cubic_cuts(field, 9);
    for (int a = 0; a < 3; ++a) {
        const int o = field.domain().min()[a], cells = field.domain().max()[a] - o;
        REQUIRE(c9.at[a].size() == std::size_t((cells + 8) / 9 + 1));
        for (std::size_t x = 0; x < c9.at[a].size(); ++x) CHECK(c9.at[a][x] == o + 9 * int(x));
    }
}

TEST_CASE("balanced blocks mesh what verifies, the same at 1 and 2 threads", "[mesher][partition][determinism]")
{
    const auto grid = box_torus(48, 26, 20);
    for (int count : {2, 3}) {
        INFO(count << " blocks");
        MeshOptions mo;
        mo.isovalue = 0.0;
        mo.inside = Inside::Above;
        mo.eps_voxels = 0.25;
        mo.block_count = count;
        mo.threads = 1;
        const testing::MeshAndVerify a = testing::mesh_and_verify(*grid, mo);
        mo.threads = 2;
        const MeshResult b = mesh_isosurface(*grid, mo);
        CHECK(a.mesh.stats.partition.blocks == count);
        CHECK(a.mesh.surface.vertices == b.surface.vertices);
        CHECK(a.mesh.surface.triangles == b.surface.triangles);
        INFO(a.report.summary());
        CHECK(a.report.passed());
        CHECK(a.report.topology_verdict == TopologyVerdict::Pass);
        CHECK(a.genera == std::vector<int>{1});
    }
    MeshOptions both;
    both.block_count = 2;
    both.block_voxels = 16;
    CHECK_THROWS_AS(check_mesh_options(both), InvalidInput);
    MeshOptions negative;
    negative.block_count = -1;
    CHECK_THROWS_AS(check_mesh_options(negative), InvalidInput);
    MeshOptions release;
    release.block_count = 2;
    release.release_blocks = true;
    CHECK_NOTHROW(check_mesh_options(release));
}
