// random_sweep: the mesher's failure rate on random volumes, on seeds of your choosing.
//
// The property test (tests/corpus/test_verify_property.cpp) holds a fixed set of seeds, and fixes
// tuned against that set can overfit it. This program meshes and verifies random n^3 volumes on
// any seed range (held-out seeds: e.g. 21-100 at n 5), plain and quantized (samples in
// {-1, -0.5, 0, 0.5, 1}: ties with the isovalue 0), at each eps, and prints one row per
// (kind, eps): runs, verified, failures by seed, total vertices and time.
//
//   random_sweep [--n 5] [--seeds 21-100] [--eps-voxels 0.5,0.25,0.1] [--kinds plain,quantized]
//                [--threads 1] [--certify 0|1]
// With --certify 1 each run is MeshOptions::certify (verified before it is returned); a run it
// refuses (GuaranteeViolated) is listed as "(error)".
// The volumes are the property test's (isodel::testing::random_volume in
// tests/support/random_volume.h, shared with the tests, whose seeds refer to it): n^3 uniform
// samples in [-1, 1] drawn from std::mt19937(seed) in x-fastest order, padded by one layer of -1.
// Exit status 0 only if every run verifies; 2 on bad arguments.
#include <isodel/mesh.h>
#include <isodel/verify.h>

#include "support/bench_support.h"
#include "tests/support/random_volume.h"

#include <openvdb/openvdb.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

struct Row {
    int runs = 0, verified = 0, undetermined = 0;
    std::size_t vertices = 0;
    double seconds = 0;
    std::ostringstream failures;
};

} // namespace

int main(int argc, char** argv)
{
    using isodel::bench::split;
    int n = 5, threads = 1, first = 21, last = 100;
    bool certify = false;
    std::vector<double> eps{0.5, 0.25, 0.1};
    std::vector<std::string> kinds{"plain", "quantized"};
    try {
        for (int i = 1; i < argc; ++i) {
            const std::string a = argv[i];
            if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
            const std::string v = argv[++i];
            try {
                if (a == "--n")
                    n = std::stoi(v);
                else if (a == "--threads")
                    threads = std::stoi(v);
                else if (a == "--seeds") {
                    const auto dash = v.find('-');
                    first = std::stoi(v.substr(0, dash));
                    last = dash == std::string::npos ? first : std::stoi(v.substr(dash + 1));
                }
                else if (a == "--eps-voxels") {
                    eps.clear();
                    for (const auto& e : split(v))
                        eps.push_back(std::stod(e));
                }
                else if (a == "--kinds")
                    kinds = split(v);
                else if (a == "--certify")
                    certify = std::stoi(v) != 0;
                else
                    throw std::invalid_argument("unknown option " + a + " (see tools/qa/random_sweep.cpp)");
            }
            catch (const std::invalid_argument& e) {
                if (std::string(e.what()).rfind("sto", 0) != 0) throw;
                throw std::invalid_argument(a + ": not a number: " + v);
            }
        }
        if (n < 1 || threads < 0 || first < 0 || last < first || eps.empty())
            throw std::invalid_argument(
                "need --n >= 1, --threads >= 0, --seeds A-B with 0 <= A <= B, some --eps-voxels");
        for (const auto& k : kinds)
            if (k != "plain" && k != "quantized")
                throw std::invalid_argument("--kinds: '" + k + "' is not plain or quantized");
    }
    catch (const std::exception& e) { // std::stoi/stod say only "stoi": name the problem
        std::fprintf(stderr, "random_sweep: bad arguments: %s\n", e.what());
        return 2;
    }
    openvdb::initialize();
    bool all_pass = true;
    std::printf("| n | kind | eps (voxel) | runs | verified | failed (seed) | undetermined | vertices | seconds |\n");
    std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
    for (const auto& kind : kinds) {
        const bool quantized = kind == "quantized";
        for (double e : eps) {
            Row row;
            for (int s = first; s <= last; ++s) {
                const auto grid = isodel::testing::random_volume(n, unsigned(s), quantized);
                isodel::MeshOptions mo;
                mo.isovalue = 0.0;
                mo.inside = isodel::Inside::Above;
                mo.eps_voxels = e;
                mo.threads = threads;
                mo.certify = certify;
                ++row.runs;
                const auto t0 = std::chrono::steady_clock::now();
                isodel::MeshResult r;
                try {
                    r = isodel::mesh_isosurface(*grid, mo);
                }
                catch (const std::exception& ex) {
                    std::fprintf(stderr, "seed %d (%s, eps %g): %s\n", s, kind.c_str(), e, ex.what());
                    row.failures << ' ' << s << " (error)";
                    continue;
                }
                row.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
                row.vertices += r.surface.vertices.size();
                isodel::VerifyOptions vo;
                vo.isovalue = 0.0;
                vo.inside = isodel::Inside::Above;
                vo.eps_voxels = e;
                const auto rep = isodel::verify_surface(*grid, r.surface, vo);
                if (rep.topology_verdict == isodel::TopologyVerdict::Undetermined) ++row.undetermined;
                if (rep.passed())
                    ++row.verified;
                else
                    row.failures << ' ' << s;
            }
            all_pass &= row.verified == row.runs;
            const std::string failed = row.failures.str().empty() ? "-" : row.failures.str().substr(1);
            std::printf("| %d | %s | %g | %d | %d | %s | %d | %zu | %.1f |\n", n, kind.c_str(), e, row.runs,
                        row.verified, failed.c_str(), row.undetermined, row.vertices, row.seconds);
            std::fflush(stdout);
        }
    }
    return all_pass ? 0 : 1;
}
