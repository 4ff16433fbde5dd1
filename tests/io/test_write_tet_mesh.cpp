// Tetrahedral mesh writers (src/io/write_tet_mesh.cpp): the ASCII formats print every coordinate
// as printf's %.17g and every index in decimal -- the text iostream gave before the writers
// formatted numbers themselves -- so coordinates round-trip exactly through read_tet_mesh, also
// denormal, huge, negative-zero and non-terminating ones.
#include "support/test_files.h"

#include <isodel/surface_mesh.h>

#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

using namespace isodel;
using namespace isodel::test;

namespace {

std::string g17(double v)
{
    char b[64];
    std::snprintf(b, sizeof b, "%.17g", v);
    return b;
}

std::vector<std::string> lines_of(const std::string& path)
{
    std::ifstream in(path);
    std::vector<std::string> out;
    for (std::string l; std::getline(in, l);) out.push_back(l);
    return out;
}

/// Two tets on awkward coordinates, one per region, and a triangle.
TetMesh awkward()
{
    TetMesh m;
    m.vertices = {{1.0 / 3.0, -0.0, 1e-310},
                  {1e300, -2.5e-8, 123456789.123456789},
                  {0.1, 0.2, 0.30000000000000004},
                  {-std::numeric_limits<double>::max(), std::numeric_limits<double>::min(), 7},
                  {-1.0 / 7.0, 1e17, 2.0 / 3.0}};
    m.triangles = {{0, 1, 2}};
    m.tets = {{0, 1, 2, 3}, {1, 2, 3, 4}};
    m.tet_region = {1, 2};
    return m;
}

} // namespace

TEST_CASE("tet mesh writers: coordinates as %.17g, indices and regions in decimal, exact round trip", "[mesh-io]")
{
    TempDir dir;
    const TetMesh m = awkward();

    const std::string medit = dir / "m.mesh";
    write_tet_mesh(medit, m);
    const std::vector<std::string> lines = lines_of(medit);
    REQUIRE(lines.size() == 17);
    CHECK(lines[0] == "MeshVersionFormatted 2");
    CHECK(lines[2] == "Vertices");
    CHECK(lines[3] == "5");
    for (std::size_t i = 0; i < m.vertices.size(); ++i) {
        const auto& v = m.vertices[i];
        CHECK(lines[4 + i] == g17(v[0]) + " " + g17(v[1]) + " " + g17(v[2]) + " 0");
    }
    CHECK(lines[9] == "Triangles");
    CHECK(lines[11] == "1 2 3 1");
    CHECK(lines[12] == "Tetrahedra");
    CHECK(lines[14] == "1 2 3 4 1");
    CHECK(lines[15] == "2 3 4 5 2");
    CHECK(lines[16] == "End");

    const TetMesh r = read_tet_mesh(medit);
    CHECK(r.vertices == m.vertices);
    CHECK(r.tets == m.tets);
    CHECK(r.tet_region == m.tet_region);
    CHECK(r.triangles == m.triangles);

    // Gmsh: the node coordinates follow the node tags.
    const std::string msh = dir / "m.msh";
    write_tet_mesh(msh, m);
    const std::vector<std::string> g = lines_of(msh);
    std::size_t at = 0;
    while (at < g.size() && g[at] != "$Nodes") ++at;
    REQUIRE(at + 3 + 2 * m.vertices.size() < g.size());
    for (std::size_t i = 0; i < m.vertices.size(); ++i) {
        CHECK(g[at + 3 + i] == std::to_string(i + 1));
        const auto& v = m.vertices[i];
        CHECK(g[at + 3 + m.vertices.size() + i] == g17(v[0]) + " " + g17(v[1]) + " " + g17(v[2]));
    }
    std::size_t el = 0;
    while (el < g.size() && g[el] != "$Elements") ++el;
    REQUIRE(el + 7 < g.size());
    CHECK(g[el + 1] == "3 3 1 3");
    CHECK(g[el + 2] == "2 1 2 1");
    CHECK(g[el + 3] == "1 1 2 3");
    CHECK(g[el + 4] == "3 1 4 1");
    CHECK(g[el + 5] == "2 1 2 3 4");
    CHECK(g[el + 6] == "3 2 4 1");
    CHECK(g[el + 7] == "3 2 3 4 5");
}
