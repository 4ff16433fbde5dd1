// MRC2014 / CCP4 reader: modes, byte orders, axis permutation, start indices, origin, sheared
// cells, extended header, and the refusals. Files are written byte by byte from the spec.
#include "support/test_files.h"

#include <isodel/errors.h>
#include <isodel/volume.h>

#include <catch2/catch.hpp>

#include "support/skip.h"

using namespace isodel;
using namespace isodel::test;

namespace {
// A value that differs at every lattice point, so a wrong axis order cannot go unnoticed.
double f_xyz(int x, int y, int z) { return x + 7 * y + 31 * z; }

void check_samples(const Volume& vol, std::array<int, 3> dims, const std::function<double(int, int, int)>& f)
{
    REQUIRE(vol.lattice.min() == openvdb::Coord(0, 0, 0));
    REQUIRE(vol.lattice.dim() == openvdb::Coord(dims[0], dims[1], dims[2]));
    REQUIRE(vol.grid->activeVoxelCount() == openvdb::Index64(dims[0]) * dims[1] * dims[2]);
    auto acc = vol.grid->getConstAccessor();
    double lo = 1e300, hi = -1e300;
    for (int z = 0; z < dims[2]; ++z)
        for (int y = 0; y < dims[1]; ++y)
            for (int x = 0; x < dims[0]; ++x) {
                const openvdb::Coord c(x, y, z);
                INFO("index " << c);
                REQUIRE(acc.isValueOn(c));
                REQUIRE(acc.getValue(c) == float(f(x, y, z)));
                lo = std::min(lo, f(x, y, z));
                hi = std::max(hi, f(x, y, z));
            }
    CHECK(vol.value_min == float(lo));
    CHECK(vol.value_max == float(hi));
}

Volume write_and_read(const TempDir& dir, const MrcSpec& spec, const std::function<double(int, int, int)>& f_file,
                      const std::string& name = "t.mrc")
{
    write_bytes(dir / name, mrc_bytes(spec, f_file));
    return read_volume(dir / name);
}
} // namespace

TEST_CASE("MRC modes 0, 1, 2, 6 in both byte orders", "[mrc]")
{
    TempDir dir;
    for (int mode : {0, 1, 2, 6})
        for (bool big : {false, true})
            for (bool stamp : {true, false}) {
                INFO("mode " << mode << (big ? " big" : " little") << "-endian, stamp " << stamp);
                MrcSpec s;
                s.n = {5, 4, 3};
                s.mode = mode;
                s.big_endian = big;
                s.stamp = stamp; // without a stamp the reader must infer the order from the dims
                // mode 0 is int8: keep values in range; mode 1 gets negatives too.
                auto f = [mode](int x, int y, int z) { return f_xyz(x, y, z) - (mode == 1 ? 40 : 0); };
                const Volume vol = write_and_read(dir, s, f);
                CHECK(vol.format == "mrc");
                check_samples(vol, {5, 4, 3}, f);
            }
}

TEST_CASE("MRC voxel size from cell/MX and the origin field", "[mrc]")
{
    TempDir dir;
    MrcSpec s;
    s.n = {6, 5, 4};
    s.voxel = {0.5f, 1.25f, 2.0f};
    s.origin = {10.f, -3.f, 0.25f};
    const Volume vol = write_and_read(dir, s, f_xyz);
    check_samples(vol, {6, 5, 4}, f_xyz);
    const auto& xf = vol.grid->transform();
    CHECK(xf.voxelSize().x() == Approx(0.5));
    CHECK(xf.voxelSize().y() == Approx(1.25));
    CHECK(xf.voxelSize().z() == Approx(2.0));
    const auto w = xf.indexToWorld(openvdb::Vec3d(2, 3, 1));
    CHECK(w.x() == Approx(10 + 2 * 0.5));
    CHECK(w.y() == Approx(-3 + 3 * 1.25));
    CHECK(w.z() == Approx(0.25 + 1 * 2.0));
}

TEST_CASE("MRC axis permutation MAPC/MAPR/MAPS and start indices", "[mrc]")
{
    TempDir dir;
    MrcSpec s;
    s.map = {3, 1, 2};    // columns run along z, rows along x, sections along y
    s.n = {6, 4, 5};      // so the lattice is x=4, y=5, z=6
    s.start = {2, -3, 7}; // start along z, x, y
    s.voxel = {1.0f, 0.5f, 2.0f};
    // The file stores (c, r, s) = (z, x, y).
    const Volume vol = write_and_read(dir, s, [](int c, int r, int sec) { return f_xyz(r, sec, c); });
    check_samples(vol, {4, 5, 6}, f_xyz);
    // No origin field: sample (0,0,0) sits at the start indices on the cell lattice.
    const auto w = vol.grid->transform().indexToWorld(openvdb::Vec3d(0, 0, 0));
    CHECK(w.x() == Approx(-3 * 1.0));
    CHECK(w.y() == Approx(7 * 0.5));
    CHECK(w.z() == Approx(2 * 2.0));
}

