// Surface mesh writers and readers: every format round-trips (STL to float precision), ASCII PLY
// and polygon faces read, bad extensions refused, no temporary file left behind.
#include "support/test_files.h"

#include <isodel/errors.h>
#include <isodel/surface_mesh.h>

#include <catch2/catch.hpp>

using namespace isodel;
using namespace isodel::test;

namespace {
// An octahedron with coordinates that are not exactly representable in float or in short decimals.
SurfaceMesh octahedron()
{
    SurfaceMesh m;
    const double a = 1.0 / 3.0, b = std::sqrt(2.0), c = -std::acos(-1.0);
    m.vertices = {{a, 0, 0}, {-a, 0, 0}, {0, b, 0}, {0, -b, 0}, {0, 0, c}, {0, 0, -c}};
    m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    return m;
}
} // namespace

TEST_CASE("surface meshes round-trip through every format", "[mesh-io]")
{
    TempDir dir;
    const SurfaceMesh m = octahedron();
    for (std::string ext : {".ply", ".obj", ".off", ".stl"}) {
        INFO(ext);
        const std::string p = dir / ("m" + ext);
        write_surface_mesh(p, m);
        CHECK(list_dir(dir.path()).size() == 1); // only the final file, no temporary
        const SurfaceMesh r = read_surface_mesh(p);
        REQUIRE(r.vertices.size() == m.vertices.size());
        REQUIRE(r.triangles.size() == m.triangles.size());
        // STL stores no indices: the welded vertex order is the order of first appearance, so
        // compare triangles by position; everything else must be identical.
        for (std::size_t t = 0; t < m.triangles.size(); ++t)
            for (int k = 0; k < 3; ++k) {
                const auto& want = m.vertices[m.triangles[t][k]];
                const auto& got = r.vertices[r.triangles[t][k]];
                for (int d = 0; d < 3; ++d) {
                    if (ext == ".stl") CHECK(got[d] == double(float(want[d])));
                    else CHECK(got[d] == want[d]);
                }
            }
        std::remove(p.c_str());
    }
}

TEST_CASE("ASCII PLY with quads and extra properties", "[mesh-io]")
{
    TempDir dir;
    write_bytes(dir / "q.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                               "property float z\nproperty uchar red\nelement face 1\n"
                               "property list uchar int vertex_indices\nend_header\n"
                               "0 0 0 1\n1 0 0 2\n1 1 0 3\n0 1 0 4\n4 0 1 2 3\n");
    const SurfaceMesh r = read_surface_mesh(dir / "q.ply");
    REQUIRE(r.vertices.size() == 4);
    REQUIRE(r.triangles.size() == 2);
    CHECK(r.vertices[2] == std::array<double, 3>{1, 1, 0});
    CHECK(r.triangles[1] == std::array<std::int32_t, 3>{0, 2, 3});
}

TEST_CASE("mesh writer refusals leave nothing behind", "[mesh-io][errors]")
{
    TempDir dir;
    CHECK_THROWS_AS(write_surface_mesh(dir / "m.xyz", octahedron()), InvalidInput);
    SurfaceMesh bad = octahedron();
    bad.triangles.push_back({0, 1, 99});
    CHECK_THROWS_AS(write_surface_mesh(dir / "m.ply", bad), InvalidInput);
    CHECK_THROWS_AS(write_surface_mesh(dir.path() + "/no/such/folder/m.ply", octahedron()), IoError);
    CHECK(list_dir(dir.path()).empty());
}
