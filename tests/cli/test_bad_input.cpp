// Every kind of bad input (include/isodel/errors.h) through the real executable: exit code 2, exactly one line on
// stderr "isodel: <file>: <problem>", and nothing (neither output nor temporary) in the output
// folder. Malformed inputs are generated here, in a temporary folder.
#include "support/test_files.h"

#include <catch2/catch.hpp>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <filesystem>

using namespace isodel::test;

namespace {

double f(int x, int y, int z) { return 0.5 * x - y + 0.25 * z; }

struct BadCase {
    std::string name;
    std::string input;                 // path of the malformed input
    std::vector<std::string> expected; // substrings of the message
    std::string extra_args;            // e.g. --grid NAME
    std::string env;                   // e.g. ISODEL_MAX_VOXELS=10
};

void write_vdb_file(const std::string& path, const openvdb::GridPtrVec& grids)
{
    openvdb::io::File file(path);
    file.write(grids);
    file.close();
}

openvdb::FloatGrid::Ptr small_grid(const std::string& name)
{
    auto g = openvdb::FloatGrid::create(0.f);
    g->setName(name);
    g->tree().setValue(openvdb::Coord(1, 2, 3), 1.5f);
    g->tree().setValue(openvdb::Coord(2, 2, 3), -0.5f);
    return g;
}

void expect_refused(const std::string& command, const std::string& input, const std::vector<std::string>& expected,
                    const TempDir& scratch, const std::string& out_dir)
{
    const RunResult r = run(command, scratch.path());
    INFO("command: " << command << "\nstderr: " << r.err << "\nstdout: " << r.out);
    CHECK(r.status == 2);
    CHECK(r.err.rfind("isodel: " + input + ": ", 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    for (const auto& s : expected) CHECK(r.err.find(s) != std::string::npos);
    const auto left = list_dir(out_dir);
    INFO("left in the output folder: " << left.size());
    CHECK(left.empty());
}

} // namespace

TEST_CASE("bad inputs: exit 2, one line naming file and problem, no file written", "[cli][errors]")
{
    TempDir in, out, scratch;
    std::vector<BadCase> cases;
    MrcSpec good;
    good.n = {4, 3, 2};
    const std::string good_mrc = mrc_bytes(good, f);

    cases.push_back({"missing file", in / "missing.mrc", {"cannot open", "No such file"}});
    write_bytes(in / "volume.xyz", good_mrc);
    cases.push_back({"unknown extension", in / "volume.xyz", {"unknown extension '.xyz'"}});
    {
        MrcSpec s = good;
        s.magic = "ABC ";
        write_bytes(in / "magic.mrc", mrc_bytes(s, f));
        cases.push_back({"wrong magic (MRC)", in / "magic.mrc", {"wrong magic number"}});
        write_bytes(in / "magic.inr", "#INRIMAGE-5#{\n" + std::string(300, '\n'));
        cases.push_back({"wrong magic (INR)", in / "magic.inr", {"wrong magic number"}});
        write_bytes(in / "magic.vdb", std::string(200, 'v'));
        cases.push_back({"wrong magic (VDB)", in / "magic.vdb", {"not a readable OpenVDB file"}});
    }
    {
        write_bytes(in / "truncated.mrc", good_mrc.substr(0, good_mrc.size() - 7));
        cases.push_back({"truncated MRC", in / "truncated.mrc",
                         {"truncated", std::to_string(good_mrc.size()), std::to_string(good_mrc.size() - 7)}});
        const std::string inr = inr_bytes({3, 3, 3}, "float", 32, "decm", {1, 1, 1}, f);
        write_bytes(in / "truncated.inr", inr.substr(0, inr.size() - 10));
        cases.push_back({"truncated INR", in / "truncated.inr", {"truncated"}});
        write_bytes(in / "truncated_header.mrc", good_mrc.substr(0, 500));
        cases.push_back({"truncated MRC header", in / "truncated_header.mrc", {"truncated", "500"}});
    }
    {
        write_bytes(in / "toolong.mrc", good_mrc + std::string(40, '\0'));
        cases.push_back({"header dims disagree with the file size", in / "toolong.mrc",
                         {"disagree", std::to_string(good_mrc.size()), std::to_string(good_mrc.size() + 40)}});
    }
    {
        std::string b = good_mrc;
        const std::int32_t huge[3] = {50000, 50000, 50000};
        std::memcpy(&b[0], huge, sizeof huge);
        write_bytes(in / "absurd.mrc", b);
        cases.push_back({"absurd header dims", in / "absurd.mrc", {"50000 x 50000 x 50000", "limit"}});
        write_bytes(in / "capped.mrc", good_mrc);
        cases.push_back({"over a configured voxel cap", in / "capped.mrc", {"limit of 10"}, "", "ISODEL_MAX_VOXELS=10"});
    }
    {
        MrcSpec s = good;
        s.voxel = {1, 0, 1};
        write_bytes(in / "zero_voxel.mrc", mrc_bytes(s, f));
        cases.push_back({"zero voxel size", in / "zero_voxel.mrc", {"voxel size"}});
        s.voxel = {1, 1, 1};
        s.cell = {-4, 3, 2};
        write_bytes(in / "negative_voxel.mrc", mrc_bytes(s, f));
        cases.push_back({"negative voxel size", in / "negative_voxel.mrc", {"voxel size"}});
        write_bytes(in / "zero_voxel.inr", inr_bytes({2, 2, 2}, "float", 32, "decm", {0, 1, 1}, f));
        cases.push_back({"zero voxel size (INR)", in / "zero_voxel.inr", {"voxel size"}});
    }
    {
        write_bytes(in / "nan.mrc", mrc_bytes(good, [](int x, int y, int z) { return x == 3 && y == 1 && z == 1 ? NAN : 1.0; }));
        cases.push_back({"NaN sample", in / "nan.mrc", {"NaN", "(3, 1, 1)"}});
        write_bytes(in / "inf.inr", inr_bytes({3, 3, 3}, "float", 32, "decm", {1, 1, 1},
                                             [](int x, int y, int z) { return x == 0 && y == 2 && z == 1 ? -INFINITY : 1.0; }));
        cases.push_back({"Inf sample", in / "inf.inr", {"Inf", "(0, 2, 1)"}});
        auto g = small_grid("density");
        g->tree().setValue(openvdb::Coord(2, 2, 3), std::numeric_limits<float>::infinity());
        write_vdb_file(in / "inf.vdb", {g});
        cases.push_back({"Inf voxel (VDB)", in / "inf.vdb", {"Inf", "(2, 2, 3)"}});
    }
    {
        auto empty = openvdb::FloatGrid::create(0.f);
        empty->setName("nothing");
        write_vdb_file(in / "empty.vdb", {empty});
        cases.push_back({"empty grid", in / "empty.vdb", {"empty grid 'nothing'"}});
        auto vec = openvdb::Vec3SGrid::create();
        vec->setName("velocity");
        vec->tree().setValue(openvdb::Coord(0), openvdb::Vec3s(1, 0, 0));
        write_vdb_file(in / "vector.vdb", {vec});
        cases.push_back({"non-scalar grid", in / "vector.vdb", {"no float or double scalar grid", "'velocity'"}});
        cases.push_back({"non-scalar grid by name", in / "vector.vdb", {"not a scalar grid"}, "--grid velocity"});
        write_vdb_file(in / "two.vdb", {small_grid("alpha"), small_grid("beta")});
        cases.push_back({"--grid name not there", in / "two.vdb", {"no grid named 'gamma'", "'alpha'", "'beta'"}, "--grid gamma"});
    }
    {
        write_bytes(in / "raw.bin", std::string(100, '\0'));
        cases.push_back({"raw dims disagree with the file size", in / "raw.bin", {"disagree", "100"},
                         "--raw-dims 4,4,4 --raw-type uint8"});
    }

    for (const BadCase& c : cases) {
        DYNAMIC_SECTION(c.name)
        {
            const std::string cmd = (c.env.empty() ? "" : "env " + c.env + " ") + shell_quote(ISODEL_CLI) +
                                    " convert " + shell_quote(c.input) + " -o " + shell_quote(out / "out.vdb") +
                                    (c.extra_args.empty() ? "" : " " + c.extra_args);
            expect_refused(cmd, c.input, c.expected, scratch, out.path());
            // info refuses the same input the same way (nothing to write there).
            const std::string info = (c.env.empty() ? "" : "env " + c.env + " ") + shell_quote(ISODEL_CLI) +
                                     " info " + shell_quote(c.input) + (c.extra_args.empty() ? "" : " " + c.extra_args);
            expect_refused(info, c.input, c.expected, scratch, out.path());
        }
    }
}

TEST_CASE("isovalue outside the value range is refused with the range", "[cli][errors]")
{
    TempDir in, out, scratch;
    MrcSpec s;
    s.n = {4, 3, 2};
    write_bytes(in / "v.mrc", mrc_bytes(s, f));
    // The range of f over the lattice, computed here independently of the reader.
    double lo = 1e300, hi = -1e300;
    for (int z = 0; z < 2; ++z)
        for (int y = 0; y < 3; ++y)
            for (int x = 0; x < 4; ++x) lo = std::min(lo, f(x, y, z)), hi = std::max(hi, f(x, y, z));
    std::ostringstream range;
    range << "[" << lo << ", " << hi << "]";
    for (const char* iso : {"1000", "-7.5"}) {
        INFO("iso " << iso);
        expect_refused(shell_quote(ISODEL_CLI) + " mesh " + shell_quote(in / "v.mrc") + " -o " +
                           shell_quote(out / "s.ply") + " --iso " + iso,
                       in / "v.mrc", {"outside the value range", range.str()}, scratch, out.path());
    }
}

TEST_CASE("usage errors: exit 2 and one line", "[cli][errors]")
{
    TempDir scratch;
    for (const char* args : {"", "convert", "info", "frobnicate x", "mesh x.mrc --iso 1", "convert a.mrc -o b.vdb --bogus"}) {
        INFO("isodel " << args);
        const RunResult r = run_isodel(args, scratch.path());
        CHECK(r.status == 2);
        CHECK(r.err.rfind("isodel: ", 0) == 0);
        CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    }
    // A block size that would mesh each voxel's collar over and over: refused before any work.
    const std::string out = scratch / "blocks.ply";
    const RunResult tiny = run_isodel("mesh " + shell_quote(std::string(ISODEL_TEST_DATA) + "/two_blobs.mrc") +
                                          " --iso 0.5 --blocks 1 -o " + shell_quote(out),
                                      scratch.path());
    CHECK(tiny.status == 2);
    CHECK(tiny.err.find("at least 4") != std::string::npos);
    CHECK(std::count(tiny.err.begin(), tiny.err.end(), '\n') == 1);
    CHECK(!std::filesystem::exists(out));
    // Two ways to cut the blocks at once, and more blocks than the volume has room for.
    const std::string blobs = shell_quote(std::string(ISODEL_TEST_DATA) + "/two_blobs.mrc");
    for (const char* cut : {"--blocks 8 --block-count 2", "--block-count 100000"}) {
        INFO(cut);
        const RunResult r = run_isodel("mesh " + blobs + " --iso 0.5 " + cut + " -o " + shell_quote(out), scratch.path());
        CHECK(r.status == 2);
        CHECK(r.err.rfind("isodel: ", 0) == 0);
        CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
        CHECK(!std::filesystem::exists(out));
    }
    const RunResult help = run_isodel("mesh --help", scratch.path());
    CHECK(help.status == 0);
    for (const char* opt : {"--iso", "--grid", "--inside", "--eps", "--eps-voxels", "--tets", "--region", "--threads",
                            "--stats", "--quiet"})
        CHECK(help.out.find(opt) != std::string::npos);
}

TEST_CASE("an unwritable output folder is an error naming the output", "[cli][errors]")
{
    TempDir in, scratch;
    MrcSpec s;
    write_bytes(in / "v.mrc", mrc_bytes(s, f));
    const std::string target = in.path() + "/no/such/folder/out.vdb";
    const RunResult r = run_isodel("convert " + shell_quote(in / "v.mrc") + " -o " + shell_quote(target), scratch.path());
    CHECK(r.status == 2);
    CHECK(r.err.rfind("isodel: " + target + ": cannot write", 0) == 0);
}
