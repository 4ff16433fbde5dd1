// CBP_VF's loop clause (src/closed_ball/facet_loops.cpp) on degenerate Voronoi facets. Samples at
// exactly v (quantized data, the tie rule of octree/sample_field.h) make symmetric point sets:
// E points concyclic around a face centre, N points mirrored across a grid plane. Their Voronoi
// facets are exactly perpendicular to an axis or have vertices that coincide up to rounding, and
// the loop scan must still see the thin tubes of Sigma through them. Both volumes are crops of
// the property test's quantized random volumes (tests/corpus/test_verify_property.cpp) in which
// M lost part of Sigma; the literal samples are kept here (inside = above 0, -1 around).
#include <catch2/catch.hpp>

#include "support/mesher_test_support.h"

using namespace isodel;


TEST_CASE("a needle along a grid edge through a facet perpendicular to it is seen (quantized seed 910)",
          "[mesher][facet-loops]")
{
    // Four tie samples joined by grid edges: at v* just below v, Sigma is a needle ~0.03 voxel
    // thick around those edges. Two N points on the needle along the x edge (y = 1, z = 4) have
    // a Voronoi facet exactly perpendicular to x, whose bounding box has zero thickness; the
    // point of the edge solved onto its plane fell just outside the box, and M lost the needle's
    // middle (3 components instead of 2).
    const double s[3][2][2] = {
        {{-0.5, -1.0}, {1.0, -0.5}}, // z = 2
        {{0.0, -1.0}, {-0.5, 0.5}},  // z = 3
        {{0.0, 0.0}, {0.0, -1.0}},   // z = 4
    };
    testing::require_certified(*testing::samples_in_box(s, openvdb::Coord(1, 1, 2)), {0.5, 0.25}, {0, 0});
}

TEST_CASE("a neck through a face saddle at exactly v is seen across coincident Voronoi vertices (quantized seed 1275)",
          "[mesher][facet-loops]")
{
    // On the face y = 1, x in [3, 4], z in [4, 5], the corners are -0.5, 0.5, 0.5, -0.5: the
    // bilinear saddle is exactly v, so at v* the blob of (3, 1, 5) joins the rest through a flat
    // neck ~0.04 x 0.12 voxel. The Voronoi facet across the neck has two vertices that coincide up
    // to rounding (cospherical sites), and that 1e-16 edge made the face point look outside the
    // facet: M had the blob as a third component.
    const double s[5][4][3] = {
        {{1.0, 0.0, 0.5}, {-0.5, 0.0, 0.0}, {-0.5, 0.5, 0.5}, {0.0, -0.5, 0.0}},    // z = 1
        {{0.5, -0.5, 0.5}, {-1.0, 0.0, 1.0}, {0.0, 0.5, -1.0}, {-0.5, 0.5, 0.0}},   // z = 2
        {{0.5, 0.0, -0.5}, {0.5, 0.0, -0.5}, {0.0, 1.0, 0.0}, {0.5, 1.0, 0.0}},     // z = 3
        {{-0.5, 0.5, 0.5}, {0.5, -0.5, 1.0}, {-0.5, -0.5, 0.0}, {-0.5, -0.5, 0.0}}, // z = 4
        {{0.5, -0.5, 1.0}, {-1.0, 0.0, -0.5}, {-0.5, 0.0, 1.0}, {-0.5, -0.5, 0.0}}, // z = 5
    };
    testing::require_certified(*testing::samples_in_box(s, openvdb::Coord(3, 1, 1)), {0.5, 0.25}, {0, 3});
}
