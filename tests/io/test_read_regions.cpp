// ReadOptions::regions (include/isodel/volume.h): a dense file read box by box holds exactly the
// samples of the boxes, each equal to the whole read's, with the whole file's lattice; an empty
// list reads the header alone; a .vdb is delay-loaded (Volume::partial).
#include "support/test_files.h"

#include <isodel/errors.h>
#include <isodel/volume.h>

#include <catch2/catch.hpp>

#include <cmath>

#include <openvdb/openvdb.h>

using namespace isodel;
using namespace isodel::test;

namespace {

double sample_value(int x, int y, int z) { return x + 7 * y + 31 * z; }

/// \p part holds the samples of \p boxes (clipped to the lattice), each as \p whole has it, and
/// no other sample.
void check_part(const Volume& whole, const Volume& part, const std::vector<openvdb::CoordBBox>& boxes)
{
    CHECK(part.partial);
    CHECK(part.lattice == whole.lattice);
    CHECK(part.grid->transform() == whole.grid->transform());
    auto w = whole.grid->getConstAccessor();
    auto p = part.grid->getConstAccessor();
    std::uint64_t expected = 0;
    const openvdb::CoordBBox& L = whole.lattice;
    for (auto c = L.beginXYZ(); c; ++c) {
        bool in = false;
        for (const auto& b : boxes) in = in || b.isInside(*c);
        INFO("sample " << *c);
        REQUIRE(p.isValueOn(*c) == in);
        if (in) {
            ++expected;
            REQUIRE(p.getValue(*c) == w.getValue(*c));
        }
    }
    CHECK(part.grid->activeVoxelCount() == expected);
}

} // namespace

TEST_CASE("an MRC file read by boxes holds exactly their samples, with permuted axes and swapped bytes", "[io][mrc]")
{
    TempDir dir;
    for (const bool big : {false, true})
        for (const auto& map : {std::array<int, 3>{1, 2, 3}, std::array<int, 3>{3, 1, 2}}) {
            INFO("big endian " << big << ", map " << map[0] << map[1] << map[2]);
            MrcSpec s;
            s.n = {9, 6, 5};
            s.map = map;
            s.big_endian = big;
            s.nsymbt = 80;
            // Samples by lattice index whatever the file order.
            std::array<int, 3> axis{};
            for (int f = 0; f < 3; ++f) axis[f] = map[f] - 1;
            const std::string path = dir / "v.mrc";
            write_bytes(path, mrc_bytes(s, [&](int c, int r, int q) {
                            std::array<int, 3> xyz{};
                            xyz[axis[0]] = c, xyz[axis[1]] = r, xyz[axis[2]] = q;
                            return sample_value(xyz[0], xyz[1], xyz[2]);
                        }));
            const Volume whole = read_volume(path);
            CHECK_FALSE(whole.partial);
            const std::vector<openvdb::CoordBBox> boxes{
                openvdb::CoordBBox(openvdb::Coord(1, 2, 0), openvdb::Coord(3, 4, 1)),
                openvdb::CoordBBox(openvdb::Coord(2, 3, 1), openvdb::Coord(40, 40, 40)), // overlaps, leaves the lattice
                openvdb::CoordBBox(openvdb::Coord(-5, -5, -5), openvdb::Coord(-1, -1, -1))}; // misses it
            ReadOptions opt;
            opt.regions = boxes;
            const Volume part = read_volume(path, opt);
            check_part(whole, part, boxes);
            opt.regions = std::vector<openvdb::CoordBBox>{};
            const Volume head = read_volume(path, opt);
            CHECK(head.partial);
            CHECK(head.lattice == whole.lattice);
            CHECK(head.grid->activeVoxelCount() == 0);
        }
}

TEST_CASE("a raw volume read by boxes holds exactly their samples; a .vdb loads the leaves read", "[io][raw]")
{
    TempDir dir;
    const std::string path = dir / "v.raw";
    std::string bytes;
    for (int z = 0; z < 4; ++z)
        for (int y = 0; y < 5; ++y)
            for (int x = 0; x < 6; ++x) append<std::uint16_t>(bytes, std::uint16_t(sample_value(x, y, z)));
    write_bytes(path, bytes);
    ReadOptions opt;
    opt.raw = RawLayout{{6, 5, 4}, "uint16", 0.5};
    const Volume whole = read_volume(path, opt);
    const std::vector<openvdb::CoordBBox> boxes{openvdb::CoordBBox(openvdb::Coord(0, 1, 2), openvdb::Coord(5, 2, 3))};
    opt.regions = boxes;
    check_part(whole, read_volume(path, opt), boxes);

    // A float .vdb is delay-loaded: its topology, and the values of the leaves read.
    openvdb::initialize();
    const std::string vdb = dir / "v.vdb";
    write_vdb(vdb, {whole.grid});
    ReadOptions vo;
    vo.regions = boxes;
    const Volume v = read_volume(vdb, vo);
    CHECK(v.partial);
    CHECK(v.lattice == whole.lattice);
    CHECK(v.samples_read == 512); // the one leaf meeting the box
    auto a = v.grid->getConstAccessor();
    auto b = whole.grid->getConstAccessor();
    for (auto c = boxes[0].beginXYZ(); c; ++c) REQUIRE(a.getValue(*c) == b.getValue(*c));
}

TEST_CASE("a box of a file with a non-finite sample is refused when it holds the sample, naming it", "[io][mrc]")
{
    TempDir dir;
    MrcSpec s;
    s.n = {4, 4, 4};
    const std::string path = dir / "nan.mrc";
    write_bytes(path, mrc_bytes(s, [](int c, int r, int q) { return c == 3 && r == 3 && q == 3 ? NAN : 1.0; }));
    ReadOptions opt;
    opt.regions = std::vector<openvdb::CoordBBox>{openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(1))};
    CHECK(read_volume(path, opt).grid->activeVoxelCount() == 8);
    opt.regions = std::vector<openvdb::CoordBBox>{openvdb::CoordBBox(openvdb::Coord(2), openvdb::Coord(3))};
    try {
        read_volume(path, opt);
        FAIL("expected InvalidInput");
    } catch (const InvalidInput& e) {
        const std::string what = e.what();
        CHECK(what.find(path) == 0);
        CHECK(what.find("NaN sample at index (i,j,k) = (3, 3, 3)") != std::string::npos);
    }
}
