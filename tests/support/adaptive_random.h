#pragma once
// Random adaptive grids for the octree property tests (fixed seeds): random samples on an
// n^3 lattice, random top-down refinement from level L, then the balancing pass.
#include "octree/adaptive_grid.h"
#include "octree/balance.h"

#include <openvdb/openvdb.h>

#include <memory>
#include <random>
#include <string>

namespace isodel::octree::testing {

inline openvdb::FloatGrid::Ptr random_samples(int n, unsigned seed, bool smooth = false)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    auto g = openvdb::FloatGrid::create(0.f);
    auto acc = g->getAccessor();
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const float v = smooth ? float(std::sin(0.3 * x) + std::cos(0.25 * y) * 0.5 + 0.1 * z - 1.0) + 0.01f * u(rng)
                                       : u(rng);
                acc.setValueOn(openvdb::Coord(x, y, z), v);
            }
    g->setName("density");
    return g;
}

inline void refine_random(AdaptiveGrid& g, const CellId& c, std::mt19937& rng, double keep)
{
    if (!g.inside(c)) return;
    if (c.level == 0) return;
    if (std::uniform_real_distribution<double>(0, 1)(rng) < keep) {
        g.set_leaf(c, true);
        return;
    }
    const int h = c.size() / 2;
    for (int m = 0; m < 8; ++m)
        refine_random(g, {c.origin.offsetBy((m & 1) * h, ((m >> 1) & 1) * h, ((m >> 2) & 1) * h), c.level - 1},
                      rng, keep);
}

/// A random k-balanced adaptive grid over random samples on [0, n-1]^3 (domain [-1, n]^3).
inline std::unique_ptr<AdaptiveGrid> random_adaptive(unsigned seed, int k, int n = 20, int L = 3,
                                                     bool smooth = false)
{
    std::mt19937 rng(seed * 7919u + 13u);
    auto g = std::make_unique<AdaptiveGrid>(random_samples(n, seed, smooth), k);
    const int s = 1 << L;
    const double keep = std::uniform_real_distribution<double>(0.3, 0.7)(rng);
    for (int z = -s; z <= n; z += s)
        for (int y = -s; y <= n; y += s)
            for (int x = -s; x <= n; x += s) refine_random(*g, {openvdb::Coord(x, y, z), L}, rng, keep);
    balance(*g, k);
    return g;
}

} // namespace isodel::octree::testing
