#pragma once
// Internal: the index behind the crease check (hausdorff_creases.cpp). The check asks, for
// each crease sample s of a crossed cell, whether some triangle of M lies within the threshold
// of s. A triangle can only pass s when its index-space box, grown by the threshold (in index
// units), meets s's cell; so each cell to check gets a bucket of the triangles whose grown box
// meets it, and only those are tried. When few cells are to be checked (later calls recheck a
// few cells of many), most triangles are nowhere near one: the 8^3 blocks holding a cell to
// check let a triangle's box be dismissed with one look-up per block instead of one per cell.
//
// The bucket of a cell has every triangle within the threshold of the cell, so its size grows
// with the threshold cubed in cells; the crease check uses the buckets only while the grown
// boxes span a few cells (crease_bucket_margin) and an AABB tree of M otherwise.
#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace isodel::mesher {

/// A triangle of M as the crease check reads it: a pure function of its facet's key (vertices
/// in id order), so a facet still in M keeps its triangle from one call to the next.
struct CreaseTriangle {
    openvdb::Vec3d a, b, c; ///< world
    openvdb::Vec3d lo, hi;  ///< bounding box in index space
};

/// Cells (lower corners) with their index in the list of cells to check, sorted by cell.
using CellSet = std::vector<std::pair<openvdb::Coord, std::uint32_t>>;

/// Grown boxes wider than this many index units per side of a triangle's box make buckets cost
/// more than an AABB tree query per sample: the crease check then measures with the tree.
constexpr double crease_bucket_margin = 2.0;

/// The 8^3 block holding cell \p c (floor division, also for negative coordinates).
inline openvdb::Coord block_of(const openvdb::Coord& c)
{
    const auto down = [](int x) { return x >= 0 ? x / 8 : -((7 - x) / 8); };
    return openvdb::Coord(down(c[0]), down(c[1]), down(c[2]));
}

/// Calls f(index) for each cell of \p cells that the index-space box [lo, hi], grown by
/// \p margin, meets. \p blocks: the sorted blocks (block_of) holding a cell of \p cells, or
/// empty; when given, a box that meets none of them meets no cell and is skipped whole.
template <class F>
void for_each_cell_near(const openvdb::Vec3d& lo, const openvdb::Vec3d& hi, const CellSet& cells, double margin,
                        const std::vector<openvdb::Coord>& blocks, F&& f)
{
    // Cells [c, c + 1] meeting the box [lo - margin, hi + margin].
    const openvdb::Coord a(int(std::ceil(lo[0] - margin)) - 1, int(std::ceil(lo[1] - margin)) - 1,
                           int(std::ceil(lo[2] - margin)) - 1);
    const openvdb::Coord b(int(std::floor(hi[0] + margin)), int(std::floor(hi[1] + margin)),
                           int(std::floor(hi[2] + margin)));
    if (!blocks.empty()) {
        const openvdb::Coord ba = block_of(a), bb = block_of(b);
        bool any = false;
        for (int x = ba[0]; x <= bb[0] && !any; ++x)
            for (int y = ba[1]; y <= bb[1] && !any; ++y)
                for (int z = ba[2]; z <= bb[2] && !any; ++z)
                    any = std::binary_search(blocks.begin(), blocks.end(), openvdb::Coord(x, y, z));
        if (!any) return;
    }
    for (int x = a[0]; x <= b[0]; ++x)
        for (int y = a[1]; y <= b[1]; ++y)
            for (int z = a[2]; z <= b[2]; ++z) {
                const openvdb::Coord c(x, y, z);
                const auto it = std::lower_bound(cells.begin(), cells.end(), c,
                                                 [](const auto& e, const openvdb::Coord& k) { return e.first < k; });
                if (it != cells.end() && it->first == c) f(it->second);
            }
}

/// Each cell's bucket: the triangles whose box, grown by the margin, meets the cell, in
/// triangle order.
struct CreaseBuckets {
    std::vector<std::uint32_t> n_near; ///< per triangle: how many cells to check its grown box meets
    std::vector<std::size_t> at;       ///< the bucket of cell ti is list[at[ti] .. at[ti + 1])
    std::vector<std::uint32_t> list;   ///< triangle indices
};

/// Buckets for the \p n_cells cells of \p cells (indices 0 .. n_cells - 1), in parallel; the
/// same lists at any thread count.
CreaseBuckets bucket_triangles(const std::vector<CreaseTriangle>& tris, const CellSet& cells, std::size_t n_cells,
                               double margin, const std::vector<openvdb::Coord>& blocks);

} // namespace isodel::mesher
