#include "octree/balance.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <climits>

namespace isodel::octree {

namespace {

bool overlaps(const CoordBBox& cells, const CellId& b) // unit-cell box vs cell b
{
    for (int ax = 0; ax < 3; ++ax)
        if (b.origin[ax] + b.size() - 1 < cells.min()[ax] || b.origin[ax] > cells.max()[ax])
            return false;
    return true;
}

bool contained(const CoordBBox& cells, const CellId& b)
{
    return cells.isInside(b.origin) && cells.isInside(b.origin.offsetBy(b.size() - 1));
}

// Min leaf level in box b (an aligned cell-sized box touching c) among leaves touching c.
void visit(const AdaptiveGrid::Reader& r, const CoordBBox& cells, const CellId& c, const CellId& b,
           int stop_at, int& best)
{
    if (best <= stop_at || !overlaps(cells, b)) return;
    const int q = r.leaf_level(b.origin);
    if (q >= b.level) { // b lies in one leaf of level q
        best = std::min(best, q);
        return;
    }
    if (q >= 0 && b.level - 1 <= stop_at && contained(cells, b)) {
        // b is subdivided, so the leaf of b at the contact with c has level <= b.level - 1.
        best = std::min(best, b.level - 1);
        return;
    }
    if (b.level == 0) return; // unit cell outside the domain
    const int h = b.size() / 2;
    const CoordBBox cn = c.nodes();
    for (int m = 0; m < 8; ++m) {
        const CellId ch{b.origin.offsetBy((m & 1) * h, ((m >> 1) & 1) * h, ((m >> 2) & 1) * h),
                        b.level - 1};
        if (boxes_touch(ch.nodes(), cn)) visit(r, cells, c, ch, stop_at, best);
    }
}
} // namespace

int min_touching_level(const AdaptiveGrid::Reader& r, const CellId& c, int stop_at)
{
    // The 26 same-size boxes around c cover every point touching c; a leaf of level >= c.level
    // touching c contains one of them (alignment), finer leaves lie inside one of them.
    int best = INT_MAX;
    const CoordBBox cells = r.grid().unit_cells();
    const int s = c.size();
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                if (!dx && !dy && !dz) continue;
                visit(r, cells, c, CellId{c.origin.offsetBy(dx * s, dy * s, dz * s), c.level},
                      stop_at, best);
                if (best <= stop_at) return best;
            }
    return best;
}

bool may_merge(const AdaptiveGrid::Reader& r, const CellId& p, int k)
{
    if (!r.grid().inside(p)) return false;
    const int h = p.size() / 2;
    for (int m = 0; m < 8; ++m)
        if (!r.is_leaf({p.origin.offsetBy((m & 1) * h, ((m >> 1) & 1) * h, ((m >> 2) & 1) * h), p.level - 1}))
            return false;
    return !(p.level > k && touches_finer_than(r, p, p.level - k));
}

std::size_t merge_flagged(AdaptiveGrid& g, const std::vector<CellId>& candidates, const std::vector<char>& flags)
{
    std::size_t merged = 0;
    for (std::size_t i = 0; i < candidates.size(); ++i)
        if (flags[i]) {
            g.merge(candidates[i]);
            ++merged;
        }
    return merged;
}

int max_level_difference(const AdaptiveGrid& g)
{
    std::atomic<int> worst{0};
    for (int l = 1; l <= g.max_level(); ++l) {
        const auto leaves = g.leaves(l);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.size(), 256),
                          [&](const tbb::blocked_range<std::size_t>& rg) {
                              AdaptiveGrid::Reader r(g);
                              int w = 0;
                              for (std::size_t i = rg.begin(); i < rg.end(); ++i) {
                                  const int m = min_touching_level(r, leaves[i], -1);
                                  if (m != INT_MAX) w = std::max(w, l - m);
                              }
                              int cur = worst.load();
                              while (w > cur && !worst.compare_exchange_weak(cur, w)) {}
                          });
    }
    return worst.load();
}

std::size_t balance(AdaptiveGrid& g, int k)
{
    // Coarse to fine, repeated to a fixed point: a split at level l creates level l-1 leaves that
    // are checked in the same sweep; a later split at a finer level may invalidate a coarser leaf
    // only by one level, which the next sweep fixes. Only refines, so it terminates.
    g.set_k(k);
    std::size_t splits = 0;
    for (bool changed = true; changed;) {
        changed = false;
        for (int l = g.max_level(); l > k; --l) {
            const auto leaves = g.leaves(l);
            std::vector<char> bad(leaves.size(), 0);
            tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.size(), 64),
                              [&](const tbb::blocked_range<std::size_t>& rg) {
                                  AdaptiveGrid::Reader r(g);
                                  for (std::size_t i = rg.begin(); i < rg.end(); ++i)
                                      bad[i] = touches_finer_than(r, leaves[i], l - k);
                              });
            for (std::size_t i = 0; i < leaves.size(); ++i)
                if (bad[i]) {
                    g.split(leaves[i]);
                    ++splits;
                    changed = true;
                }
        }
    }
    g.trim_levels();
    return splits;
}

std::vector<CellId> merge_candidates(const AdaptiveGrid& g, int l)
{
    std::vector<CellId> out;
    if (l == 1) {
        // Only cells touching allocated samples can differ from their neighbours; constant
        // regions (tiles, background) stay level 0, which costs no storage.
        for (const Coord& u : value_cells_sparse(g)) out.push_back({align_down(u, 1), 1});
    } else {
        for (const CellId& c : g.leaves(l - 1)) out.push_back({align_down(c.origin, l), l});
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

} // namespace isodel::octree
