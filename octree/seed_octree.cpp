#include "octree/seed_octree.h"

#include "octree/balance.h"
#include "octree/far_field.h"
#include "octree/monotone_edges.h"

#include <isodel/errors.h>

#include <tbb/parallel_for.h>

#include <vector>

namespace isodel::octree {

bool seed_leaf_certified(const SampleField::Reader& f, const CellId& p)
{
    const int s = p.size();
    // Off Sigma: f keeps the corners' strict sign on every unit cell. Read without storing, and
    // stop at the first sign change: most candidates of a smooth volume are decided here.
    bool pos = false, neg = false;
    for (int k = 0; k <= s && !(pos && neg); ++k)
        for (int j = 0; j <= s && !(pos && neg); ++j)
            for (int i = 0; i <= s && !(pos && neg); ++i) (f.phi(p.origin.offsetBy(i, j, k)) > 0 ? pos : neg) = true;
    if (!(pos && neg)) return true;
    // A leaf that Sigma crosses is read whole, span and rim, so its edge bounds the memory.
    if (s > kMaxBandLeafVoxels) return false;

    // Nodes -1 .. s + 1 per axis: the span and its one-cell rim.
    const int n = s + 3;
    std::vector<double> phi(std::size_t(n) * n * n);
    auto idx = [n](int i, int j, int k) { return (std::size_t(k + 1) * n + (j + 1)) * n + (i + 1); };
    for (int k = -1; k <= s + 1; ++k)
        for (int j = -1; j <= s + 1; ++j)
            for (int i = -1; i <= s + 1; ++i) phi[idx(i, j, k)] = f.phi(p.origin.offsetBy(i, j, k));

    // Band cells of the span and the rim (cells -1 .. s per axis): the only ones Sigma meets.
    const int cells = s + 2;
    std::vector<char> band(std::size_t(cells) * cells * cells);
    auto cell = [cells](int i, int j, int k) { return (std::size_t(k + 1) * cells + (j + 1)) * cells + (i + 1); };
    for (int k = -1; k <= s; ++k)
        for (int j = -1; j <= s; ++j)
            for (int i = -1; i <= s; ++i) {
                bool p2 = false, n2 = false;
                for (int m = 0; m < 8; ++m)
                    (phi[idx(i + (m & 1), j + ((m >> 1) & 1), k + ((m >> 2) & 1))] > 0 ? p2 : n2) = true;
                band[cell(i, j, k)] = p2 && n2;
            }
    int monotone_axes = 0;
    for (int d = 0; d < 3; ++d) {
        Monotone mono;
        for (int k = -1; k <= s && mono.ok; ++k)
            for (int j = -1; j <= s && mono.ok; ++j)
                for (int i = -1; i <= s && mono.ok; ++i) {
                    if (!band[cell(i, j, k)]) continue;
                    for (int m = 0; m < 8; ++m) { // the cell's four d-edges: corners with bit d clear
                        if (m & (1 << d)) continue;
                        const int x = i + (m & 1), y = j + ((m >> 1) & 1), z = k + ((m >> 2) & 1);
                        mono.add(phi[idx(x + (d == 0), y + (d == 1), z + (d == 2))] - phi[idx(x, y, z)]);
                    }
                }
        monotone_axes += mono.ok && mono.sign != 0;
    }
    return monotone_axes >= 2;
}

AdaptiveGrid seed_octree(const SampleField& fine, const SeedOctreeOptions& options, Interrupter* intr)
{
    if (options.k < 1) throw InvalidInput("seed octree: k must be >= 1");
    if (options.max_level < 0 || options.max_level > AdaptiveGrid::kMaxLevel)
        throw InvalidInput("seed octree: max level must be in [0, 15]");
    AdaptiveGrid g(fine.grid_ptr(), options.k);
    coarsen_far_field(g, fine, options.max_level, intr);
    for (int l = 1; l <= options.max_level; ++l) {
        if (intr && intr->wasInterrupted(40 * l / std::max(1, options.max_level)))
            throw Cancelled("seed octree: interrupted");
        const auto cand = merge_candidates(g, l);
        std::vector<char> ok(cand.size(), 0);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cand.size(), 64),
                          [&](const tbb::blocked_range<std::size_t>& rg) {
                              AdaptiveGrid::Reader r(g);
                              SampleField::Reader f(fine);
                              for (std::size_t i = rg.begin(); i < rg.end(); ++i)
                                  if (may_merge(r, cand[i], options.k)) ok[i] = seed_leaf_certified(f, cand[i]);
                          });
        if (!merge_flagged(g, cand, ok)) break;
    }
    g.trim_levels();
    balance(g, options.k);
    return g;
}

} // namespace isodel::octree
