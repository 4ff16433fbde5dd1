// check_vdb_file_layout's walk of the grids' data (octree/vdb_tree_layout.h): every grid type it
// knows passes as OpenVDB writes it (each compression, half floats, tiles at every level,
// instances, files with and without grid offsets), every cut of a file written as a stream is
// refused, and a chunk whose stated length is not its node's (the overflow in OpenVDB's
// bloscFromStream and unzipFromStream), a count the file cannot hold or a leaf stored away from
// where its parents place it is refused with one line naming it.
#include "octree/vdb_file_layout.h"

#include "support/test_files.h"

#include <isodel/errors.h>
#include <isodel/volume.h>

#include <catch2/catch.hpp>
#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>
#include <openvdb/points/PointDataGrid.h>

#include <cstring>
#include <fstream>

using namespace isodel;
using namespace isodel::test;
using isodel::octree::check_vdb_file_layout;
using openvdb::Coord;

namespace vdb_tree_layout_test {

/// A grid with leaves under two root children (one full leaf, one partly active), inactive
/// values, and tiles at both internal levels and at the root.
template <class GridT>
typename GridT::Ptr varied(const std::string& name, typename GridT::ValueType a, typename GridT::ValueType b)
{
    auto g = GridT::create(b);
    g->setName(name);
    auto& t = g->tree();
    for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j)
            for (int k = 0; k < 8; ++k) t.setValue(Coord(i, j, k), (i + j + k) % 2 ? a : b);
    for (int i = 0; i < 20; ++i) t.setValue(Coord(100 + i, 2 * i, 3 * i), a);
    t.setValueOff(Coord(-5000, 7, 9), a);
    t.addTile(1, Coord(256, 0, 0), a, true);
    t.addTile(2, Coord(0, 2048, 0), b, false);
    t.addTile(3, Coord(0, 0, 8192), a, true);
    return g;
}

openvdb::GridPtrVec every_checked_type()
{
    using V3s = openvdb::Vec3s;
    using V3d = openvdb::Vec3d;
    using V3i = openvdb::Vec3i;
    auto half = varied<openvdb::FloatGrid>("half", 1.5f, -2.0f);
    half->setSaveFloatAsHalf(true);
    auto half_vec = varied<openvdb::Vec3SGrid>("half_vec", V3s(1, 2, 3), V3s(0.5f));
    half_vec->setSaveFloatAsHalf(true);
    auto mask = openvdb::MaskGrid::create();
    mask->setName("mask");
    mask->tree().setValueOn(Coord(9, 10, 11));
    mask->tree().setValueOn(Coord(-3000, 40, 5));
    mask->tree().addTile(2, Coord(0, 4096, 0), true, true);
    return {varied<openvdb::FloatGrid>("float", 1.5f, -2.0f),
            half,
            varied<openvdb::DoubleGrid>("double", 1.25, 3.0),
            varied<openvdb::Int32Grid>("int32", 7, -1),
            varied<openvdb::Int64Grid>("int64", 1LL << 40, 3),
            varied<openvdb::Vec3SGrid>("vec3s", V3s(1, 2, 3), V3s(0.5f)),
            half_vec,
            varied<openvdb::Vec3DGrid>("vec3d", V3d(1, 2, 3), V3d(-1)),
            varied<openvdb::Vec3IGrid>("vec3i", V3i(1, 2, 3), V3i(0)),
            varied<openvdb::BoolGrid>("bool", true, false),
            mask};
}

void write_indexed(const std::string& path, const openvdb::GridPtrVec& grids, std::uint32_t compression)
{
    openvdb::io::File f(path);
    f.setCompression(compression);
    f.write(grids);
    f.close();
}

void write_stream(const std::string& path, const openvdb::GridPtrVec& grids, std::uint32_t compression)
{
    std::ofstream out(path, std::ios::binary);
    openvdb::io::Stream s(out);
    s.setCompression(compression);
    s.write(grids);
}

std::string walk_refusal(const std::string& path)
{
    try {
        check_vdb_file_layout(path);
    } catch (const isodel::InvalidInput& e) {
        return e.what();
    }
    return "(accepted)";
}

template <class T>
T get(const std::string& bytes, std::size_t at)
{
    T v;
    std::memcpy(&v, &bytes[at], sizeof(T));
    return v;
}
template <class T>
std::string with(std::string bytes, std::size_t at, T value)
{
    std::memcpy(&bytes[at], &value, sizeof(T));
    return bytes;
}

