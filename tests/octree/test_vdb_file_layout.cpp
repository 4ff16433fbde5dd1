// check_vdb_file_layout (octree/vdb_file_layout.h): every file OpenVDB writes passes (metadata
// of every registered type, half floats, several grids, isodel's adaptive files, the corpus);
// cuts of a file are refused before OpenVDB reads it; a stated size the file cannot hold (a
// string length, a delayed-load leaf count, a grid offset) is refused with one line naming it.
#include "octree/vdb_file_layout.h"

#include "support/json.h"
#include "support/test_files.h"

#include <isodel/adaptive.h>
#include <isodel/errors.h>
#include <isodel/volume.h>

#include <catch2/catch.hpp>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetSphere.h>

#include <cstring>

using namespace isodel;
using namespace isodel::test;
using isodel::octree::check_vdb_file_layout;

namespace {

openvdb::FloatGrid::Ptr sphere(const std::string& name)
{
    auto g = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(3.0f, openvdb::Vec3f(0), 0.5f);
    g->setName(name);
    return g;
}

void write(const std::string& path, const openvdb::GridPtrVec& grids)
{
    openvdb::io::File f(path);
    f.write(grids);
    f.close();
}

std::string refusal(const std::string& path)
{
    try {
        check_vdb_file_layout(path);
    } catch (const isodel::InvalidInput& e) {
        return e.what();
    }
    return "(accepted)";
}

/// \p bytes with the uint32 at \p at replaced by \p value.
std::string with_u32(std::string bytes, std::size_t at, std::uint32_t value)
{
    std::memcpy(&bytes[at], &value, 4);
    return bytes;
}

std::uint32_t get_u32(const std::string& bytes, std::size_t at)
{
    std::uint32_t v = 0;
    std::memcpy(&v, &bytes[at], 4);
    return v;
}

/// The offset of the uint32 length before the first occurrence of the string \p s.
std::size_t length_of(const std::string& bytes, const std::string& s)
{
    const std::size_t at = bytes.find(s);
    REQUIRE(at != std::string::npos);
    REQUIRE(at >= 4);
    return at - 4;
}

} // namespace

TEST_CASE("VDB layout: files OpenVDB writes pass", "[octree][vdb_file_layout]")
{
    openvdb::initialize();
    TempDir dir;
    auto a = sphere("a");
    a->insertMeta("a_string", openvdb::StringMetadata("text"));
    a->insertMeta("a_bool", openvdb::BoolMetadata(true));
    a->insertMeta("a_int64", openvdb::Int64Metadata(7));
    a->insertMeta("a_vec3d", openvdb::Vec3DMetadata(openvdb::Vec3d(1, 2, 3)));
    a->insertMeta("a_mat4d", openvdb::Mat4DMetadata(openvdb::Mat4d::identity()));
    auto half = sphere("half");
    half->setSaveFloatAsHalf(true);
    auto d = openvdb::DoubleGrid::create(1.0);
    d->setName("double");
    d->tree().setValue(openvdb::Coord(5, 6, 7), 2.0);
    auto empty = openvdb::FloatGrid::create();
    empty->setName("empty");
    openvdb::GridPtrVec grids{a, half, d, empty};
    {
        openvdb::io::File f(dir / "many.vdb");
        openvdb::MetaMap file_meta;
        file_meta.insertMeta("creator", openvdb::StringMetadata("isodel test"));
        file_meta.insertMeta("count", openvdb::Int32Metadata(4));
        f.write(grids, file_meta);
    }
    CHECK(refusal(dir / "many.vdb") == "(accepted)");

    save_adaptive(dir / "adaptive.vdb", uniform_adaptive(sphere("samples"), 1));
    CHECK(refusal(dir / "adaptive.vdb") == "(accepted)");

    if (!shared_data_present()) {
        WARN("skipped: the corpus (../shared/data) is absent");
        return;
    }
    // Every .vdb of the manifest that is not meant to be refused passes.
    int files = 0;
    for (const auto& e : isodel::testing::read_json_file(std::string(ISODEL_SHARED_DATA) + "/manifest.json")) {
        if (isodel::testing::json_string(e, "format") != "vdb" || e.value("expect_error", false)) continue;
        const std::string path = std::string(ISODEL_SHARED_DATA) + "/" + isodel::testing::json_string(e, "file");
        CAPTURE(path);
        CHECK(refusal(path) == "(accepted)");
        ++files;
    }
    CHECK(files > 10);
}

TEST_CASE("VDB layout: cuts of a file are refused", "[octree][vdb_file_layout]")
{
    openvdb::initialize();
    TempDir dir;
    write(dir / "whole.vdb", {sphere("a"), sphere("b")});
    const std::string bytes = read_text(dir / "whole.vdb");
    REQUIRE(refusal(dir / "whole.vdb") == "(accepted)");
    std::size_t accepted = 0;
    // Every cut through the header, the metadata and the descriptors (the first 2 KiB), then
    // one in 61 bytes through the grids' data: all are refused.
    for (std::size_t n = 0; n < bytes.size(); n += n < 2048 ? 1 : 61) {
        CAPTURE(n);
        write_bytes(dir / "cut.vdb", bytes.substr(0, n));
        const std::string r = refusal(dir / "cut.vdb");
        accepted += r == "(accepted)";
        CHECK(r.rfind(dir / "cut.vdb" + ": not a readable OpenVDB file: ", 0) == 0);
        CHECK(r.find('\n') == std::string::npos);
    }
    CHECK(accepted == 0);
    // The reader names the cut, not OpenVDB's failure after an allocation.
    write_bytes(dir / "cut.vdb", bytes.substr(0, bytes.size() / 2));
    try {
        read_volume(dir / "cut.vdb");
        FAIL("a cut file was read");
    } catch (const isodel::InvalidInput& e) {
        CHECK(std::string(e.what()).find("truncated or corrupt") != std::string::npos);
    }
}

