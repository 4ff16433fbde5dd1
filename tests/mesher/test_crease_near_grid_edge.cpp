// Knife-edge crease tips are cut (octree/segment_walk.h), but not next to a critical grid edge
// (CreaseTolerance::critical_edge): there Sigma is four trilinear patches around the edge (a
// steep saddle, a thin tube or neck), not a wedge, and cutting changes its topology. The volume
// is a 5^3 crop of ../shared/data/cells/random_n16_s4 around the grid edge (1,1,1)-(1,1,2) with
// samples 0.0076 and -0.0023 (v = 0): across the edge F has a ridge along x and a valley along y.
// Without the guard isodel meshed genus 1 at eps 0.5 and 0.25 voxel (all 139 cut pairs within
// 0.013 voxel of that edge); Sigma is a sphere (verify's reference, and brute force at R = 128).
// The random 5^3 volume of seed 25 (plain, eps 0.5) is the same defect with one side of the
// edge's second direction within 1 % of v: genus 6 instead of 7 until such a side counted as
// turning either way.
#include <catch2/catch.hpp>

#include "mesher_test_support.h"
#include "../verify/verify_test_support.h"

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

TEST_CASE("crease cut: Sigma around a grid edge with both samples near v keeps its topology", "[mesher][crease]")
{
    testing::require_certified(*crop_near_grid_edge(), {0.5, 0.25, 0.1}, {0});
}

TEST_CASE("crease cut: a critical grid edge with one neighbour within 1 % of v (random seed 25)", "[mesher][crease]")
{
    // testing::random_volume(5, 25): edge (3,4,5)-(3,5,5) with samples -0.0016 and 0.0028; across
    // it F has a ridge along x, and along z one side is -1 (padding) and the other 0.0148. The
    // reference (verify) has one component of genus 7.
    testing::require_certified(*testing::random_volume(5, 25, false), {0.5, 0.25, 0.1}, {7});
}
