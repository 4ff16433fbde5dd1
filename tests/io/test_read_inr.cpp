// INRIMAGE-4 reader: sample types, byte orders (CPU), voxel size, .inr.gz, refusals.
#include "support/test_files.h"

#include <isodel/errors.h>
#include <isodel/volume.h>

#include <catch2/catch.hpp>

#include "support/skip.h"

using namespace isodel;
using namespace isodel::test;

namespace {
double f(int x, int y, int z) { return 3 + x + 5 * y + 17 * z; }

void check(const Volume& vol, std::array<int, 3> d, std::array<double, 3> vox)
{
    REQUIRE(vol.format == "inr");
    REQUIRE(vol.lattice == openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(d[0] - 1, d[1] - 1, d[2] - 1)));
    REQUIRE(vol.grid->activeVoxelCount() == openvdb::Index64(d[0]) * d[1] * d[2]);
    auto acc = vol.grid->getConstAccessor();
    for (auto it = vol.lattice.begin(); it; ++it) {
        INFO("index " << *it);
        REQUIRE(acc.getValue(*it) == float(f((*it).x(), (*it).y(), (*it).z())));
    }
    CHECK(vol.value_min == float(f(0, 0, 0)));
    CHECK(vol.value_max == float(f(d[0] - 1, d[1] - 1, d[2] - 1)));
    for (int a = 0; a < 3; ++a) CHECK(vol.grid->transform().voxelSize()[a] == Approx(vox[a]));
}
} // namespace

TEST_CASE("INR sample types and byte orders", "[inr]")
{
    TempDir dir;
    const std::array<int, 3> d{5, 4, 3};
    const std::array<double, 3> vox{0.5, 0.75, 2.5};
    struct T { const char* type; int bits; };
    for (T t : {T{"float", 32}, T{"float", 64}, T{"unsigned fixed", 8}, T{"unsigned fixed", 16},
                T{"signed fixed", 16}, T{"signed fixed", 32}})
        for (const char* cpu : {"decm", "pc", "sun", "sgi"}) {
            INFO(t.type << " " << t.bits << " bits, CPU=" << cpu);
            const std::string p = dir / "t.inr";
            write_bytes(p, inr_bytes(d, t.type, t.bits, cpu, vox, f));
            check(read_volume(p), d, vox);
        }
}

TEST_CASE("INR .inr.gz reads the same samples as .inr", "[inr]")
{
    TempDir dir;
    const std::array<int, 3> d{6, 3, 4};
    write_bytes(dir / "t.inr", inr_bytes(d, "signed fixed", 16, "sun", {1, 2, 3}, f));
    REQUIRE(std::system(("gzip -c " + shell_quote(dir / "t.inr") + " > " + shell_quote(dir / "t.inr.gz")).c_str()) == 0);
    check(read_volume(dir / "t.inr.gz"), d, {1, 2, 3});
}

TEST_CASE("INR refusals", "[inr][errors]")
{
    TempDir dir;
    const std::string p = dir / "bad.inr";
    auto expect_error = [&](const std::string& bytes, const std::string& what) {
        write_bytes(p, bytes);
        try {
            read_volume(p);
            FAIL("no exception for: " << what);
        } catch (const isodel::Error& e) {
            const std::string msg = e.what();
            INFO(msg);
            CHECK(msg.rfind(p + ": ", 0) == 0);
            CHECK(msg.find(what) != std::string::npos);
        }
    };
    const std::string good = inr_bytes({4, 3, 2}, "float", 32, "decm", {1, 1, 1}, f);
    SECTION("wrong magic") { expect_error("#NOTINR-4#{\n" + good.substr(12), "magic"); }
    SECTION("truncated") { expect_error(good.substr(0, good.size() - 3), "truncated"); }
    SECTION("extra bytes") { expect_error(good + "xxxx", "disagree"); }
    SECTION("non-scalar") { expect_error(inr_bytes({2, 2, 2}, "float", 32, "decm", {1, 1, 1}, f, 3), "VDIM=3"); }
    SECTION("zero voxel size") { expect_error(inr_bytes({2, 2, 2}, "float", 32, "decm", {1, 0, 1}, f), "voxel size"); }
    SECTION("negative voxel size") { expect_error(inr_bytes({2, 2, 2}, "float", 32, "decm", {-1, 1, 1}, f), "voxel size"); }
    SECTION("NaN")
    {
        expect_error(inr_bytes({3, 3, 3}, "float", 32, "decm", {1, 1, 1},
                               [](int i, int j, int k) { return i == 1 && j == 2 && k == 0 ? NAN : 0.0; }),
                     "(1, 2, 0)");
    }
}

TEST_CASE("INR: the shared skull .inr and .mrc hold the same samples", "[inr][shared]")
{
    const std::string inr = std::string(ISODEL_SHARED_DATA) + "/ct/skull_2.9.inr";
    const std::string mrc = std::string(ISODEL_SHARED_DATA) + "/ct/skull_2.9.mrc";
    if (!file_exists(inr) || !file_exists(mrc)) {
        ISODEL_SKIP("../shared/data is absent: skull comparison skipped");
    }
    const Volume a = read_volume(inr), b = read_volume(mrc);
    REQUIRE(a.lattice == b.lattice);
    auto aa = a.grid->getConstAccessor();
    auto bb = b.grid->getConstAccessor();
    std::size_t differ = 0;
    for (auto it = a.lattice.begin(); it; ++it) differ += aa.getValue(*it) != bb.getValue(*it);
    CHECK(differ == 0);
    for (int k = 0; k < 3; ++k)
        CHECK(a.grid->transform().voxelSize()[k] == Approx(b.grid->transform().voxelSize()[k]).epsilon(1e-6));
}
