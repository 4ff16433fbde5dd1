// `isodel mesh --blocks N` (partitioned meshing after the paper's Fig. 8): the blocks
// contribute the refinement, the stats say so, and the merged mesh verifies like the
// unpartitioned one; with tetrahedra too. Adaptive inputs are refused with a one-line error and
// no output file.
#include "support/json.h"
#include "support/test_files.h"

#include <catch2/catch.hpp>

#include <filesystem>

using namespace isodel::test;
using isodel::testing::Json;
using isodel::testing::read_json_file;

TEST_CASE("mesh --blocks: partitioned and unpartitioned meshes both verify", "[cli][partition]")
{
    TempDir tmp;
    const std::string torus = std::string(ISODEL_TEST_DATA) + "/torus.vdb";
    for (const char* blocks : {"0", "9"}) {
        INFO("--blocks " << blocks);
        const std::string out = tmp / (std::string("m") + blocks + ".ply"), stats = tmp / (std::string("s") + blocks + ".json");
        const std::string tets = tmp / (std::string("t") + blocks + ".mesh");
        const RunResult m = run_isodel("mesh " + shell_quote(torus) + " --iso 0 --eps-voxels 0.25 --blocks " + blocks +
                                           " -o " + shell_quote(out) + " --tets " + shell_quote(tets) +
                                           " --threads 2 --quiet --stats " + shell_quote(stats),
                                       tmp.path());
        INFO(m.err);
        REQUIRE(m.status == 0);
        const Json s = read_json_file(stats);
        if (std::string(blocks) != "0") {
            const Json& p = s.at("partition");
            CHECK(p.at("blocks").get<int>() > 1);
            CHECK(p.at("exchange_rounds").get<int>() >= 1);
            CHECK(p.at("block_points").get<long>() > p.at("seam_points").get<long>());
            CHECK(s.at("seconds").at("blocks").get<double>() > 0);
        }
        const RunResult v = run_isodel("verify " + shell_quote(torus) + " --iso 0 --eps-voxels 0.25 --mesh " +
                                           shell_quote(out) + " --tets " + shell_quote(tets),
                                       tmp.path());
        INFO(v.out << v.err);
        CHECK(v.status == 0);
        CHECK(v.out.find("VERIFIED") != std::string::npos);
    }
}

TEST_CASE("mesh --blocks refuses an adaptive grid without writing output", "[cli][partition]")
{
    TempDir tmp;
    const std::string torus = std::string(ISODEL_TEST_DATA) + "/torus.vdb";
    const std::string adaptive = tmp / "torus_k1.vdb", out = tmp / "a.ply";
    REQUIRE(run_isodel("decimate " + shell_quote(torus) + " -o " + shell_quote(adaptive) + " --k 1 --tolerance 0.005",
                       tmp.path())
                .status == 0);
    const RunResult m = run_isodel("mesh " + shell_quote(adaptive) + " --iso 0 --blocks 8 --quiet -o " + shell_quote(out),
                                   tmp.path());
    CHECK(m.status != 0);
    CHECK(m.err.find("dense grids only") != std::string::npos);
    CHECK(!std::filesystem::exists(out));
}
