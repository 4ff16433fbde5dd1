// The readers' fuzz findings (tests/fuzz/, docs/testing.md), each with the input that found it
// (or the smallest equivalent): every one is now a one-line InvalidInput naming the file, where it
// was an uncaught OpenVDB exception, an allocation the file could not back, or a non-finite
// vertex handed to the verifier's exact predicates.
#include "support/test_files.h"

#include <isodel/errors.h>
#include <isodel/surface_mesh.h>
#include <isodel/volume.h>

#include <catch2/catch.hpp>
#include <openvdb/openvdb.h>

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

TEST_CASE("fuzz finding: a Medit section given twice is refused", "[io][fuzz]")
{
    // fuzz_read_tet_mesh (30-minute run): a second Vertices section with fewer vertices after the
    // Tetrahedra left tet indices beyond the vertex array the reader returned.
    TempDir dir;
    const std::string p = dir / "vertices_twice.mesh";
    write_bytes(p, "Dimension 3\nVertices\n4\n0 0 0 5\n1 0 0 0\n0 1 0 1\n0 0 1 1\nTetrahedra\n1\n1 2 3 4 1\n"
                   "Vertices\n2\n0 0 0 0\n1 0 0 0\nEnd\n");
    CHECK_THROWS_WITH(read_tet_mesh(p), Catch::StartsWith(p) && Catch::Contains("section Vertices appears twice"));
    CHECK_THROWS_AS(read_tet_mesh(p), InvalidInput);
    const std::string q = dir / "tets_twice.mesh";
    write_bytes(q, "Dimension 3\nVertices\n4\n0 0 0 5\n1 0 0 0\n0 1 0 1\n0 0 1 1\nTetrahedra\n1\n1 2 3 4 1\n"
                   "Tetrahedra\n1\n1 2 4 3 1\nEnd\n");
    CHECK_THROWS_WITH(read_tet_mesh(q), Catch::StartsWith(q) && Catch::Contains("section Tetrahedra appears twice"));
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

TEST_CASE("fuzz finding: PLY and OFF records the file cannot hold are refused before reading them", "[io][fuzz]")
{
    TempDir dir;
    // fuzz_read_surface_mesh: a vertex element without properties and a count of 999999994. Its
    // records took no bytes, so the reader appended a billion vertices (1.6 GB) from a 220-byte
    // file; smaller counts made the slow inputs of the fuzz runs.
    const std::string p = dir / "no_properties.ply";
    write_bytes(p, "ply\nformat binary_little_endian 1.0\nelement vertex 999999994\nend_header\n");
    CHECK_THROWS_WITH(read_surface_mesh(p), Catch::StartsWith(p) && Catch::Contains("no properties"));
    // Records with properties, but more than the bytes after the header.
    const std::string q = dir / "huge_count.ply";
    write_bytes(q, "ply\nformat ascii 1.0\nelement vertex 100000\nproperty float x\nproperty float y\n"
                   "property float z\nend_header\n0 0 0\n");
    CHECK_THROWS_WITH(read_surface_mesh(q), Catch::StartsWith(q) && Catch::Contains("more than the file can hold"));
    // A face list length that no file holds (and a NaN one, which a float count type can spell).
    const std::string r = dir / "long_face.ply";
    write_bytes(r, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                   "element face 1\nproperty list float int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
                   "1e18 0 1 2\n");
    CHECK_THROWS_WITH(read_surface_mesh(r), Catch::StartsWith(r) && Catch::Contains("list length"));
    // fuzz_read_surface_mesh: a face list of float type holding NaN, cast to an index (undefined).
    const std::string n = dir / "nan_index.ply";
    write_bytes(n, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                   "element face 1\nproperty list uchar float vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
                   "3 0 1 1e300\n");
    CHECK_THROWS_WITH(read_surface_mesh(n), Catch::StartsWith(n) && Catch::Contains("list entry out of range"));
    // An OFF face announcing 10^15 vertices: refused before its index vector is allocated.
    const std::string o = dir / "long_face.off";
    write_bytes(o, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n1000000000000000 0 1 2\n");
    CHECK_THROWS_WITH(read_surface_mesh(o), Catch::StartsWith(o) && Catch::Contains("impossible vertex count"));
    // The same files with sensible counts still read.
    const std::string ok = dir / "ok.ply";
    write_bytes(ok, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                    "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
                    "3 0 1 2\n");
    CHECK(read_surface_mesh(ok).triangles.size() == 1);
}

TEST_CASE("fuzz finding: a VDB chunk longer than its node is refused before OpenVDB reads it", "[io][fuzz]")
{
    // fuzz_read_vdb and fuzz_load_adaptive: an internal node's chunk states more uncompressed
    // bytes than the node holds; OpenVDB's bloscFromStream read them into the node's buffer (a
    // heap overflow) before comparing. The tree walk of octree/vdb_tree_layout.h refuses it.
    const std::string p = std::string(ISODEL_TEST_DATA) + "/../fuzz/findings/openvdb_blosc_overflow_read_vdb.vdb";
    CHECK_THROWS_WITH(read_volume(p), Catch::StartsWith(p + ": not a readable OpenVDB file: grid ") &&
                                          Catch::Contains("an uncompressed chunk states"));
    CHECK_THROWS_AS(read_volume(p), InvalidInput);
}

TEST_CASE("fuzz finding: a VDB zip chunk that decompresses short is refused with one line", "[io][fuzz]")
{
    // fuzz_read_vdb: the file's layout is sound, but a zip chunk inflates to fewer bytes than its
    // node needs; OpenVDB throws from inside its tree reader (and leaks the nodes it had
    // allocated, suppressed in cmake/lsan_suppressions.txt). The reader names the file.
    const std::string p = std::string(ISODEL_TEST_DATA) + "/../fuzz/findings/openvdb_zip_short_chunk_leak_read_vdb.vdb";
    CHECK_THROWS_WITH(read_volume(p), Catch::StartsWith(p + ": ") && Catch::Contains("decompress"));
    CHECK_THROWS_AS(read_volume(p), InvalidInput);
}

TEST_CASE("fuzz finding: a VDB transform with a negative voxel size is refused", "[io][fuzz]")
{
    // fuzz_read_vdb: a ScaleMap stores its voxel size beside its scale, and OpenVDB reads both as
    // they are; a negative one reached the mesher's world coordinates.
    openvdb::initialize();
    TempDir dir;
    auto g = openvdb::FloatGrid::create(1.0f);
    g->setName("s");
    for (int i = 0; i < 4; ++i) g->tree().setValue(openvdb::Coord(i, 0, 0), float(i));
    g->setTransform(openvdb::math::Transform::createLinearTransform(openvdb::math::scale<openvdb::Mat4d>(openvdb::Vec3d(2, 3, 4))));
    const std::string ok = dir / "ok.vdb";
    openvdb::io::File(ok).write({g});
    std::string bytes = read_text(ok);
    const std::string map("\x08\0\0\0ScaleMap", 12);
    const std::size_t at = bytes.find(map);
    REQUIRE(at != std::string::npos);
    double voxel = 0;
    std::memcpy(&voxel, &bytes[at + map.size() + 24], 8); // after the scale: the voxel size
    REQUIRE(voxel == 2.0);
    voxel = -2.0;
    std::memcpy(&bytes[at + map.size() + 24], &voxel, 8);
    const std::string p = dir / "negative_voxel.vdb";
    write_bytes(p, bytes);
    CHECK(read_volume(ok).value_max == 3.0f);
    CHECK_THROWS_WITH(read_volume(p), Catch::StartsWith(p + ": ") && Catch::Contains("voxel -2"));
    CHECK_THROWS_AS(read_volume(p), InvalidInput);
}
