// Raw volumes: layout from the options, little-endian, x fastest; size must match exactly.
#include "support/test_files.h"

#include <isodel/errors.h>
#include <isodel/volume.h>

#include <catch2/catch.hpp>

using namespace isodel;
using namespace isodel::test;

namespace {
double raw_sample(int x, int y, int z) { return 1 + x + 3 * y + 11 * z; }

std::string raw_bytes(std::array<int, 3> d, const std::string& type)
{
    std::string s;
    for (int z = 0; z < d[2]; ++z)
        for (int y = 0; y < d[1]; ++y)
            for (int x = 0; x < d[0]; ++x) {
                const double v = raw_sample(x, y, z);
                if (type == "float32") append<float>(s, float(v) + 0.25f);
                else if (type == "uint8") append<std::uint8_t>(s, std::uint8_t(v));
                else if (type == "uint16") append<std::uint16_t>(s, std::uint16_t(v * 300));
                else append<std::int16_t>(s, std::int16_t(-v * 100));
            }
    return s;
}

double expected(const std::string& type, int x, int y, int z)
{
    const double v = raw_sample(x, y, z);
    if (type == "float32") return v + 0.25;
    if (type == "uint8") return v;
    if (type == "uint16") return v * 300;
    return -v * 100;
}
} // namespace

TEST_CASE("raw volumes of every sample type", "[raw]")
{
    TempDir dir;
    const std::array<int, 3> d{4, 5, 3};
    for (std::string type : {"float32", "uint8", "uint16", "int16"}) {
        INFO(type);
        const std::string p = dir / "v.raw";
        write_bytes(p, raw_bytes(d, type));
        ReadOptions opt;
        opt.raw = RawLayout{d, type, 0.3};
        const Volume vol = read_volume(p, opt);
        CHECK(vol.format == "raw");
        REQUIRE(vol.lattice.dim() == openvdb::Coord(4, 5, 3));
        REQUIRE(vol.grid->activeVoxelCount() == 60);
        auto acc = vol.grid->getConstAccessor();
        for (auto it = vol.lattice.begin(); it; ++it)
            REQUIRE(acc.getValue(*it) == float(expected(type, (*it).x(), (*it).y(), (*it).z())));
        CHECK(vol.grid->transform().voxelSize().x() == Approx(0.3));
    }
}

TEST_CASE("raw volume refusals", "[raw][errors]")
{
    TempDir dir;
    const std::string p = dir / "v.bin";
    write_bytes(p, raw_bytes({4, 4, 4}, "float32"));
    auto expect_error = [&](const ReadOptions& opt, const std::string& what) {
        try {
            read_volume(p, opt);
            FAIL("no exception for: " << what);
        } catch (const isodel::Error& e) {
            const std::string msg = e.what();
            INFO(msg);
            CHECK(msg.rfind(p + ": ", 0) == 0);
            CHECK(msg.find(what) != std::string::npos);
        }
    };
    ReadOptions opt;
    SECTION("unknown extension without a raw layout") { expect_error(opt, "unknown extension '.bin'"); }
    SECTION("dims larger than the file") { opt.raw = RawLayout{{4, 4, 5}, "float32", 1}; expect_error(opt, "truncated"); }
    SECTION("dims smaller than the file") { opt.raw = RawLayout{{4, 4, 3}, "float32", 1}; expect_error(opt, "256"); }
    SECTION("zero spacing") { opt.raw = RawLayout{{4, 4, 4}, "float32", 0}; expect_error(opt, "voxel size"); }
    SECTION("negative dims") { opt.raw = RawLayout{{4, -4, 4}, "float32", 1}; expect_error(opt, "dimensions"); }
    SECTION("voxel cap")
    {
        opt.raw = RawLayout{{4, 4, 4}, "float32", 1};
        opt.max_voxels = 63;
        expect_error(opt, "limit of 63");
    }
}

TEST_CASE("a missing file is an IoError naming it", "[errors]")
{
    TempDir dir;
    const std::string p = dir / "nothing.mrc";
    try {
        read_volume(p);
        FAIL("no exception");
    } catch (const isodel::IoError& e) {
        CHECK(std::string(e.what()).rfind(p + ": cannot open", 0) == 0);
    }
}
