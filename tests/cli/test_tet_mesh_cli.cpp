// `isodel mesh --tets` (DELVOLMESH, paper Section 4.1): the .mesh, .vtu and .msh files load in the readers FEM users
// have -- meshio, VTK's XML reader, the Gmsh CLI -- and each agrees with the run's statistics on
// vertex, triangle and per-region tetrahedron counts (tests/cli/tet_mesh_readers.py); a bad
// extension is refused before any meshing.
#include "support/json.h"
#include "support/test_files.h"

#include <catch2/catch.hpp>

using namespace isodel::test;
using isodel::testing::Json;
using isodel::testing::read_json_file;

namespace {

std::string readers_script() { return std::string(ISODEL_TEST_DATA) + "/../cli/tet_mesh_readers.py"; }
std::string blobs() { return std::string(ISODEL_TEST_DATA) + "/two_blobs.mrc"; }

} // namespace

TEST_CASE("mesh --tets: real readers load .mesh, .vtu and .msh with the same counts", "[cli][tets]")
{
    TempDir tmp;
    for (const std::string region : {"inside", "both"})
        for (const std::string ext : {"mesh", "vtu", "msh"}) {
            const std::string tets = tmp / ("blobs_" + region + "." + ext), stats = tmp / "stats.json";
            INFO("region " << region << ", " << tets);
            const RunResult r = run_isodel("mesh " + shell_quote(blobs()) + " -o " + shell_quote(tmp / "s.ply") +
                                               " --iso 0.5 --tets " + shell_quote(tets) + " --region " + region +
                                               " --stats " + shell_quote(stats),
                                           tmp.path());
            INFO("stderr: " << r.err);
            REQUIRE(r.status == 0);
            const Json s = read_json_file(stats);
            const Json& t = s.at("tets");
            const long nv = t.at("vertices").get<long>(), nin = t.at("tets_inside").get<long>(),
                       nout = t.at("tets_outside").get<long>(), ntri = s.at("counts").at("triangles").get<long>();
            CHECK(nin > 0);
            CHECK((region == "both") == (nout > 0));
            CHECK(t.at("volume_inside").get<double>() ==
                  Approx(t.at("volume_enclosed_by_surface").get<double>()).epsilon(1e-9));
            // Where the tets phase's time went: every step, adding up to at most the phase.
            double steps = 0;
            for (const char* step : {"insert_g_prime", "conformity_checks", "crowding_points", "region_labels",
                                     "numbering", "improvement", "quality"}) {
                INFO(step);
                REQUIRE(t.at("seconds").contains(step));
                CHECK(t.at("seconds").at(step).get<double>() >= 0);
                steps += t.at("seconds").at(step).get<double>();
            }
            CHECK(steps <= s.at("seconds").at("tets").get<double>() + 1e-6);
            CHECK(t.at("seconds").at("improvement").get<double>() >= t.at("improvement_seconds").get<double>());
            const RunResult py = run("/usr/bin/python3 " + shell_quote(readers_script()) + " " + shell_quote(tets) +
                                         " " + std::to_string(nv) + " " + std::to_string(ntri) + " " +
                                         std::to_string(nin) + " " + std::to_string(nout),
                                     tmp.path());
            INFO("readers:\n" << py.out << py.err);
            if (py.status == 2) FAIL("a reader is missing: apt-get install gmsh python3-meshio python3-vtk9");
            CHECK(py.status == 0);
            CHECK(py.out.find("\nOK\n") != std::string::npos);
        }
}

TEST_CASE("mesh --tets: an unknown extension is refused before meshing", "[cli][tets]")
{
    TempDir tmp;
    const std::string bad = tmp / "t.stl";
    const RunResult r = run_isodel("mesh " + shell_quote(blobs()) + " -o " + shell_quote(tmp / "s.ply") +
                                       " --iso 0.5 --tets " + shell_quote(bad),
                                   tmp.path());
    CHECK(r.status == 2);
    CHECK(r.err.find(bad) != std::string::npos);
    CHECK(r.err.find(".mesh, .vtu or .msh") != std::string::npos);
    CHECK(list_dir(tmp.path()).empty()); // nothing written: not even the surface
}

TEST_CASE("mesh --tets: --uniform-tets, --tet-size and --grading change the tets, not the surface", "[cli][tets]")
{
    TempDir tmp;
    const auto mesh = [&](const std::string& name, const std::string& extra) {
        const RunResult r = run_isodel("mesh " + shell_quote(blobs()) + " -o " + shell_quote(tmp / (name + ".ply")) +
                                           " --iso 0.5 --region both --tets " + shell_quote(tmp / (name + ".mesh")) + extra,
                                       tmp.path());
        INFO(r.err);
        REQUIRE(r.status == 0);
        return read_text(tmp / (name + ".mesh"));
    };
    const std::string graded = mesh("graded", ""), uniform = mesh("uniform", " --uniform-tets");
    const std::string small = mesh("small", " --tet-size 0.5 --grading 2");
    const std::string gentle = mesh("gentle", " --grading 0.25");
    CHECK(read_text(tmp / "graded.ply") == read_text(tmp / "uniform.ply"));
    CHECK(read_text(tmp / "graded.ply") == read_text(tmp / "small.ply"));
    CHECK(read_text(tmp / "graded.ply") == read_text(tmp / "gentle.ply"));
    CHECK(graded.size() < uniform.size());
    CHECK(graded.size() < gentle.size()); // slower growth: more points
    CHECK(gentle.size() < uniform.size());
    CHECK(small == uniform); // a largest spacing of one voxel (0.5) is every sample
    for (const std::string bad : {" --grading 0", " --tet-size -1", " --uniform-tets --tet-size 2"}) {
        TempDir out;
        const RunResult r = run_isodel("mesh " + shell_quote(blobs()) + " -o " + shell_quote(out / "s.ply") +
                                           " --iso 0.5 --tets " + shell_quote(out / "t.mesh") + bad,
                                       out.path());
        CHECK(r.status != 0);
        CHECK(list_dir(out.path()).empty());
    }
}

TEST_CASE("verify --tets: isodel's .mesh verifies; a .vtu is refused with the file named", "[cli][tets][verify]")
{
    TempDir tmp;
    const std::string surf = tmp / "s.ply", tets = tmp / "t.mesh";
    const RunResult m = run_isodel("mesh " + shell_quote(blobs()) + " -o " + shell_quote(surf) + " --iso 0.5 --tets " +
                                       shell_quote(tets) + " --region both",
                                   tmp.path());
    REQUIRE(m.status == 0);
    const RunResult v = run_isodel("verify " + shell_quote(blobs()) + " --iso 0.5 --mesh " + shell_quote(surf) +
                                       " --tets " + shell_quote(tets) + " --eps-voxels 0.5",
                                   tmp.path());
    INFO(v.out << v.err);
    CHECK(v.status == 0);
    CHECK(v.out.find("[PASS] tetrahedra:") != std::string::npos);

    const std::string vtu = tmp / "t.vtu";
    const RunResult bad = run_isodel("verify " + shell_quote(blobs()) + " --iso 0.5 --mesh " + shell_quote(surf) +
                                         " --tets " + shell_quote(vtu),
                                     tmp.path());
    CHECK(bad.status == 2);
    CHECK(bad.err.find(vtu) != std::string::npos);
}
