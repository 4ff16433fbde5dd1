#pragma once
/// \file adaptive_grid.h
/// The adaptive (octree) grid of isodel, stored with OpenVDB (paper Section 4.2, "adaptive gridding
/// in an octree construction"; Property IV).
///
///  - Samples: one openvdb::FloatGrid at the finest resolution; sample (i,j,k) at index (i,j,k).
///    Only the corner samples of leaf cells are read (hanging nodes are derived, see interpolant.h).
///  - Cells: a level-l leaf cell spans 2^l voxels per axis, its origin aligned to 2^l. Level l >= 1
///    is one openvdb::MaskGrid whose voxel (o >> l) is on iff the cell with origin o is a leaf, so
///    a level stores one bit per cell of its own lattice (its transform is the sample transform
///    scaled by 2^l, so viewers draw it in place). Level 0 is never stored: a unit cell is a level-0
///    leaf iff no coarser leaf covers it. A uniform grid therefore has no mask at all and costs
///    nothing beyond the sample grid.
///  - Domain: the samples of domain() = active bounding box grown by one voxel (the rule of
///    sample_field.h); every leaf cell lies inside it. The domain is stored, not re-derived, so
///    pruning samples of a decimated grid cannot move it. The ring always reads the background
///    here; SampleField reads it as "outside" when the background is at or inside v (a dense
///    file's 0 at v = 0), so decimating such a grid meshes its ring differently (known gap).
///
/// Sparse volumes (narrow-band level sets) are never densified: masks and samples stay sparse,
/// and value_cells_sparse() lists only the unit cells that touch allocated sample nodes.
#include <openvdb/openvdb.h>

#include <cstdint>
#include <optional>
#include <vector>

namespace isodel::octree {

using openvdb::Coord;
using openvdb::CoordBBox;

/// floor(x / 2^l) (arithmetic shift: floor for negatives with GCC/Clang, guaranteed in C++20).
inline int shift_down(int x, int l) { return x >> l; }
/// x rounded down to a multiple of 2^l (two's complement mask, valid for negatives).
inline int align_down(int x, int l) { return x & ~((1 << l) - 1); }
inline Coord align_down(const Coord& c, int l)
{
    return Coord(align_down(c.x(), l), align_down(c.y(), l), align_down(c.z(), l));
}

/// True when two closed index boxes share at least a point (a corner, an edge, a face or more).
inline bool boxes_touch(const CoordBBox& a, const CoordBBox& b)
{
    for (int ax = 0; ax < 3; ++ax)
        if (a.max()[ax] < b.min()[ax] || b.max()[ax] < a.min()[ax]) return false;
    return true;
}

/// A cell: lowest corner (index space, aligned to 2^level) and level.
struct CellId {
    Coord origin;
    int level = 0;
    int size() const { return 1 << level; }
    /// Closed box of the sample nodes the cell spans (corners included).
    CoordBBox nodes() const { return CoordBBox(origin, origin.offsetBy(size())); }
    bool operator==(const CellId& o) const { return level == o.level && origin == o.origin; }
    bool operator!=(const CellId& o) const { return !(*this == o); }
    bool operator<(const CellId& o) const
    {
        return level != o.level ? level < o.level : origin < o.origin;
    }
};

class AdaptiveGrid {
public:
    static constexpr int kMaxLevel = 15;

    /// The uniform (one-level) grid over \p samples: O(1) work beyond the active bounding box.
    explicit AdaptiveGrid(openvdb::FloatGrid::ConstPtr samples, int k = 1);
    /// A grid with explicit domain and level masks (masks[l] for l >= 1; masks[0] is ignored).
    AdaptiveGrid(openvdb::FloatGrid::ConstPtr samples, const CoordBBox& domain,
                 std::vector<openvdb::MaskGrid::Ptr> masks, int k);

    const openvdb::FloatGrid& samples() const { return *samples_; }
    openvdb::FloatGrid::ConstPtr samples_ptr() const { return samples_; }
    void set_samples(openvdb::FloatGrid::ConstPtr s) { samples_ = std::move(s); }
    /// Closed box of the samples read through the grid (active bbox grown by one voxel).
    const CoordBBox& domain() const { return domain_; }
    /// Origins of the unit cells of the domain.
    CoordBBox unit_cells() const { return CoordBBox(domain_.min(), domain_.max().offsetBy(-1)); }
    /// True when the closed span of \p c lies in the domain (every leaf does).
    bool inside(const CellId& c) const;

    /// Largest level that may hold leaves (0 for a uniform grid).
    int max_level() const { return int(masks_.size()) - 1; }
    /// Balance bound: adjacent leaves differ by at most k levels (see balance.h).
    int k() const { return k_; }
    void set_k(int k) { k_ = k; }

    /// The mask of level l >= 1 (voxel o >> l on = leaf with origin o), or null.
    openvdb::MaskGrid::ConstPtr mask(int level) const;
    /// Sets or clears the leaf bit of a level >= 1 cell (creates the level's mask if needed).
    void set_leaf(const CellId& c, bool on);
    /// Replaces the leaf \p c (level >= 1) by its 8 children.
    void split(const CellId& c);
    /// Replaces the 8 children of \p parent (all leaves at parent.level - 1) by \p parent.
    void merge(const CellId& parent);
    /// Drops empty top levels.
    void trim_levels();
    /// All leaves of one level >= 1, sorted.
    std::vector<CellId> leaves(int level) const;

    /// Leaves per level; level 0 is derived: domain cells minus the cells coarser leaves cover.
    std::vector<std::uint64_t> level_histogram() const;
    std::uint64_t cell_count() const;
    /// Bytes held by the samples and the masks (OpenVDB memUsage()).
    std::size_t memory_bytes() const;
    const std::vector<openvdb::MaskGrid::Ptr>& masks() const { return masks_; }

    /// Per-thread lookups (owns OpenVDB accessors, which are not thread-safe). Create it after the
    /// structure is final: it does not see levels added later.
    class Reader {
    public:
        explicit Reader(const AdaptiveGrid& g);
        const AdaptiveGrid& grid() const { return *g_; }
        /// Level of the leaf covering unit cell \p u, or -1 outside the domain. Cost: one mask
        /// lookup per level >= 1 (none for a uniform grid).
        int leaf_level(const Coord& u) const;
        std::optional<CellId> leaf(const Coord& u) const;
        bool is_leaf(const CellId& c) const;
        /// Raw sample read through the grid (background / tile values for inactive voxels).
        float sample(const Coord& ijk) const { return acc_.getValue(ijk); }

    private:
        const AdaptiveGrid* g_;
        mutable openvdb::FloatGrid::ConstAccessor acc_;
        mutable std::vector<openvdb::MaskGrid::ConstAccessor> masks_; // index l - 1
    };

private:
    openvdb::FloatGrid::ConstPtr samples_;
    CoordBBox domain_;
    std::vector<openvdb::MaskGrid::Ptr> masks_; // masks_[0] always null
    int k_ = 1;
};

/// The unit cells whose corners touch an allocated leaf node of the samples, i.e. the only cells
/// whose corner values can differ, clipped to the domain (cells inside one tile or the background
/// are constant). Sorted, unique. This is how sparse level sets avoid dense loops.
std::vector<Coord> value_cells_sparse(const AdaptiveGrid& g);

} // namespace isodel::octree
