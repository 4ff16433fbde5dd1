// `isodel decimate` then `isodel mesh` (paper Property IV; the users' "adaptive decimation
// then meshing"): an adaptive file is meshed on its leaves -- the stats report the leaf voxel
// bound 3k+1 and fewer E and G points and tetrahedra than meshing its dense resampling -- and
// `isodel verify` certifies surface and tetrahedra against the adaptive interpolant.
#include "support/json.h"
#include "support/test_files.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>

using namespace isodel::test;
using isodel::testing::Json;
using isodel::testing::read_json_file;

TEST_CASE("decimate then mesh: the adaptive file is meshed on its leaves and verifies", "[cli][adaptive]")
{
    TempDir tmp;
    const std::string torus = std::string(ISODEL_TEST_DATA) + "/torus.vdb";
    const std::string adaptive = tmp / "torus_k2.vdb", dense = tmp / "torus_dense.vdb";
    RunResult r = run_isodel("decimate " + shell_quote(torus) + " -o " + shell_quote(adaptive) +
                                 " --k 2 --tolerance 0.005",
                             tmp.path());
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    REQUIRE(run_isodel("resample " + shell_quote(adaptive) + " -o " + shell_quote(dense), tmp.path()).status == 0);

    auto mesh = [&](const std::string& in, const std::string& tag, const std::string& extra = "") {
        const std::string stats = tmp / (tag + ".json");
        const RunResult m = run_isodel("mesh " + shell_quote(in) + " --iso 0 -o " + shell_quote(tmp / (tag + ".ply")) +
                                           " --tets " + shell_quote(tmp / (tag + ".mesh")) +
                                           " --region both --quiet --stats " + shell_quote(stats) + extra,
                                       tmp.path());
        INFO(m.err);
        REQUIRE(m.status == 0);
        return read_json_file(stats);
    };
    // The dense file with every sample as G' (--uniform-tets): the leaf corners are far fewer.
    const Json a = mesh(adaptive, "adaptive"), d = mesh(dense, "dense", " --uniform-tets");
    const Json& vb = a.at("voxel_bound");
    CHECK(vb.at("bound_E").get<int>() == 7); // 3k + 1
    CHECK(vb.at("max_cells_E").get<int>() <= vb.at("bound_E").get<int>());
    CHECK(vb.at("max_cells_N").get<int>() <= vb.at("bound_N").get<int>());
    CHECK(d.at("voxel_bound").at("bound_E").get<int>() == 4);
    INFO("E " << a.at("counts").at("E").get<double>() << " vs " << d.at("counts").at("E").get<double>());
    CHECK(a.at("counts").at("E").get<double>() < 0.5 * d.at("counts").at("E").get<double>());
    CHECK(a.at("counts").at("G").get<double>() < 0.5 * d.at("counts").at("G").get<double>());
    auto tets = [](const Json& s) {
        return s.at("tets").at("tets_inside").get<double>() + s.at("tets").at("tets_outside").get<double>();
    };
    const double tets_a = tets(a), tets_d = tets(d);
    CHECK(tets_a < 0.5 * tets_d);

    const RunResult v = run_isodel("verify " + shell_quote(adaptive) + " --iso 0 --eps-voxels 0.5 --mesh " +
                                       shell_quote(tmp / "adaptive.ply") + " --tets " + shell_quote(tmp / "adaptive.mesh"),
                                   tmp.path());
    INFO(v.out << v.err);
    CHECK(v.status == 0);
    CHECK(v.out.find("VERIFIED") != std::string::npos);
}

TEST_CASE("mesh --adaptive: certified against the input, stats report the eps split", "[cli][adaptive]")
{
    TempDir tmp;
    const std::string torus = std::string(ISODEL_TEST_DATA) + "/torus.vdb";
    const std::string out = tmp / "m.ply", stats = tmp / "m.json";
    const RunResult r = run_isodel("mesh " + shell_quote(torus) + " --iso 0 --adaptive --certify --quiet -o " +
                                       shell_quote(out) + " --stats " + shell_quote(stats),
                                   tmp.path());
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    const Json s = read_json_file(stats);
    const Json& a = s.at("adaptive");
    CHECK(a.at("distance_world").get<double>() <= a.at("eps_coarsening_world").get<double>());
    CHECK(a.at("eps_meshing_world").get<double>() ==
          Approx(s.at("eps_world").get<double>() - a.at("distance_world").get<double>()));
    CHECK(a.at("leaves_per_level").size() >= 2);
    CHECK(s.at("certify_attempts").get<int>() == 1);
    // An independent run of isodel verify against the input agrees.
    const RunResult v = run_isodel("verify " + shell_quote(torus) + " --iso 0 --eps-voxels 0.5 --mesh " + shell_quote(out),
                                   tmp.path());
    INFO(v.out << v.err);
    CHECK(v.status == 0);
}

TEST_CASE("mesh --adaptive --adaptive-field input: the whole eps to the mesher, verified against the input",
          "[cli][adaptive]")
{
    TempDir tmp;
    const std::string torus = std::string(ISODEL_TEST_DATA) + "/torus.vdb";
    const std::string out = tmp / "m.ply", stats = tmp / "m.json";
    const RunResult r = run_isodel("mesh " + shell_quote(torus) + " --iso 0 --adaptive --adaptive-field input "
                                       "--adaptive-min-saving 0 --quiet -o " + shell_quote(out) + " --stats " + shell_quote(stats),
                                   tmp.path());
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    const Json s = read_json_file(stats);
    const Json& a = s.at("adaptive");
    CHECK(a.at("eps_coarsening_world").get<double>() == 0.0);
    CHECK(a.at("eps_meshing_world").get<double>() == Approx(s.at("eps_world").get<double>()));
    CHECK(a.at("meshed_on").get<std::string>() == "octree");
    CHECK(a.at("E_octree").get<double>() < a.at("E_uniform").get<double>());
    const RunResult v = run_isodel("verify " + shell_quote(torus) + " --iso 0 --eps-voxels 0.5 --mesh " + shell_quote(out),
                                   tmp.path());
    INFO(v.out << v.err);
    CHECK(v.status == 0);
    // A misspelt field is refused with one line.
    const RunResult bad = run_isodel("mesh " + shell_quote(torus) + " --iso 0 --adaptive --adaptive-field fine -o " +
                                         shell_quote(tmp / "bad.ply"),
                                     tmp.path());
    INFO(bad.err);
    CHECK(bad.status != 0);
    CHECK(std::count(bad.err.begin(), bad.err.end(), '\n') == 1);
    CHECK(bad.err.find("--adaptive-field") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(tmp / "bad.ply"));
}

