// The readers' fuzz findings (tests/fuzz/, docs/testing.md), each with the input that found it
// (or the smallest equivalent): every one is now a one-line InvalidInput naming the file, where it
// was an uncaught OpenVDB exception, an allocation the file could not back, or a non-finite
// vertex handed to the verifier's exact predicates.
#include "support/test_files.h"

#include <isodel/errors.h>
#include <isodel/surface_mesh.h>
#include <isodel/volume.h>

#include <catch2/catch.hpp>

#include <cstring>
#include <limits>

using namespace isodel;
using namespace isodel::test;

TEST_CASE("fuzz finding: an MRC voxel too small for OpenVDB's transforms is refused", "[io][fuzz]")
{
    // fuzz_read_mrc: cell lengths giving a 1e-6 voxel; OpenVDB's map threw ArithmeticError
    // ("Non-zero scale values required") out of read_volume.
    TempDir dir;
    MrcSpec s;
    s.voxel = {1e-6f, 1e-6f, 1e-6f};
    const std::string p = dir / "tiny_voxel.mrc";
    write_bytes(p, mrc_bytes(s, [](int i, int, int) { return double(i); }));
    CHECK_THROWS_WITH(read_volume(p), Catch::StartsWith(p) && Catch::Contains("larger units"));
    CHECK_THROWS_AS(read_volume(p), InvalidInput);
}

TEST_CASE("fuzz finding: a Medit count the file cannot hold is refused before allocating", "[io][fuzz]")
{
    // fuzz_read_tet_mesh's input: 214748364710 vertices announced in an 91-byte file.
    TempDir dir;
    const std::string p = dir / "huge_count.mesh";
    write_bytes(p, "MeshVersionFormatted 2\nDimension 3\nVertices\n214748364710 03 4 1\nTetrahedra\n1\n1 2 3 4 1\nEnd\n");
    CHECK_THROWS_WITH(read_tet_mesh(p), Catch::StartsWith(p) && Catch::Contains("more than the file"));
    // A vertex spelled "nan": refused (the stream does not parse it), never handed on.
    const std::string q = dir / "nan_vertex.mesh";
    write_bytes(q, "MeshVersionFormatted 2\nDimension 3\nVertices\n4\nnan 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n"
                   "Tetrahedra\n1\n1 2 3 4 1\nEnd\n");
    CHECK_THROWS_WITH(read_tet_mesh(q), Catch::StartsWith(q));
}

TEST_CASE("fuzz finding: surface meshes with non-finite vertices or impossible counts are refused", "[io][fuzz]")
{
    TempDir dir;
    // fuzz_read_surface_mesh: a binary STL whose coordinates are NaN bit patterns.
    std::string stl(80, ' ');
    const std::uint32_t one = 1;
    stl.append(reinterpret_cast<const char*>(&one), 4);
    const float nan = std::numeric_limits<float>::quiet_NaN(), zero = 0, unit = 1;
    const float facet[12] = {0, 0, 1, nan, 0, 0, unit, 0, 0, zero, unit, 0};
    stl.append(reinterpret_cast<const char*>(facet), sizeof facet);
    stl.append(2, '\0');
    const std::string p = dir / "nan.stl";
    write_bytes(p, stl);
    CHECK_THROWS_WITH(read_surface_mesh(p), Catch::StartsWith(p) && Catch::Contains("non-finite"));
    const std::string o = dir / "inf.obj";
    write_bytes(o, "v inf 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    CHECK_THROWS_WITH(read_surface_mesh(o), Catch::StartsWith(o)); // text "inf": refused as malformed
    // An OFF header announcing more vertices than its bytes can hold.
    const std::string f = dir / "huge.off";
    write_bytes(f, "OFF\n4000000000 1 0\n0 0 0\n");
    CHECK_THROWS_WITH(read_surface_mesh(f), Catch::StartsWith(f) && Catch::Contains("more than the file"));
}
