// Exact Delaunay conformity on cospherical input: the 8 corners of a cube are cospherical, so
// CGAL's Del picks one diagonal per face and the other is only certifiable by the exact
// empty-ball test; a triangle cutting through the cube has no empty ball.
#include <catch2/catch.hpp>

#include "verify/checks.h"

using namespace isodel;

namespace {

SurfaceMesh cube(bool flip_diagonals)
{
    SurfaceMesh m;
    for (int n = 0; n < 8; ++n) m.vertices.push_back({double(n & 1), double((n >> 1) & 1), double((n >> 2) & 1)});
    // Faces as quads (outward CCW), split along one diagonal or the other.
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
        if (!flip_diagonals) {
            m.triangles.push_back({q[0], q[1], q[2]});
            m.triangles.push_back({q[0], q[2], q[3]});
        } else {
            m.triangles.push_back({q[0], q[1], q[3]});
            m.triangles.push_back({q[1], q[2], q[3]});
        }
    }
    return m;
}

} // namespace

TEST_CASE("delaunay conformity: cospherical cube corners are judged exactly", "[verify][delaunay]")
{
    for (bool flip : {false, true}) {
        const SurfaceMesh m = cube(flip);
        const DelaunayReport r = verify::delaunay_conformity(m);
        CHECK(r.passed);
        CHECK(r.non_delaunay == 0);
        CHECK(r.dt_facets + r.empty_ball_exact == 12);
    }
    std::vector<int> comp;
    const auto topo = verify::mesh_topology(cube(false), comp);
    CHECK(topo.closed);
    CHECK(topo.manifold);
    CHECK(topo.oriented);
    REQUIRE(topo.components.size() == 1);
    CHECK(topo.components[0].genus == 0);
}

TEST_CASE("delaunay conformity: a triangle with a point strictly inside every ball fails", "[verify][delaunay]")
{
    // Tetrahedron-like fan: triangle (0,1,2) is big, point 3 is near its centre just above it and
    // point 4 just below, so every sphere through 0,1,2 contains 3 or 4.
    SurfaceMesh m;
    m.vertices = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {1, 1, 0.01}, {1, 1, -0.01}};
    m.triangles = {{0, 1, 2}};
    const DelaunayReport r = verify::delaunay_conformity(m);
    CHECK_FALSE(r.passed);
    CHECK(r.non_delaunay == 1);
    // Without point 4 a ball far below the plane is empty.
    m.vertices.pop_back();
    const DelaunayReport r2 = verify::delaunay_conformity(m);
    CHECK(r2.passed);
}
