// `mpirun -np N isodel mesh ... --blocks B` (docs/partitioned.md): the blocks spread over MPI
// processes give the thread engine's mesh byte for byte at any process count, and that mesh
// verifies, for cubes (--blocks) and for a count of blocks (--block-count); without either the
// run is refused; a process that fails ends the run everywhere
// with one message naming the block, and nothing is written.
#include "support/json.h"
#include "support/skip.h"
#include "support/test_files.h"

#include <catch2/catch.hpp>

#include <filesystem>

using namespace isodel::test;

namespace {

#ifdef ISODEL_MPIRUN
/// mpirun with \p np processes (oversubscribed: CI has 2 cores; root allowed: CI runs as root).
RunResult run_mpi(int np, const std::string& args, const std::string& scratch)
{
    return run("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " + shell_quote(ISODEL_MPIRUN) + " -np " +
                   std::to_string(np) + " --oversubscribe --bind-to none " + shell_quote(ISODEL_CLI) + " " + args,
               scratch);
}

/// `mpirun -np 2` with \p options and one thread per process writes what one process with two
/// threads writes, and that mesh verifies (isovalue 0, eps 0.25).
void check_two_processes_write_the_threads_mesh(const std::string& volume, const std::string& options,
                                                const TempDir& tmp, const std::string& name)
{
    INFO(name << ":" << options);
    const std::string threads = tmp / (name + "_threads.ply"), processes = tmp / (name + "_np2.ply");
    const RunResult t = run_isodel("mesh " + shell_quote(volume) + options + " --threads 2 -o " + shell_quote(threads),
                                   tmp.path());
    INFO(t.err);
    REQUIRE(t.status == 0);
    const RunResult m =
        run_mpi(2, "mesh " + shell_quote(volume) + options + " --threads 1 -o " + shell_quote(processes), tmp.path());
    INFO(m.err);
    REQUIRE(m.status == 0);
    CHECK(read_text(processes) == read_text(threads));
    const RunResult v = run_isodel("verify " + shell_quote(volume) + " --iso 0 --eps-voxels 0.25 --mesh " +
                                       shell_quote(processes),
                                   tmp.path());
    INFO(v.out << v.err);
    CHECK(v.status == 0);
}
#endif

} // namespace

TEST_CASE("mpirun: 1, 2 and 4 processes mesh what the threads mesh, and it verifies", "[cli][partition][mpi]")
{
#ifndef ISODEL_MPIRUN
    ISODEL_SKIP("isodel was built without MPI, or mpirun is missing (Debian: libopenmpi-dev openmpi-bin)");
#else
    TempDir tmp;
    const std::string torus = std::string(ISODEL_TEST_DATA) + "/torus.vdb";
    const std::string common = " --iso 0 --eps-voxels 0.25 --blocks 12 --quiet";
    const std::string threads = tmp / "threads.ply";
    const RunResult t = run_isodel("mesh " + shell_quote(torus) + common + " --threads 2 -o " + shell_quote(threads), tmp.path());
    INFO(t.err);
    REQUIRE(t.status == 0);
    const RunResult v = run_isodel("verify " + shell_quote(torus) + " --iso 0 --eps-voxels 0.25 --mesh " + shell_quote(threads),
                                   tmp.path());
    INFO(v.out << v.err);
    CHECK(v.status == 0);
    CHECK(v.out.find("VERIFIED") != std::string::npos);
    const std::string expected = read_text(threads);
    for (int np : {1, 2, 4}) {
        INFO(np << " processes");
        const std::string out = tmp / ("np" + std::to_string(np) + ".ply"), stats = tmp / ("np" + std::to_string(np) + ".json");
        const RunResult m = run_mpi(np, "mesh " + shell_quote(torus) + common + " --threads 1 -o " + shell_quote(out) +
                                            " --stats " + shell_quote(stats),
                                    tmp.path());
        INFO(m.err);
        REQUIRE(m.status == 0);
        CHECK(read_text(out) == expected);
        const auto s = isodel::testing::read_json_file(stats);
        CHECK(s.at("partition").at("processes").get<int>() == np);
        CHECK(s.at("topology").at("components").get<int>() == 1);
    }
    // --block-count 2 (two slabs of about equal work, one per process) and --release-blocks (one
    // block alive per thread, rebuilt when points arrive): 2 processes write the thread engine's
    // mesh with the same option, and it verifies.
    check_two_processes_write_the_threads_mesh(torus, " --iso 0 --eps-voxels 0.25 --block-count 2 --quiet", tmp,
                                               "count");
    check_two_processes_write_the_threads_mesh(torus, common + " --release-blocks", tmp, "released");
#endif
}

