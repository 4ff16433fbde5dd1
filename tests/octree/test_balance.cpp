// Balance (paper Section 4.2: adjacent leaves differ by at most k levels) over random refinements.
#include "support/adaptive_random.h"

#include "octree/adaptive_queries.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>

using namespace isodel::octree;

namespace {
// Independent brute force: two leaves touch iff two of their unit cells are 26-adjacent (or equal
// leaf), so the max level difference is the max over 26-adjacent unit-cell pairs.
int brute_force_max_difference(const AdaptiveGrid& g)
{
    AdaptiveGrid::Reader r(g);
    const CoordBBox cells = g.unit_cells();
    int worst = 0;
    for (auto it = cells.begin(); it; ++it) {
        const int a = r.leaf_level(*it);
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int b = r.leaf_level((*it).offsetBy(dx, dy, dz));
                    if (b >= 0) worst = std::max(worst, std::abs(a - b));
                }
    }
    return worst;
}
} // namespace

TEST_CASE("uniform grid is one level and costs no mask", "[octree][balance]")
{
    auto s = testing::random_samples(8, 1);
    AdaptiveGrid g(s, 1);
    CHECK(g.max_level() == 0);
    CHECK(g.memory_bytes() == s->memUsage());
    CHECK(g.cell_count() == 9u * 9u * 9u); // domain [-1, 8]^3 -> 9^3 unit cells
    CHECK(max_level_difference(g) == 0);
    CHECK(balance(g, 1) == 0);
}

TEST_CASE("balance holds after the balancing pass, k = 1, 2, 3", "[octree][balance]")
{
    for (int k = 1; k <= 3; ++k)
        for (unsigned seed = 1; seed <= 12; ++seed) {
            INFO("k = " << k << ", seed = " << seed);
            auto g = testing::random_adaptive(seed, k, 18, 4);
            const int reported = max_level_difference(*g);
            CHECK(reported <= k);
            CHECK(reported == brute_force_max_difference(*g));
            CHECK(balance(*g, k) == 0); // idempotent
            // Cell count bookkeeping: level histogram covers the domain exactly.
            std::uint64_t vol = 0;
            const auto h = g->level_histogram();
            for (std::size_t l = 0; l < h.size(); ++l) vol += h[l] << (3 * l);
            CHECK(vol == g->unit_cells().volume());
        }
}

TEST_CASE("an unbalanced refinement is detected and fixed", "[octree][balance]")
{
    auto s = testing::random_samples(16, 3);
    AdaptiveGrid g(s, 1);
    g.set_leaf({openvdb::Coord(0, 0, 0), 3}, true); // level 3 next to level-0 cells
    CHECK(max_level_difference(g) == 3);
    CHECK(brute_force_max_difference(g) == 3);
    const auto splits = balance(g, 1);
    CHECK(splits > 0);
    CHECK(max_level_difference(g) <= 1);
    CHECK(brute_force_max_difference(g) <= 1);
}
