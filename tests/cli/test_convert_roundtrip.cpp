// `isodel convert` MRC -> VDB keeps every sample bit-identical, the same lattice and the same
// index-to-world transform, and records the source file.
#include "support/test_files.h"

#include <isodel/volume.h>

#include <catch2/catch.hpp>

#include "support/skip.h"

#include <cstring>

using namespace isodel;
using namespace isodel::test;

namespace {

void check_roundtrip(const std::string& input, const TempDir& out, const TempDir& scratch)
{
    INFO("input " << input);
    const std::string vdb = out / "converted.vdb";
    const RunResult r = run_isodel("convert " + shell_quote(input) + " -o " + shell_quote(vdb), scratch.path());
    INFO("stderr: " << r.err);
    REQUIRE(r.status == 0);
    CHECK(r.err.empty()); // no progress output when stderr is not a terminal
    CHECK(list_dir(out.path()) == std::vector<std::string>{"converted.vdb"});

    const Volume a = read_volume(input), b = read_volume(vdb);
    REQUIRE(a.lattice == b.lattice);
    CHECK(b.grid->activeVoxelCount() == a.grid->activeVoxelCount());
    const auto ma = a.grid->transform().baseMap()->getAffineMap()->getMat4();
    const auto mb = b.grid->transform().baseMap()->getAffineMap()->getMat4();
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) CHECK(ma(i, j) == mb(i, j));
    auto aa = a.grid->getConstAccessor();
    auto bb = b.grid->getConstAccessor();
    std::size_t differ = 0, inactive = 0;
    for (auto it = a.lattice.begin(); it; ++it) {
        const float va = aa.getValue(*it), vb = bb.getValue(*it);
        differ += std::memcmp(&va, &vb, sizeof(float)) != 0;
        inactive += !bb.isValueOn(*it);
    }
    CHECK(differ == 0);
    CHECK(inactive == 0);
    auto src = b.grid->getMetadata<openvdb::StringMetadata>("isodel_source");
    REQUIRE(src);
    CHECK(src->value() == input);
    std::remove(vdb.c_str());
}

} // namespace

TEST_CASE("convert: synthetic MRC with permuted axes and a sheared cell", "[cli][convert]")
{
    TempDir in, out, scratch;
    MrcSpec s;
    s.n = {7, 5, 6};
    s.map = {2, 3, 1};
    s.start = {-4, 3, 11};
    s.angles = {80, 95, 110};
    s.voxel = {0.7f, 1.1f, 0.9f};
    s.mode = 2;
    write_bytes(in / "sheared.mrc", mrc_bytes(s, [](int c, int r, int k) { return std::sin(c * 1.3 + r * 0.7) * k - 0.1; }));
    check_roundtrip(in / "sheared.mrc", out, scratch);
    s.mode = 1;
    s.big_endian = true;
    write_bytes(in / "int16.map", mrc_bytes(s, [](int c, int r, int k) { return c * 100 - r * 7 + k; }));
    check_roundtrip(in / "int16.map", out, scratch);
}

TEST_CASE("convert: bundled sample", "[cli][convert]")
{
    TempDir out, scratch;
    check_roundtrip(std::string(ISODEL_TEST_DATA) + "/two_blobs.mrc", out, scratch);
}

TEST_CASE("convert: every MRC of ../shared/data, emd3001.map included", "[cli][convert][shared]")
{
    if (!shared_data_present()) {
        ISODEL_SKIP("../shared/data is absent: shared MRC round trips skipped");
    }
    TempDir out, scratch;
    const std::string data = ISODEL_SHARED_DATA;
    std::size_t n = 0;
    for (const std::string& dir : {"em", "ct", "protein", "analytic", "cells"})
        for (const std::string& name : list_dir(data + "/" + dir)) {
            if (name.size() < 4) continue;
            const std::string ext = name.substr(name.size() - 4);
            if (ext != ".mrc" && ext != ".map") continue;
            check_roundtrip(data + "/" + dir + "/" + name, out, scratch);
            ++n;
        }
    CHECK(n > 10);
}
