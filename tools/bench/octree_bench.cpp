// octree_bench: for the shared volumes, OpenVDB read time vs. the time to build the (uniform)
// adaptive grid, and decimation (T = 1% of the value range, k = 1) time and peak memory.
// Usage: octree_bench [DATA_DIR]   (default ../shared/data)
#include "octree/adaptive_grid.h"

#include <isodel/adaptive.h>

#include <openvdb/openvdb.h>

#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

namespace {
double now()
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
long peak_kib()
{
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss;
}
} // namespace

int main(int argc, char** argv)
{
    openvdb::initialize();
    const std::string root = argc > 1 ? argv[1] : "../shared/data";
    const char* files[] = {"ct/skull_2.9.vdb", "protein/1hpv_blobby_1A.vdb", "protein/1hpv_molmap_6A_2A.vdb",
                           "levelset/bunny.vdb", "levelset/eight.vdb", "analytic/gyroid_ball.vdb"};
    std::printf("%-32s %9s %9s %6s %10s %10s %8s %9s %9s\n", "volume", "read ms", "build ms", "ratio",
                "cells", "dec cells", "dec ms", "maxerr/T", "peak MiB");
    for (const char* rel : files) {
        const std::string path = root + "/" + rel;
        if (!std::filesystem::exists(path)) continue;
        const int reps = 5;
        double tread = 1e30, tbuild = 1e30;
        openvdb::FloatGrid::Ptr grid;
        for (int r = 0; r < reps; ++r) {
            double t = now();
            openvdb::io::File f(path);
            f.open();
            grid = openvdb::gridPtrCast<openvdb::FloatGrid>(f.readGrid(f.beginName().gridName()));
            f.close();
            tread = std::min(tread, now() - t);
            t = now();
            isodel::octree::AdaptiveGrid g(grid, 1);
            volatile auto n = g.cell_count();
            (void)n;
            tbuild = std::min(tbuild, now() - t);
        }
        float lo = grid->background(), hi = lo;
        for (auto it = grid->cbeginValueOn(); it; ++it) { lo = std::min(lo, *it); hi = std::max(hi, *it); }
        isodel::DecimateOptions opt;
        opt.k = 1;
        opt.tolerance = 0.01 * (double(hi) - double(lo));
        const double t = now();
        const auto res = isodel::decimate(*grid, opt);
        const double tdec = now() - t;
        std::printf("%-32s %9.3f %9.3f %6.3f %10llu %10llu %8.1f %9.4f %9.1f\n", rel, 1e3 * tread, 1e3 * tbuild,
                    tbuild / tread, (unsigned long long)res.cells_before, (unsigned long long)res.cells_after,
                    1e3 * tdec, res.max_error / opt.tolerance, peak_kib() / 1024.0);
    }
    return 0;
}
