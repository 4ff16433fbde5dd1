// isodel mesh --certify through the real executable: a volume the default crease cut gets wrong
// (property seed 719) is written after a retry, and one no cut of the list gets right (held-out
// seed 28 at eps 0.5) exits 1 with one line naming the file and every attempt, writing nothing.
#include "io/test_files.h"
#include "verify/verify_test_support.h"

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

TEST_CASE("mesh --certify: writes a verified mesh after a retry, or exits 1 and writes nothing", "[cli][certify]")
{
    openvdb::initialize();
    TempDir in, out, scratch;
    const std::string cli = ISODEL_CLI;

    const std::string wrong_by_default = write_random_volume(in, 719);
    const std::string surface = out / "m.ply";
    const std::string stats = out / "m.json";
    RunResult r = run(cli + " mesh " + wrong_by_default + " -o " + surface + " --iso 0 --inside above --certify --quiet --stats " + stats,
                      scratch.path());
    INFO("stderr: " << r.err);
    REQUIRE(r.status == 0);
    const RunResult v = run(cli + " verify " + wrong_by_default + " --iso 0 --inside above --eps-voxels 0.5 --mesh " + surface,
                            scratch.path());
    INFO("verify: " << v.out << v.err);
    CHECK(v.status == 0);
    CHECK(read_text(stats).find("\"certify_attempts\": ") != std::string::npos);
    CHECK(read_text(stats).find("\"certify_attempts\": 1") == std::string::npos);

    TempDir refused_out;
    const std::string out2 = refused_out.path();
    const std::string refused = write_random_volume(in, 28);
    r = run(cli + " mesh " + refused + " -o " + out2 + "/m.ply --iso 0 --inside above --eps-voxels 0.5 --certify --quiet",
            scratch.path());
    INFO("stderr: " << r.err);
    if (r.status == 0) {
        // A later mesher may get this volume right; then the mesh it wrote must verify.
        CHECK(run(cli + " verify " + refused + " --iso 0 --inside above --eps-voxels 0.5 --mesh " + out2 + "/m.ply",
                  scratch.path()).status == 0);
    } else {
        CHECK(r.status == 1);
        CHECK(r.err.rfind("isodel: " + refused + ": certify: ", 0) == 0);
        CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
        CHECK(r.err.find("attempt 5") != std::string::npos);
        CHECK(list_dir(out2).empty());
    }
}