TEST_CASE("MRC non-orthogonal cell gives a sheared transform; NSYMBT is skipped", "[mrc]")
{
    TempDir dir;
    MrcSpec s;
    s.n = {3, 3, 3};
    s.m = {3, 3, 3};
    s.cell = {3.f, 6.f, 9.f};
    s.angles = {90.f, 100.f, 90.f};
    s.nsymbt = 160;
    const Volume vol = write_and_read(dir, s, f_xyz);
    check_samples(vol, {3, 3, 3}, f_xyz);
    const double beta = 100.0 * 3.14159265358979323846 / 180.0;
    const auto c = vol.grid->transform().indexToWorld(openvdb::Vec3d(0, 0, 1));
    CHECK(c.x() == Approx(3.0 * std::cos(beta)));
    CHECK(c.y() == Approx(0.0).margin(1e-12));
    CHECK(c.z() == Approx(3.0 * std::sin(beta)));
    const auto a = vol.grid->transform().indexToWorld(openvdb::Vec3d(1, 0, 0));
    CHECK(a.x() == Approx(1.0));
}

TEST_CASE("MRC refusals name the file and the problem", "[mrc][errors]")
{
    TempDir dir;
    const std::string p = dir / "bad.mrc";
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
    MrcSpec s;
    SECTION("wrong magic")
    {
        s.magic = "XYZ ";
        expect_error(mrc_bytes(s, f_xyz), "magic");
    }
    SECTION("truncated data")
    {
        std::string b = mrc_bytes(s, f_xyz);
        b.resize(b.size() - 5);
        expect_error(b, std::to_string(b.size()));
    }
    SECTION("file larger than the header says")
    {
        expect_error(mrc_bytes(s, f_xyz) + std::string(12, '\0'), "disagree");
    }
    SECTION("absurd dims are refused before allocating")
    {
        s.n = {100000, 100000, 100000};
        MrcSpec small;
        std::string b = mrc_bytes(small, f_xyz);
        std::memcpy(&b[0], &s.n[0], 12); // header dims only; the data stays tiny
        expect_error(b, "limit");
    }
    SECTION("zero voxel size")
    {
        s.cell = {0.f, 1.f, 1.f};
        s.voxel = {0.f, 1.f, 1.f};
        expect_error(mrc_bytes(s, f_xyz), "voxel size");
    }
    SECTION("negative voxel size")
    {
        s.cell = {4.f, -3.f, 2.f};
        expect_error(mrc_bytes(s, f_xyz), "voxel size");
    }
    SECTION("NaN sample names its index")
    {
        expect_error(mrc_bytes(s, [](int i, int j, int k) { return i == 2 && j == 1 && k == 1 ? NAN : 1.0; }),
                     "NaN sample at index (i,j,k) = (2, 1, 1)");
    }
    SECTION("Inf sample names its index")
    {
        expect_error(mrc_bytes(s, [](int i, int j, int k) { return i == 3 && j == 0 && k == 1 ? INFINITY : 1.0; }),
                     "Inf sample at index (i,j,k) = (3, 0, 1)");
    }
    SECTION("unsupported mode")
    {
        s.mode = 2;
        std::string b = mrc_bytes(s, f_xyz);
        const std::int32_t mode = 4;
        std::memcpy(&b[12], &mode, 4);
        expect_error(b, "mode 4");
    }
}

TEST_CASE("emd3001.map (legacy CCP4: permuted axes, start indices, monoclinic cell) matches its .vdb copy", "[mrc][shared]")
{
    const std::string map = std::string(ISODEL_SHARED_DATA) + "/em/emd3001.map";
    const std::string vdb = std::string(ISODEL_SHARED_DATA) + "/em/emd3001.vdb";
    if (!file_exists(map) || !file_exists(vdb)) {
        ISODEL_SKIP("../shared/data is absent: emd3001 comparison skipped");
    }
    const Volume a = read_volume(map), b = read_volume(vdb);
    REQUIRE(a.lattice == b.lattice);
    const auto ma = a.grid->transform().baseMap()->getAffineMap()->getMat4();
    const auto mb = b.grid->transform().baseMap()->getAffineMap()->getMat4();
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) CHECK(ma(r, c) == Approx(mb(r, c)).margin(1e-9));
    auto acc_a = a.grid->getConstAccessor();
    auto acc_b = b.grid->getConstAccessor();
    std::size_t differ = 0;
    for (auto it = a.lattice.begin(); it; ++it)
        if (acc_a.getValue(*it) != acc_b.getValue(*it)) ++differ;
    CHECK(differ == 0);
    CHECK(a.value_min == b.value_min);
    CHECK(a.value_max == b.value_max);
}
