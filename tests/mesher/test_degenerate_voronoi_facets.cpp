// CBP_VF's loop clause (src/mesher/facet_loops.cpp) on degenerate Voronoi facets. Samples at
// exactly v (quantized data, the tie rule of octree/sample_field.h) make symmetric point sets:
// E points concyclic around a face centre, N points mirrored across a grid plane. Their Voronoi
// facets are exactly perpendicular to an axis or have vertices that coincide up to rounding, and
// the loop scan must still see the thin tubes of Sigma through them. Both volumes are crops of
// the property test's quantized random volumes (tests/corpus/test_verify_property.cpp) in which
// M lost part of Sigma; the literal samples are kept here (inside = above 0, -1 around).
#include <catch2/catch.hpp>

#include "mesher_test_support.h"

using namespace isodel;

namespace {

/// samples[z][y][x] at index (x0 + x, y0 + y, z0 + z); every other sample is -1.
template <int NZ, int NY, int NX>
openvdb::FloatGrid::Ptr crop(const double (&samples)[NZ][NY][NX], openvdb::Coord origin)
{
    auto grid = openvdb::FloatGrid::create(-1.f);
    auto acc = grid->getAccessor();
    for (int z = -1; z <= NZ; ++z)
        for (int y = -1; y <= NY; ++y)
            for (int x = -1; x <= NX; ++x) {
                const bool core = x >= 0 && x < NX && y >= 0 && y < NY && z >= 0 && z < NZ;
                acc.setValueOn(origin.offsetBy(x, y, z), core ? float(samples[z][y][x]) : -1.f);
            }
    return grid;
}

void require_verified(const openvdb::FloatGrid& grid, double eps, std::size_t components)
{
    const auto r = testing::mesh_and_verify(grid, 0.0, Inside::Above, eps);
    INFO("eps " << eps << " voxel\n" << r.report.summary());
    CHECK(r.report.reference.determined);
    CHECK(r.report.reference.components.size() == components);
    CHECK(r.report.topology_verdict == "pass");
    CHECK(r.report.passed());
}

} // namespace

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
    const auto grid = crop(s, openvdb::Coord(1, 1, 2));
    for (double eps : {0.5, 0.25}) require_verified(*grid, eps, 2);
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
    const auto grid = crop(s, openvdb::Coord(3, 1, 1));
    for (double eps : {0.5, 0.25}) require_verified(*grid, eps, 2);
}