/// The descriptor's block offset (where the buffers begin) of the only grid of type \p type.
std::size_t block_pos(const std::string& bytes, const std::string& type)
{
    const std::size_t at = bytes.find(type);
    REQUIRE(at != std::string::npos);
    const std::size_t parent_at = at + type.size();
    REQUIRE(get<std::uint32_t>(bytes, parent_at) == 0); // no instance parent
    return std::size_t(get<std::int64_t>(bytes, parent_at + 4 + 8));
}

const std::uint32_t kCompressions[] = {
    openvdb::io::COMPRESS_NONE, openvdb::io::COMPRESS_ZIP, openvdb::io::COMPRESS_BLOSC,
    openvdb::io::COMPRESS_ZIP | openvdb::io::COMPRESS_ACTIVE_MASK,
    openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK};

} // namespace vdb_tree_layout_test

using namespace vdb_tree_layout_test;

TEST_CASE("VDB tree walk: every checked grid type passes, with and without grid offsets", "[octree][vdb_file_layout]")
{
    openvdb::initialize();
    TempDir dir;
    const auto grids = every_checked_type();
    for (const auto& g : grids) CHECK(isodel::octree::vdb_grid_type_checked(g->type()));
    for (std::uint32_t c : kCompressions) {
        CAPTURE(c);
        write_indexed(dir / "indexed.vdb", grids, c);
        CHECK(walk_refusal(dir / "indexed.vdb") == "(accepted)");
        write_stream(dir / "stream.vdb", grids, c);
        CHECK(walk_refusal(dir / "stream.vdb") == "(accepted)");
    }
    // OpenVDB reads back what was written, tiles included.
    openvdb::io::File f(dir / "indexed.vdb");
    f.open(false);
    auto d = openvdb::gridPtrCast<openvdb::DoubleGrid>(f.readGrid("double"));
    REQUIRE(d);
    CHECK(d->tree().getValue(Coord(1, 0, 0)) == 1.25);
    CHECK(d->tree().getValue(Coord(0, 0, 8192 + 7)) == 1.25);
    CHECK(d->tree().hasSameTopology(openvdb::gridPtrCast<openvdb::DoubleGrid>(grids[2])->tree()));
}

TEST_CASE("VDB tree walk: instances and grid types it does not walk", "[octree][vdb_file_layout]")
{
    openvdb::initialize();
    TempDir dir;
    auto a = openvdb::FloatGrid::create(0.0f);
    a->setName("a");
    for (int i = 0; i < 30; ++i) a->tree().setValue(Coord(i, i % 5, 2), 1.0f);
    auto b = a->copyGrid(); // shares a's tree: written as an instance of a
    b->setName("b");
    write_indexed(dir / "instance.vdb", {a, b}, openvdb::io::COMPRESS_BLOSC);
    const std::string bytes = read_text(dir / "instance.vdb");
    const std::size_t b_at = bytes.find(std::string("\x01\0\0\0b", 5)); // b's descriptor: name, type, parent
    REQUIRE(b_at != std::string::npos);
    const std::size_t parent_at = b_at + 5 + 4 + get<std::uint32_t>(bytes, b_at + 5);
    CHECK(bytes.substr(parent_at, 5) == std::string("\x01\0\0\0a", 5));
    CHECK(walk_refusal(dir / "instance.vdb") == "(accepted)");
    ReadOptions opt;
    opt.grid_name = "b";
    CHECK(read_volume(dir / "instance.vdb", opt).grid->tree().getValue(Coord(1, 1, 2)) == 1.0f);

    // A point grid: not walked, and not read, in a file with grid offsets; refused in a stream,
    // which OpenVDB reads whole.
    auto points = openvdb::points::PointDataGrid::create();
    points->setName("points");
    CHECK_FALSE(isodel::octree::vdb_grid_type_checked(points->type()));
    write_indexed(dir / "points.vdb", {a, points}, openvdb::io::COMPRESS_BLOSC);
    CHECK(walk_refusal(dir / "points.vdb") == "(accepted)");
    CHECK(read_volume(dir / "points.vdb").grid->tree().getValue(Coord(1, 1, 2)) == 1.0f);
    write_stream(dir / "points.vdb", {a, points}, openvdb::io::COMPRESS_BLOSC);
    CHECK(walk_refusal(dir / "points.vdb").find("grid 'points' has type " + points->type() + ", whose data isodel cannot check") !=
          std::string::npos);

    // A float grid named as a point grid before it: File::readGrid(name) would return the point
    // grid (unwalked), so the reader does not choose it.
    auto x = a->deepCopy();
    x->setName("x");
    points->setName("x");
    write_indexed(dir / "shadowed.vdb", {points, x}, openvdb::io::COMPRESS_BLOSC);
    CHECK_THROWS_WITH(read_volume(dir / "shadowed.vdb"), Catch::Contains("which OpenVDB would read in its place"));
    opt.grid_name = "x";
    CHECK_THROWS_WITH(read_volume(dir / "shadowed.vdb", opt), Catch::Contains("is not a scalar grid"));
}

