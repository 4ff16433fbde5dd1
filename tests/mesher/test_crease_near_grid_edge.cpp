// OPEN DEFECT (issue 4), kept as a reproducer: knife-edge crease tips are cut
// (octree/segment_walk.h), and next to a grid edge whose two samples are both near v that cut
// changes Sigma's topology - there Sigma is four trilinear patches around the edge, not a wedge.
// The volume is a 5^3 crop of ../shared/data/cells/random_n16_s4 around the grid edge
// (1,1,1)-(1,1,2) with samples 0.0076 and -0.0023 (v = 0): isodel meshes genus 1 at eps 0.5 and
// 0.25 voxel (all 139 cut pairs lie within 0.013 voxel of that edge); Sigma is a sphere (verify's
// reference, and brute force at R = 128 without critical planes). Without the cut (trim 0) every
// eps gives genus 0. A guard (no cut within 4 trims of an edge whose samples are within 1 % of
// the range of v) fixed this and random_n16_s4, but em/emd3001 at eps 0.5 then had 54
// components instead of 53, so the guard was not kept (2026-11-25). [!mayfail]: reported on every
// run, not failing it; the whole volume is in tests/corpus/test_mesh_near_critical.cpp.
#include <catch2/catch.hpp>

#include "mesher_test_support.h"

using namespace isodel;

namespace {

openvdb::FloatGrid::Ptr crop_near_grid_edge()
{
    // Samples (x, y, z) for x, y in 0..2, z in 1..2; everything else -1 (background).
    const float z1[3][3] = {{-0.205106735f, 0.544205189f, 0.538490653f},
                            {-0.29514721f, 0.00763360318f, 0.240934029f},
                            {-0.0808774829f, -0.188077092f, 0.41561541f}};
    const float z2[3][3] = {{-0.592730463f, 0.427845776f, 0.78632021f},
                            {-0.784723699f, -0.00225815875f, -0.347205967f},
                            {0.181892663f, 0.185433194f, -0.787881792f}};
    auto grid = openvdb::FloatGrid::create(-1.f);
    auto acc = grid->getAccessor();
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x) {
            acc.setValueOn(openvdb::Coord(x, y, 1), z1[y][x]);
            acc.setValueOn(openvdb::Coord(x, y, 2), z2[y][x]);
        }
    return grid;
}

} // namespace

TEST_CASE("crease cut: Sigma around a grid edge with both samples near v keeps its topology", "[mesher][crease][!mayfail]")
{
    testing::require_certified(*crop_near_grid_edge(), {0.5, 0.25, 0.1}, {0});
}
