// Decimation (paper Property IV) on the shared skull and protein volumes and on synthetic data.
#include "support/adaptive_random.h"

#include "octree/adaptive_vdb_format.h"
#include "octree/balance.h"
#include "octree/decimate.h"
#include "octree/resample.h"

#include <isodel/adaptive.h>

#include <catch2/catch.hpp>

#include "support/skip.h"

#include <cmath>
#include <filesystem>
#include <iostream>

using namespace isodel::octree;

namespace {
openvdb::FloatGrid::Ptr read_first_float(const std::string& path)
{
    openvdb::io::File f(path);
    f.open();
    for (auto it = f.beginName(); it != f.endName(); ++it) {
        auto g = openvdb::gridPtrCast<openvdb::FloatGrid>(f.readGrid(it.gridName()));
        if (g) return g;
    }
    return nullptr;
}

double value_range(const openvdb::FloatGrid& g)
{
    float lo = g.background(), hi = lo;
    for (auto it = g.cbeginValueAll(); it; ++it) {
        lo = std::min(lo, *it);
        hi = std::max(hi, *it);
    }
    return double(hi) - double(lo);
}

// Independent check of the stated error: resample densely and compare every domain sample.
double resampled_error(const isodel::AdaptiveVolume& v, const openvdb::FloatGrid& orig)
{
    auto dense = isodel::resample(v);
    auto a = dense->getConstAccessor();
    auto b = orig.getConstAccessor();
    double worst = 0;
    for (auto it = v.domain.begin(); it; ++it)
        worst = std::max(worst, std::abs(double(a.getValue(*it)) - double(b.getValue(*it))));
    return worst;
}
} // namespace

TEST_CASE("decimate a linear field: coarsens fully, exactly", "[octree][decimate]")
{
    auto g = openvdb::FloatGrid::create(0.f);
    auto acc = g->getAccessor();
    for (int z = 0; z < 31; ++z)
        for (int y = 0; y < 31; ++y)
            for (int x = 0; x < 31; ++x) acc.setValueOn(Coord(x, y, z), float(x + 2 * y - z));
    isodel::DecimateOptions opt;
    opt.k = 1;
    opt.tolerance = 1e-3;
    const auto res = isodel::decimate(*g, opt);
    CHECK(res.cells_after < res.cells_before / 3); // the background ring is not linear
    CHECK(res.max_error <= opt.tolerance);
    CHECK(res.max_level_difference <= 1);
    CHECK(resampled_error(res.volume, *g) <= opt.tolerance);
}

TEST_CASE("decimate random data: error bound, balance, band and importance", "[octree][decimate]")
{
    for (unsigned seed = 1; seed <= 4; ++seed) {
        auto g = testing::random_samples(24, seed, true);
        isodel::DecimateOptions opt;
        opt.k = 1 + seed % 3;
        opt.tolerance = 0.05;
        opt.iso = 0.0;
        opt.band = 1;
        const auto res = isodel::decimate(*g, opt);
        INFO("seed " << seed);
        CHECK(res.cells_after < res.cells_before);
        CHECK(res.max_error <= opt.tolerance);
        CHECK(res.max_level_difference <= opt.k);
        CHECK(resampled_error(res.volume, *g) <= opt.tolerance);
        // Band: every protected node (corner of a crossed cell) is a corner of level-0 cells only.
        const AdaptiveGrid ag = to_adaptive_grid(res.volume);
        AdaptiveGrid::Reader r(ag);
        const AdaptiveGrid uni(g, 1);
        const auto prot = protected_nodes(uni, opt);
        for (auto it = prot->cbeginValueOn(); it; ++it)
            for (int m = 0; m < 8; ++m) {
                const int l = r.leaf_level(it.getCoord().offsetBy(-(m & 1), -((m >> 1) & 1), -((m >> 2) & 1)));
                CHECK(l <= 0);
            }
    }
    // Importance: a mask over the whole volume keeps everything fine.
    auto g = testing::random_samples(16, 9, true);
    auto imp = openvdb::MaskGrid::create(false);
    imp->topologyUnion(*g);
    isodel::DecimateOptions opt;
    opt.tolerance = 10;
    opt.importance = imp;
    const auto res = isodel::decimate(*g, opt);
    // Only cells not touching an active voxel (the outer ring) may merge: none can.
    CHECK(res.histogram.size() == 1);
}

TEST_CASE("decimate the shared skull and protein volumes at 1% of the value range", "[octree][decimate][corpus]")
{
    const std::string root = ISODEL_SHARED_DATA;
    if (!std::filesystem::exists(root + "/manifest.json")) ISODEL_SKIP("../shared/data not found at " << root);
    for (const char* rel : {"ct/skull_2.9.vdb", "protein/1hpv_blobby_1A.vdb", "protein/1hpv_molmap_6A_2A.vdb"}) {
        const std::string path = root + "/" + rel;
        REQUIRE(std::filesystem::exists(path));
        auto g = read_first_float(path);
        REQUIRE(g);
        isodel::DecimateOptions opt;
        opt.k = 1;
        opt.tolerance = 0.01 * value_range(*g);
        opt.source = rel;
        const auto res = isodel::decimate(*g, opt);
        const double factor = double(res.cells_before) / double(res.cells_after);
        std::cout << "[decimate] " << rel << ": T = " << opt.tolerance << ", cells " << res.cells_before
                  << " -> " << res.cells_after << " (factor " << factor << "), memory "
                  << res.memory_before << " -> " << res.memory_after << " B, max error " << res.max_error
                  << ", levels " << res.histogram.size() << ", repairs " << res.repair_splits << ", "
                  << res.seconds << " s\n";
        INFO(rel);
        CHECK(res.cells_after < res.cells_before);
        CHECK(res.max_error <= opt.tolerance);
        CHECK(res.max_level_difference <= opt.k);
        CHECK(resampled_error(res.volume, *g) <= opt.tolerance);
    }
}
