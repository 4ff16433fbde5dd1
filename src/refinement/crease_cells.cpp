#include "refinement/crease_cells.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace isodel::mesher {

CreaseBuckets bucket_triangles(const std::vector<CreaseTriangle>& tris, const CellSet& cells, std::size_t n_cells,
                               double margin, const std::vector<openvdb::Coord>& blocks)
{
    CreaseBuckets out;
    out.n_near.assign(tris.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tris.size(), 4096), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i)
            for_each_cell_near(tris[i].lo, tris[i].hi, cells, margin, blocks, [&](std::uint32_t) { ++out.n_near[i]; });
    });
    // The (triangle, cell) pairs, triangle by triangle, then a counting sort by cell: each
    // bucket lists its triangles in triangle order whatever the thread count.
    std::vector<std::size_t> pair_at(tris.size() + 1, 0);
    for (std::size_t i = 0; i < tris.size(); ++i) pair_at[i + 1] = pair_at[i] + out.n_near[i];
    std::vector<std::uint32_t> pair_cell(pair_at.back());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tris.size(), 4096), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            if (out.n_near[i] == 0) continue;
            std::size_t at = pair_at[i];
            for_each_cell_near(tris[i].lo, tris[i].hi, cells, margin, blocks,
                               [&](std::uint32_t ti) { pair_cell[at++] = ti; });
        }
    });
    out.at.assign(n_cells + 1, 0);
    for (const std::uint32_t ti : pair_cell) ++out.at[ti + 1];
    for (std::size_t ti = 0; ti < n_cells; ++ti) out.at[ti + 1] += out.at[ti];
    out.list.resize(pair_cell.size());
    std::vector<std::size_t> fill(out.at.begin(), out.at.end() - 1);
    for (std::size_t i = 0; i < tris.size(); ++i)
        for (std::size_t k = pair_at[i]; k < pair_at[i + 1]; ++k) out.list[fill[pair_cell[k]]++] = std::uint32_t(i);
    return out;
}

} // namespace isodel::mesher