TEST_CASE("VDB tree walk: every cut of a stream-written file is refused", "[octree][vdb_file_layout]")
{
    openvdb::initialize();
    TempDir dir;
    write_stream(dir / "whole.vdb", {varied<openvdb::FloatGrid>("a", 1.0f, 0.0f), varied<openvdb::BoolGrid>("b", true, false)},
                 openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK);
    const std::string bytes = read_text(dir / "whole.vdb");
    REQUIRE(walk_refusal(dir / "whole.vdb") == "(accepted)");
    std::size_t accepted = 0;
    for (std::size_t n = 0; n < bytes.size(); n += 7) {
        CAPTURE(n);
        write_bytes(dir / "cut.vdb", bytes.substr(0, n));
        const std::string r = walk_refusal(dir / "cut.vdb");
        accepted += r == "(accepted)";
        CHECK(r.find('\n') == std::string::npos);
    }
    CHECK(accepted == 0);
}

TEST_CASE("VDB tree walk: chunk lengths, counts and origins the nodes do not have are refused", "[octree][vdb_file_layout]")
{
    openvdb::initialize();
    TempDir dir;
    // One leaf, all 512 voxels active: the buffers hold its mask (64 bytes), a flag byte, then
    // its chunk (an int64 length for Zip and Blosc).
    auto g = openvdb::FloatGrid::create(0.0f);
    g->setName("leaf");
    for (int i = 0; i < 512; ++i) g->tree().setValue(Coord(i >> 6, (i >> 3) & 7, i & 7), float(i % 17));
    const std::string type = openvdb::FloatGrid::gridType();
    const std::string p = dir / "bad.vdb";

    SECTION("an uncompressed Zip chunk longer than the leaf (read before OpenVDB compares)")
    {
        write_indexed(dir / "ok.vdb", {g}, openvdb::io::COMPRESS_BLOSC);
        const std::string bytes = read_text(dir / "ok.vdb");
        write_bytes(p, with<std::int64_t>(bytes, block_pos(bytes, type) + 65, -4096));
        CHECK(walk_refusal(p) == p + ": not a readable OpenVDB file: grid 'leaf': a leaf's values: an uncompressed chunk "
                                "states -4096 bytes, the node holds 2048");
    }
    SECTION("an uncompressed Blosc chunk longer than the leaf")
    {
        write_indexed(dir / "ok.vdb", {g}, openvdb::io::COMPRESS_BLOSC);
        const std::string bytes = read_text(dir / "ok.vdb");
        write_bytes(p, with<std::int64_t>(bytes, block_pos(bytes, type) + 65, -1000000));
        CHECK(walk_refusal(p).find("an uncompressed chunk states -1000000 bytes, the node holds 2048") != std::string::npos);
    }
    SECTION("a Blosc header whose sizes are not the chunk's")
    {
        write_indexed(dir / "ok.vdb", {g}, openvdb::io::COMPRESS_BLOSC);
        const std::string bytes = read_text(dir / "ok.vdb");
        const std::size_t chunk = block_pos(bytes, type) + 65;
        REQUIRE(get<std::int64_t>(bytes, chunk) > 16); // compressed
        REQUIRE(get<std::uint32_t>(bytes, chunk + 8 + 4) == 2048);
        write_bytes(p, with<std::uint32_t>(bytes, chunk + 8 + 4, 4096));
        CHECK(walk_refusal(p).find("compressed and 4096 uncompressed bytes, the node holds 2048") != std::string::npos);
        write_bytes(p, with<std::uint32_t>(bytes, chunk + 8 + 12, 1u << 30));
        CHECK(walk_refusal(p).find("states 1073741824 compressed") != std::string::npos);
    }
    SECTION("the precision is the grid metadata's, as OpenVDB reads it")
    {
        // fuzz_load_adaptive: Grid::readTopology reads the tree at the precision of the grid's
        // "is_saved_as_half_float" metadata, not of the descriptor's type name.
        g->setSaveFloatAsHalf(true);
        write_indexed(dir / "ok.vdb", {g}, openvdb::io::COMPRESS_BLOSC);
        const std::string bytes = read_text(dir / "ok.vdb");
        REQUIRE(walk_refusal(dir / "ok.vdb") == "(accepted)");
        const std::string name = openvdb::GridBase::META_SAVE_HALF_FLOAT;
        const std::size_t value_at = bytes.find(name) + name.size() + 4 + 4 + 4; // type "bool", byte count
        REQUIRE(get<std::uint8_t>(bytes, value_at) == 1);
        write_bytes(p, with<std::uint8_t>(bytes, value_at, 0)); // full floats: 4 bytes a value
        const std::string r = walk_refusal(p);
        CAPTURE(r);
        CHECK(r.find("grid 'leaf': an internal node's values: a Blosc chunk") != std::string::npos);
        CHECK(r.find("65536 uncompressed bytes, the node holds 131072") != std::string::npos);
        write_bytes(p, with<char>(bytes, value_at - 4 - 4, 'B')); // type "Bool": not a bool
        CHECK(walk_refusal(p).find("metadata 'is_saved_as_half_float' is not a bool") != std::string::npos);
    }
    SECTION("a root tile count the file cannot hold")
    {
        write_indexed(dir / "ok.vdb", {g}, openvdb::io::COMPRESS_NONE);
        const std::string bytes = read_text(dir / "ok.vdb");
        const std::string map = g->transform().mapType();
        const std::size_t map_at = bytes.find(map);
        REQUIRE(map_at != std::string::npos);
        const std::size_t tiles_at = map_at + map.size() + 120 + 4 + 4; // map, buffer count, background
        REQUIRE(get<std::uint32_t>(bytes, tiles_at) == 0);
        REQUIRE(get<std::uint32_t>(bytes, tiles_at + 4) == 1);
        write_bytes(p, with<std::uint32_t>(bytes, tiles_at, 0x7FFFFFFFu));
        CHECK(walk_refusal(p).find("grid 'leaf': 2147483647 root tiles cannot fit in the file") != std::string::npos);
    }
    SECTION("a bool that is neither 0 nor 1: a root tile's active flag, a mask tree's tile value")
    {
        // fuzz_read_vdb: OpenVDB loads the byte as a bool (undefined behaviour past 0 and 1).
        auto t = openvdb::FloatGrid::create(0.0f);
        t->setName("tile");
        t->tree().addTile(3, Coord(0), 1.0f, true);
        write_indexed(dir / "ok.vdb", {t}, openvdb::io::COMPRESS_NONE);
        std::string bytes = read_text(dir / "ok.vdb");
        const std::string map = t->transform().mapType();
        const std::size_t tiles_at = bytes.find(map) + map.size() + 120 + 4 + 4;
        REQUIRE(get<std::uint32_t>(bytes, tiles_at) == 1);
        const std::size_t active_at = tiles_at + 8 + 12 + 4; // counts, origin, value
        REQUIRE(get<std::uint8_t>(bytes, active_at) == 1);
        write_bytes(p, with<std::uint8_t>(bytes, active_at, 10));
        CHECK(walk_refusal(p).find("grid 'tile': a root tile's active flag: a bool stored as 10") != std::string::npos);

        auto m = openvdb::MaskGrid::create();
        m->setName("mask");
        m->tree().addTile(2, Coord(0, 128, 0), true, true);
        write_indexed(dir / "ok.vdb", {m}, openvdb::io::COMPRESS_NONE);
        bytes = read_text(dir / "ok.vdb");
        const std::string mask_map = m->transform().mapType();
        // buffer count, background, counts, the child's origin, its two masks, the values' flag
        const std::size_t values_at = bytes.find(mask_map) + mask_map.size() + 120 + 4 + 1 + 8 + 12 + 4096 + 4096 + 1;
        write_bytes(p, with<std::uint8_t>(bytes, values_at + 5, 7));
        CHECK(walk_refusal(p).find("grid 'mask': an internal node's values: a bool stored as 7") != std::string::npos);
        for (std::uint32_t c : kCompressions) { // compressed: decompressed and checked, all pass
            write_indexed(dir / "ok.vdb", {m}, c);
            CHECK(walk_refusal(dir / "ok.vdb") == "(accepted)");
        }
    }
    SECTION("a mask leaf stored at another origin")
    {
        auto m = openvdb::MaskGrid::create();
        m->setName("mask");
        m->tree().setValueOn(Coord(9, 10, 11));
        write_indexed(dir / "ok.vdb", {m}, openvdb::io::COMPRESS_BLOSC);
        const std::string bytes = read_text(dir / "ok.vdb");
        const std::size_t origin_at = block_pos(bytes, openvdb::MaskGrid::gridType()) + 64;
        REQUIRE(get<std::int32_t>(bytes, origin_at) == 8);
        write_bytes(p, with<std::int32_t>(bytes, origin_at, 16));
        CHECK(walk_refusal(p).find("a leaf stores origin (16, 8, 8), its parents place it at (8, 8, 8)") != std::string::npos);
    }
}
