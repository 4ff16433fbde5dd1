// Knife-edge crease tips are cut (octree/segment_walk.h); next to a near-critical face saddle the
// two branches of the crease curve pass within a few trims of each other, and the wedge's tip is
// a neck (saddle above v) or the gap between two fins (below v): cutting it at the full trim
// severs the neck or bridges the gap. So within 4 trims + neck of a face saddle whose neck
// 2 sqrt(|s/k|) is under 4 trims (phi = s + k u w on the face) the trim shrinks to a quarter neck
// (segment_walk.cpp, crease_trace). Tried 2026-11-25 and not kept: no cut at all there. It certified
// this cell too, but property seed 1039 then refined 5873 points into a 0.4 x 0.1 voxel patch
// next to such a saddle and gained a component; with the quarter-neck trim seed 1039 verifies.
#include <catch2/catch.hpp>

#include "mesher_test_support.h"

using namespace isodel;

TEST_CASE("crease cut: a neck through a face saddle just above v on a ridge face stays (property seed 559)",
          "[mesher][crease]")
{
    // One cell of the property test's random volume 559 (plain, n 5), -1 around it. On its face
    // y = 3 the corners 0.893, -0.994, -0.514, 0.572 have their bilinear saddle 2.8e-5 above v,
    // and the face is a ridge (y = 2 is -1): the two inside corner pairs meet in a neck 0.006
    // voxel wide along the face. The full cut (eps / 50 = 0.01 voxel at eps 0.5) took the neck
    // for a crease tip and M had two components; Sigma has one (verify's reference with a lattice
    // plane through the saddle).
    const double s[2][2][2] = {
        {{0.893291, -0.993710}, {0.080112, -0.187721}},  // z = 4: y = 3, y = 4
        {{-0.514067, 0.571950}, {-0.456278, 0.423685}}, // z = 5
    };
    testing::require_certified(*testing::samples_in_box(s, openvdb::Coord(1, 3, 4)), {0.5, 0.25, 0.1}, {0});
}

TEST_CASE("crease cut: held-out random seed 28 at eps 0.25 keeps its topology", "[mesher][crease][!mayfail]")
{
    // Known defect, kept as a reproducer ([!mayfail]: reported on every run, not failing it).
    // random_sweep's plain 5^3 volume of seed 28 (held out: never tuned against) verified at
    // eps 0.25 with the full trim everywhere (8054 vertices) and fails with the quarter-neck trim
    // next to small-neck face saddles (16624 vertices, wrong topology); at eps 0.5 and 0.1 it
    // fails either way. The cause: on the ridge face y = 1 (y = 0 is padding, y = 2 below v) the
    // cell x 2-3, z 4-5 has corners -0.625, 0.503, 0.785, -0.631 and its saddle 2e-4 above v: a
    // neck 0.018 voxel wide but only ~4e-4 thick. The trim there only goes from 0.005 to 0.0044
    // voxel, yet the new vertices (8570 more) all fall in the unit cells (2, 0, 4) and (2, 1, 4)
    // beside it. The cut is still a rule per Voronoi edge (README "Known gaps"), so near such a
    // sliver any change of it moves which cells fail: 129 at eps 0.5 now verifies.
    const auto grid = testing::random_volume(5, 28, false);
    const auto r = testing::mesh_and_verify(*grid, 0.0, Inside::Above, 0.25);
    INFO(r.report.summary());
    CHECK(r.report.reference.determined);
    CHECK(r.report.passed());
}
