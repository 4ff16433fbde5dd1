// random_sweep: the mesher's failure rate on random volumes, on seeds of your choosing.
//
// The property test (tests/corpus/test_verify_property.cpp) holds a fixed set of seeds, and fixes
// tuned against that set can overfit it. This program meshes and verifies random n^3 volumes on
// any seed range (held-out seeds: e.g. 21-100 at n 5), plain and quantized (samples in
// {-1, -0.5, 0, 0.5, 1}: ties with the isovalue 0), at each eps, and prints one row per
// (kind, eps): runs, verified, failures by seed, total vertices and time.
//
//   random_sweep [--n 5] [--seeds 21-100] [--eps-voxels 0.5,0.25,0.1] [--kinds plain,quantized]
//                [--threads 1]
// The volumes are the property test's: n^3 uniform samples in [-1, 1] drawn from
// std::mt19937(seed) in x-fastest order, padded by one layer of -1. Exit status 0 only if
// every run verifies.
#include <isodel/mesh.h>
#include <isodel/verify.h>

#include "bench_support.h"

#include <openvdb/openvdb.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

openvdb::FloatGrid::Ptr random_volume(int n, unsigned seed, bool quantized)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    auto grid = openvdb::FloatGrid::create(-1.f);
    auto acc = grid->getAccessor();
    for (int k = 0; k < n + 2; ++k)
        for (int j = 0; j < n + 2; ++j)
            for (int i = 0; i < n + 2; ++i) {
                double v = -1.0;
                if (i != 0 && j != 0 && k != 0 && i != n + 1 && j != n + 1 && k != n + 1) {
                    v = U(rng);
                    if (quantized) v = std::round(v * 2.0) / 2.0;
                }
                acc.setValueOn(openvdb::Coord(i, j, k), float(v));
            }
    return grid;
}

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
    std::vector<double> eps{0.5, 0.25, 0.1};
    std::vector<std::string> kinds{"plain", "quantized"};
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() -> std::string {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "random_sweep: %s needs a value\n", a.c_str());
                std::exit(2);
            }
            return argv[++i];
        };
        if (a == "--n") n = std::stoi(next());
        else if (a == "--threads") threads = std::stoi(next());
        else if (a == "--seeds") {
            const std::string s = next();
            const auto dash = s.find('-');
            first = std::stoi(s.substr(0, dash));
            last = dash == std::string::npos ? first : std::stoi(s.substr(dash + 1));
        } else if (a == "--eps-voxels") {
            eps.clear();
            for (const auto& e : split(next())) eps.push_back(std::stod(e));
        } else if (a == "--kinds") kinds = split(next());
        else {
            std::fprintf(stderr, "random_sweep: unknown option %s (see the header of tools/bench/random_sweep.cpp)\n", a.c_str());
            return 2;
        }
    }
    openvdb::initialize();
    bool all_pass = true;
    std::printf("| n | kind | eps (voxel) | runs | verified | failed (seed) | vertices | seconds |\n");
    std::printf("| --- | --- | --- | --- | --- | --- | --- | --- |\n");
    for (const auto& kind : kinds) {
        const bool quantized = kind == "quantized";
        for (double e : eps) {
            Row row;
            for (int s = first; s <= last; ++s) {
                const auto grid = random_volume(n, unsigned(s), quantized);
                isodel::MeshOptions mo;
                mo.isovalue = 0.0;
                mo.inside = isodel::Inside::Above;
                mo.eps_voxels = e;
                mo.threads = threads;
                ++row.runs;
                const auto t0 = std::chrono::steady_clock::now();
                isodel::MeshResult r;
                try {
                    r = isodel::mesh_isosurface(*grid, mo);
                } catch (const std::exception& ex) {
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
                if (rep.topology_verdict == "undetermined") ++row.undetermined;
                if (rep.passed()) ++row.verified;
                else row.failures << ' ' << s;
            }
            all_pass &= row.verified == row.runs;
            std::printf("| %d | %s | %g | %d | %d | %s | %zu | %.1f |\n", n, kind.c_str(), e, row.runs, row.verified,
                        row.failures.str().empty() ? "-" : row.failures.str().c_str() + 1, row.vertices, row.seconds);
            std::fflush(stdout);
        }
    }
    return all_pass ? 0 : 1;
}