TEST_CASE("mesh --adaptive: an adaptive input and --blocks are refused with one line, nothing written",
          "[cli][adaptive]")
{
    TempDir tmp;
    const std::string torus = std::string(ISODEL_TEST_DATA) + "/torus.vdb";
    const std::string adaptive = tmp / "dec.vdb", out = tmp / "m.ply";
    REQUIRE(run_isodel("decimate " + shell_quote(torus) + " -o " + shell_quote(adaptive) + " --k 1 --tolerance 0.005",
                       tmp.path()).status == 0);
    for (const std::string& args : {shell_quote(adaptive) + " --adaptive", shell_quote(torus) + " --adaptive --blocks 16",
                                    shell_quote(torus) + " --adaptive-grid " + shell_quote(tmp / "g.vdb")}) {
        const RunResult r = run_isodel("mesh " + args + " --iso 0 --quiet -o " + shell_quote(out), tmp.path());
        INFO(args << ": " << r.err);
        CHECK(r.status != 0);
        CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
        CHECK(r.err.find("adaptive") != std::string::npos);
        CHECK_FALSE(std::filesystem::exists(out));
        CHECK_FALSE(std::filesystem::exists(tmp / "g.vdb"));
    }
}

TEST_CASE("mesh --adaptive --adaptive-grid: the octree meshed is written and the surface verifies against "
          "its interpolant as well as against the input",
          "[cli][adaptive]")
{
    TempDir tmp;
    const std::string torus = std::string(ISODEL_TEST_DATA) + "/torus.vdb";
    const std::string out = tmp / "m.ply", grid = tmp / "octree.vdb", stats = tmp / "m.json";
    const RunResult r = run_isodel("mesh " + shell_quote(torus) + " --iso 0 --adaptive --quiet -o " + shell_quote(out) +
                                       " --adaptive-grid " + shell_quote(grid) + " --stats " + shell_quote(stats),
                                   tmp.path());
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    // The file holds the octree the run reports: as many levels, as many leaves per level.
    const RunResult info = run_isodel("info " + shell_quote(grid) + " --json", tmp.path());
    REQUIRE(info.status == 0);
    const Json i = Json::parse(info.out), s = read_json_file(stats);
    const Json& per_level = s.at("adaptive").at("leaves_per_level");
    REQUIRE(per_level.size() >= 2);
    INFO(info.out);
    CHECK(i.at("adaptive").at("levels").get<std::size_t>() == per_level.size());
    CHECK(i.at("adaptive").at("leaves_per_level") == per_level);
    // Against the interpolant the mesher saw (within the meshing share, so within eps), and
    // against the input.
    for (const std::string& volume : {grid, torus}) {
        const RunResult v = run_isodel("verify " + shell_quote(volume) + " --iso 0 --eps-voxels 0.5 --mesh " +
                                           shell_quote(out),
                                       tmp.path());
        INFO(volume << ": " << v.out << v.err);
        CHECK(v.status == 0);
        CHECK(v.out.find("VERIFIED") != std::string::npos);
    }
}

TEST_CASE("mesh --adaptive --adaptive-min-saving: an octree that saves too little gives way to the input's "
          "grid, which is what --adaptive-grid writes",
          "[cli][adaptive]")
{
    TempDir tmp;
    const std::string torus = std::string(ISODEL_TEST_DATA) + "/torus.vdb";
    const std::string out = tmp / "m.ply", plain = tmp / "p.ply", grid = tmp / "g.vdb", stats = tmp / "m.json";
    // The torus's octree removes about a quarter of the crossings: short of 0.9.
    const RunResult r = run_isodel("mesh " + shell_quote(torus) + " --iso 0 --adaptive --adaptive-min-saving 0.9 --quiet -o " +
                                       shell_quote(out) + " --adaptive-grid " + shell_quote(grid) + " --stats " +
                                       shell_quote(stats),
                                   tmp.path());
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    REQUIRE(run_isodel("mesh " + shell_quote(torus) + " --iso 0 --quiet -o " + shell_quote(plain), tmp.path()).status == 0);
    const Json s = read_json_file(stats);
    CHECK(s.at("adaptive").at("meshed_on") == "input grid");
    CHECK(s.at("adaptive").at("distance_world").get<double>() == 0);
    CHECK(s.at("adaptive").at("E_octree").get<std::size_t>() < s.at("adaptive").at("E_uniform").get<std::size_t>());
    CHECK(read_text(out) == read_text(plain)); // the mesh without --adaptive, byte for byte
    const RunResult info = run_isodel("info " + shell_quote(grid) + " --json", tmp.path());
    REQUIRE(info.status == 0);
    const Json i = Json::parse(info.out);
    INFO(info.out);
    CHECK(i.at("adaptive").at("levels").get<std::size_t>() == 1);
    CHECK(i.at("adaptive").at("leaves_per_level") == s.at("adaptive").at("leaves_per_level"));
}