TEST_CASE("VDB layout: sizes the file cannot hold are refused", "[octree][vdb_file_layout]")
{
    openvdb::initialize();
    TempDir dir;
    auto g = sphere("grid_name_here");
    g->insertMeta("note", openvdb::StringMetadata("a note"));
    g->insertMeta("scale", openvdb::FloatMetadata(2.0f));
    write(dir / "ok.vdb", {g});
    const std::string bytes = read_text(dir / "ok.vdb");
    const std::string p = dir / "bad.vdb";

    SECTION("a grid name's length")
    {
        write_bytes(p, with_u32(bytes, length_of(bytes, "grid_name_here"), 0xFFFFFFF0u));
        CHECK(refusal(p).find("a grid descriptor needs 4294967280 bytes") != std::string::npos);
    }
    SECTION("a string metadata's length")
    {
        // name, type name "string", then the value's byte count and characters.
        const std::size_t count_at = length_of(bytes, "a note");
        write_bytes(p, with_u32(bytes, count_at, 0x7FFFFFFFu));
        CHECK(refusal(p).find("a grid's metadata needs 2147483647 bytes") != std::string::npos);
    }
    SECTION("a fixed-size metadata's byte count")
    {
        const std::size_t type_at = length_of(bytes, "scale") + 4 + 5; // the type name "float"
        REQUIRE(bytes.substr(type_at + 4, 5) == "float");
        write_bytes(p, with_u32(bytes, type_at + 9, 1000));
        CHECK(refusal(p).find("metadata 'scale' of type float states 1000 bytes, the type has 4") != std::string::npos);
    }
    SECTION("a delayed-load leaf count")
    {
        const std::size_t type_at = length_of(bytes, "__delayedload");
        std::uint32_t stated = 0;
        std::memcpy(&stated, &bytes[type_at + 4 + 13], 4);
        REQUIRE(stated > 0); // OpenVDB's writer fills it
        const std::size_t count_at = type_at + 4 + 13 + 4; // after the type name and the byte count
        write_bytes(p, with_u32(bytes, count_at, 0x7FFFFFFFu));
        CHECK(refusal(p).find("2147483647 leaves cannot fit in the file") != std::string::npos);
    }
    SECTION("a delayed-load array whose Blosc header states more bytes than it holds")
    {
        // fuzz_load_adaptive: Blosc (LZ4) read past the array's buffer, inside MetaMap::readMeta.
        // Enough leaves that OpenVDB compresses the array of their flags.
        auto big = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(40.0f, openvdb::Vec3f(0), 0.5f);
        write(dir / "big.vdb", {big});
        const std::string big_bytes = read_text(dir / "big.vdb");
        const std::size_t array_at = length_of(big_bytes, "__delayedload") + 4 + 13 + 4 + 4;
        const auto stated = get_u32(big_bytes, array_at);
        REQUIRE(stated > 16); // compressed
        write_bytes(p, with_u32(big_bytes, array_at + 4 + 12, stated + 100));
        CHECK(refusal(p).find("a compressed array of " + std::to_string(stated) + " bytes whose header states " +
                              std::to_string(stated + 100)) != std::string::npos);
    }
    SECTION("a grid offset")
    {
        // The descriptor: name, type, instance parent (empty), then grid, block and end offsets.
        const std::size_t type_at = length_of(bytes, "Tree_float_5_4_3");
        std::uint32_t type_length = 0;
        std::memcpy(&type_length, &bytes[type_at], 4);
        const std::size_t parent_at = type_at + 4 + type_length;
        REQUIRE(bytes.substr(parent_at, 4) == std::string(4, '\0'));
        const std::size_t end_at = parent_at + 4 + 16;
        std::string cut = bytes;
        const std::int64_t beyond = std::int64_t(bytes.size()) + 1;
        std::memcpy(&cut[end_at], &beyond, 8);
        write_bytes(p, cut);
        CHECK(refusal(p).find("outside its descriptor's end") != std::string::npos);
    }
    SECTION("the grid count")
    {
        const std::size_t name_at = length_of(bytes, "grid_name_here");
        write_bytes(p, with_u32(bytes, name_at - 4, 0x10000000u));
        CHECK(refusal(p).find("268435456 grids cannot fit in the file") != std::string::npos);
    }
    SECTION("the magic number")
    {
        write_bytes(p, std::string("VDB?") + bytes.substr(4));
        CHECK(refusal(p) == p + ": not a readable OpenVDB file: wrong magic number");
    }
}
