// isodel mesh --certify through the real executable: a volume is written after it verifies
// (property seed 719, which the crease cut before the face slabs got wrong), and a run stopped
// by a bound exits 1 with one line naming the file and the bound, writing nothing.
#include "support/test_files.h"
#include "support/verify_test_support.h"

#include <catch2/catch.hpp>
#include <openvdb/openvdb.h>

#include <algorithm>

using namespace isodel::test;

namespace {

std::string write_random_volume(const TempDir& dir, unsigned seed)
{
    auto g = isodel::testing::random_volume(5, seed, false);
    g->setName("density");
    const std::string path = dir / ("random_" + std::to_string(seed) + ".vdb");
    openvdb::io::File file(path);
    file.write({g});
    file.close();
    return path;
}

} // namespace

TEST_CASE("mesh --certify: writes a verified mesh, or exits 1 and writes nothing", "[cli][certify]")
{
    openvdb::initialize();
    TempDir in, out, scratch;
    const std::string cli = ISODEL_CLI;

    const std::string volume = write_random_volume(in, 719);
    const std::string surface = out / "m.ply";
    const std::string stats = out / "m.json";
    RunResult r = run(cli + " mesh " + volume + " -o " + surface + " --iso 0 --inside above --certify --quiet --stats " + stats,
                      scratch.path());
    INFO("stderr: " << r.err);
    REQUIRE(r.status == 0);
    const RunResult v = run(cli + " verify " + volume + " --iso 0 --inside above --eps-voxels 0.5 --mesh " + surface,
                            scratch.path());
    INFO("verify: " << v.out << v.err);
    CHECK(v.status == 0);
    CHECK(read_text(stats).find("\"certify_attempts\": 1") != std::string::npos);

    TempDir refused_out;
    const std::string out2 = refused_out.path();
    r = run(cli + " mesh " + volume + " -o " + out2 + "/m.ply --iso 0 --inside above --certify --max-points 1 --quiet",
            scratch.path());
    INFO("stderr: " << r.err);
    CHECK(r.status == 1);
    CHECK(r.err.rfind("isodel: " + volume + ": ", 0) == 0);
    CHECK(r.err.find("point bound") != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(list_dir(out2).empty());
}
