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

TEST_CASE("crease cut: Sigma next to a valley-and-ridge grid edge keeps its topology (property seed 719)",
          "[mesher][crease][!mayfail]")
{
    // Known defect of the guard above, kept as a reproducer ([!mayfail]). A 3 x 2 x 3 crop of the
    // property test's random volume 719 (plain, n 5), -1 around: the edge (4,4,4)-(4,5,4) has
    // samples -0.0041 and 0.0019, a valley of F along x and a ridge along z (the crop's padding),
    // so the guard keeps every pair within 4 trims of it. Refinement there inserts ~9800 points
    // and M has genus 5; Sigma is a sphere. Without the guard this crop and seed 719 verify (99
    // and 1606 vertices) but random_n16_s4 of ../shared/data does not.
    const double s[3][2][3] = {
        {{-0.636284, 0.045230, 0.621790}, {0.332669, -0.568727, -0.362615}}, // z = 2: y = 4, y = 5
        {{0.848561, -0.406787, 0.398569}, {-0.277379, -0.867663, 0.927309}},  // z = 3
        {{0.307809, -0.004072, -0.178860}, {0.596089, 0.001850, 0.574702}},   // z = 4
    };
    testing::require_certified(*testing::samples_in_box(s, openvdb::Coord(3, 4, 2)), {0.5}, {0});
}
