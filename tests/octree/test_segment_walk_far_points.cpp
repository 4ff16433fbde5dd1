// phi_at and segment_crossings (octree/segment_walk.h) at points beyond the int range of cell
// indices: the circumcentre of a nearly flat tet can be 10^17 voxels away, and the closed ball
// checks read phi there. Such points read the outside value, and no index conversion is undefined
// (this file runs under UBSan in the sanitizer step, where the old conversion was reported).
#include "octree/segment_walk.h"

#include <catch2/catch.hpp>


using namespace isodel::octree;

TEST_CASE("points beyond the index range read the outside value", "[octree][segment]")
{
    auto g = openvdb::FloatGrid::create(0.f);
    for (int z = 0; z <= 4; ++z)
        for (int y = 0; y <= 4; ++y)
            for (int x = 0; x <= 4; ++x) g->tree().setValueOn(Coord(x, y, z), float(x) - 2.f);
    const SampleField field(g, 0.0, isodel::Inside::Above);
    const SampleField::Reader reader(field);
    for (double far : {1.6e17, -1.6e17, 3e9, -3e9}) {
        INFO("x = " << far);
        CHECK(phi_at(reader, Vec3d(far, 2, 2)) == field.outside_phi());
        CHECK(phi_at(reader, Vec3d(2, far, 2)) == field.outside_phi());
    }
    // A segment from inside the box to a far point: bounded by max_cells, so it reports overflow.
    const SegmentCrossings s = segment_crossings(reader, Vec3d(3.5, 2, 2), Vec3d(1.6e17, 2, 2), 64);
    CHECK(s.overflow);
    CHECK(s.cells_visited <= 64 + 1);
}
