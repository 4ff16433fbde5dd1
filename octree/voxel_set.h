#pragma once
// Internal: sets of voxels (E's crossed cells, G) built in parallel and listed in a fixed order,
// the iteration order of an OpenVDB MaskTree holding them. That order is a function of the set
// alone (root table by coordinate, then child offsets, then voxel offsets), so per-thread masks
// joined by a topology union list the same voxels in the same order at any thread count, and a
// sorted list with the same order (vdb_order_less) lists them the same way without any tree.
#include <openvdb/openvdb.h>
#include <openvdb/tree/LeafManager.h>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace isodel::octree {

/// The position of voxel \p c in a MaskTree's iteration order, as a key compared
/// lexicographically: the top-level node's origin (the root table is ordered by it), then the
/// offsets within the top node, the middle node and the leaf, each x-major as OpenVDB's
/// coordToOffset numbers them.
struct VdbOrderKey {
    openvdb::Coord origin;
    std::uint64_t offsets = 0;

    explicit VdbOrderKey(const openvdb::Coord& c)
    {
        using Top = openvdb::MaskTree::RootNodeType::ChildNodeType;
        using Middle = Top::ChildNodeType;
        using Leaf = Middle::ChildNodeType;
        origin = c & ~(Top::DIM - 1);
        offsets = (std::uint64_t(Top::coordToOffset(c)) << (3 * (Middle::LOG2DIM + Leaf::LOG2DIM))) |
                  (std::uint64_t(Middle::coordToOffset(c)) << (3 * Leaf::LOG2DIM)) | Leaf::coordToOffset(c);
    }
    bool operator<(const VdbOrderKey& o) const { return origin < o.origin || (origin == o.origin && offsets < o.offsets); }
};

inline bool vdb_order_less(const openvdb::Coord& a, const openvdb::Coord& b) { return VdbOrderKey(a) < VdbOrderKey(b); }

/// The active voxels of a mask without tiles, in its iteration order, listed in parallel: the
/// leaf manager holds the leaves in iteration order, and each leaf writes at its prefix offset.
inline std::vector<openvdb::Coord> coords_of(const openvdb::MaskTree& mask)
{
    if (mask.activeTileCount() > 0) { // not made by voxel_set: list the tiles' voxels too
        openvdb::MaskTree voxels(mask);
        voxels.voxelizeActiveTiles();
        return coords_of(voxels);
    }
    openvdb::tree::LeafManager<const openvdb::MaskTree> leaves(mask);
    std::vector<std::size_t> offset(leaves.leafCount() + 1, 0);
    for (std::size_t i = 0; i < leaves.leafCount(); ++i) offset[i + 1] = offset[i] + leaves.leaf(i).onVoxelCount();
    std::vector<openvdb::Coord> out(offset.back());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.leafCount(), 64), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            std::size_t k = offset[i];
            for (auto v = leaves.leaf(i).cbeginValueOn(); v; ++v) out[k++] = v.getCoord();
        }
    });
    return out;
}

/// A set of voxels in MaskTree order, and the mask itself when it was built as one.
struct VoxelSet {
    std::vector<openvdb::Coord> coords; ///< each voxel once, in vdb_order_less order
    openvdb::MaskGrid::Ptr mask;        ///< the same set; null when it was built by sorting
};

/// Few marks are sorted rather than put in a tree: a MaskTree costs its internal nodes' tables
/// (a quarter of a megabyte zeroed, and paged in, per top-level node touched) however few
/// voxels it holds, which dominates a small volume's whole run.
constexpr std::size_t kSortedVoxelSetMarks = 4096;

/// The union over i in [0, n) of the voxels \p mark(i, sink) sets on with sink.setValueOn(c),
/// about \p marks_per_item each: sorted on one thread when there are few, else marked in
/// parallel into per-thread masks joined by a topology union.
template <typename Mark>
VoxelSet voxel_set(std::size_t n, std::size_t marks_per_item, const Mark& mark)
{
    VoxelSet out;
    if (n * marks_per_item <= kSortedVoxelSetMarks) {
        struct Sink {
            std::vector<openvdb::Coord>& to;
            void setValueOn(const openvdb::Coord& c) { to.push_back(c); }
        } sink{out.coords};
        for (std::size_t i = 0; i < n; ++i) mark(i, sink);
        std::vector<std::pair<VdbOrderKey, openvdb::Coord>> keyed;
        keyed.reserve(out.coords.size());
        for (const openvdb::Coord& c : out.coords) keyed.emplace_back(VdbOrderKey(c), c);
        std::sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        out.coords.clear();
        for (std::size_t i = 0; i < keyed.size(); ++i)
            if (i == 0 || keyed[i].second != keyed[i - 1].second) out.coords.push_back(keyed[i].second);
        return out;
    }
    out.mask = openvdb::MaskGrid::create();
    tbb::enumerable_thread_specific<openvdb::MaskTree> local;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256), [&](const tbb::blocked_range<std::size_t>& r) {
        openvdb::tree::ValueAccessor<openvdb::MaskTree> acc(local.local());
        for (std::size_t i = r.begin(); i != r.end(); ++i) mark(i, acc);
    });
    for (auto& t : local) out.mask->tree().topologyUnion(t);
    out.coords = coords_of(out.mask->tree());
    return out;
}

} // namespace isodel::octree
