// `isodel verify` end to end: exit 0 and a JSON report for a correct mesh, exit 1 when a check
// fails (eps too small), exit 2 for a missing mesh file.
#include <catch2/catch.hpp>

#include "support/verify_test_support.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <sys/wait.h>
#include <unistd.h>

using namespace isodel;
namespace fs = std::filesystem;

namespace {

int run(const std::string& args)
{
    const int status = std::system((std::string(ISODEL_CLI) + " " + args + " > /dev/null 2>&1").c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

} // namespace

TEST_CASE("isodel verify: exit codes and JSON report", "[verify][cli]")
{
    const fs::path dir = fs::temp_directory_path() / ("isodel_verify_cli_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const openvdb::Vec3d c(10.3, 10.6, 10.1);
    auto grid = testing::make_grid(22, 0.5, openvdb::Vec3d(1.0, 2.0, 3.0), [&](const openvdb::Vec3d& x) { return testing::sphere_f(x, c, 7.0); });
    grid->setName("density");
    const SurfaceMesh m = testing::star_hull_mesh(*grid, c, 800, 0.004);
    const std::string vdb = (dir / "sphere.vdb").string(), off = (dir / "sphere.off").string(), json = (dir / "r.json").string();
    openvdb::io::File(vdb).write({grid});
    {
        std::ofstream o(off);
        o.precision(17);
        o << "OFF\n" << m.vertices.size() << " " << m.triangles.size() << " 0\n";
        for (const auto& v : m.vertices) o << v[0] << " " << v[1] << " " << v[2] << "\n";
        for (const auto& t : m.triangles) o << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
    }
    CHECK(run("verify " + vdb + " --iso 0 --mesh " + off + " --eps-voxels 0.25 --json " + json) == 0);
    REQUIRE(fs::exists(json));
    const testing::Json report = testing::read_json_file(json);
    CHECK(report.at("passed").get<bool>());
    CHECK(report.at("topology").at("verdict").get<std::string>() == "pass");
    CHECK(report.at("hausdorff").at("mesh_to_surface").at("max_voxels").get<double>() < 0.25);
    CHECK(run("verify " + vdb + " --iso 0 --mesh " + off + " --eps-voxels 0.005") == 1);
    CHECK(run("verify " + vdb + " --iso 0 --mesh " + (dir / "missing.off").string()) == 2);
    fs::remove_all(dir);
}