TEST_CASE("mpirun: each process reads only part of an MRC file and they write the threads' mesh", "[cli][partition][mpi]")
{
#ifndef ISODEL_MPIRUN
    ISODEL_SKIP("isodel was built without MPI, or mpirun is missing (Debian: libopenmpi-dev openmpi-bin)");
#else
    TempDir tmp;
    const std::string blobs = std::string(ISODEL_TEST_DATA) + "/two_blobs.mrc";
    const std::string common = " --iso 0.5 --eps-voxels 0.5 --quiet";
    for (const std::string& part : {std::string(" --block-count 2"), std::string(" --blocks 8")}) {
        INFO(part);
        const std::string threads = tmp / "threads.ply";
        const RunResult t =
            run_isodel("mesh " + shell_quote(blobs) + common + part + " --threads 2 -o " + shell_quote(threads), tmp.path());
        INFO(t.err);
        REQUIRE(t.status == 0);
        for (int np : {2, 3}) {
            INFO(np << " processes");
            const std::string out = tmp / "np.ply", stats = tmp / "np.json";
            const RunResult m = run_mpi(np, "mesh " + shell_quote(blobs) + common + part + " --threads 1 -o " +
                                                shell_quote(out) + " --stats " + shell_quote(stats),
                                        tmp.path());
            INFO(m.err);
            REQUIRE(m.status == 0);
            CHECK(read_text(out) == read_text(threads));
            const auto p = isodel::testing::read_json_file(stats).at("partition");
            CHECK(p.at("processes").get<int>() == np);
            // No process read the whole file: a slab of it, then its blocks' boxes (in leaves of
            // 8^3 samples; cubes of 8 with their collars meet every leaf of this small file).
            CHECK(p.at("max_process_samples_read").get<double>() > 0);
            if (part == " --block-count 2")
                CHECK(p.at("max_process_samples_read").get<double>() < p.at("file_samples").get<double>());
        }
    }
    // An isovalue outside the samples: one line naming the file (once), exit 2, no file.
    const std::string out = tmp / "none.ply";
    const RunResult r =
        run_mpi(2, "mesh " + shell_quote(blobs) + " --iso 1e6 --block-count 2 --quiet -o " + shell_quote(out), tmp.path());
    INFO(r.err);
    CHECK(r.status == 2);
    CHECK(r.err.find(blobs + ": isovalue") != std::string::npos);
    CHECK(r.err.find(blobs + ": " + blobs) == std::string::npos);
    CHECK_FALSE(std::filesystem::exists(out));
#endif
}

TEST_CASE("mpirun: refusals and a failing process end the run with one message and no file", "[cli][partition][mpi]")
{
#ifndef ISODEL_MPIRUN
    ISODEL_SKIP("isodel was built without MPI, or mpirun is missing (Debian: libopenmpi-dev openmpi-bin)");
#else
    TempDir tmp;
    const std::string torus = std::string(ISODEL_TEST_DATA) + "/torus.vdb";
    const std::string out = tmp / "m.ply";
    // Several processes need blocks to share.
    RunResult r = run_mpi(2, "mesh " + shell_quote(torus) + " --iso 0 --quiet -o " + shell_quote(out), tmp.path());
    CHECK(r.status == 2);
    CHECK(r.err.find("needs --blocks") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(out));
    // Every block stops at the round bound: every process ends, the first says which block once.
    r = run_mpi(2, "mesh " + shell_quote(torus) + " --iso 0 --eps-voxels 0.1 --blocks 12 --max-rounds 1 --quiet -o " + shell_quote(out),
                tmp.path());
    INFO(r.err);
    CHECK(r.status == 1);
    CHECK(r.err.find("block ") != std::string::npos);
    CHECK(r.err.find("round bound") != std::string::npos);
    std::size_t lines = 0;
    for (std::size_t p = r.err.find("isodel:"); p != std::string::npos; p = r.err.find("isodel:", p + 1)) ++lines;
    CHECK(lines == 1);
    CHECK_FALSE(std::filesystem::exists(out));
    // A file only one process could not read is everybody's error: nobody waits for it.
    r = run_mpi(2, "mesh " + shell_quote(tmp / "missing.vdb") + " --iso 0 --blocks 12 --quiet -o " + shell_quote(out), tmp.path());
    CHECK(r.status == 2);
    CHECK_FALSE(std::filesystem::exists(out));
#endif
}
