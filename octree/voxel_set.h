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
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace isodel::octree {

/// A voxel's position in a MaskTree's iteration order: the top-level node's origin (the root
/// table is ordered by it), then the offsets within the top node, the middle node and the leaf,
/// each x-major as OpenVDB's coordToOffset numbers them. The offsets (36 bits) locate the voxel
/// within its top node exactly, so a key made of an origin's rank and the offsets is also the
/// voxel itself.
namespace vdb_order {
using Top = openvdb::MaskTree::RootNodeType::ChildNodeType;
using Middle = Top::ChildNodeType;
using Leaf = Middle::ChildNodeType;
constexpr int kLeafBits = 3 * Leaf::LOG2DIM, kMiddleBits = 3 * Middle::LOG2DIM, kTopBits = 3 * Top::LOG2DIM;
constexpr int kOffsetBits = kTopBits + kMiddleBits + kLeafBits;

inline openvdb::Coord origin(const openvdb::Coord& c) { return c & ~(Top::DIM - 1); }
inline std::uint64_t offsets(const openvdb::Coord& c)
{
    return (std::uint64_t(Top::coordToOffset(c)) << (kMiddleBits + kLeafBits)) |
           (std::uint64_t(Middle::coordToOffset(c)) << kLeafBits) | Leaf::coordToOffset(c);
}
inline openvdb::Coord voxel(const openvdb::Coord& origin, std::uint64_t offsets)
{
    openvdb::Coord top, middle;
    Top::offsetToLocalCoord(openvdb::Index(offsets >> (kMiddleBits + kLeafBits)), top);
    Middle::offsetToLocalCoord(openvdb::Index((offsets >> kLeafBits) & ((1u << kMiddleBits) - 1)), middle);
    const openvdb::Coord leaf = Leaf::offsetToLocalCoord(openvdb::Index(offsets & ((1u << kLeafBits) - 1)));
    const auto scaled = [](const openvdb::Coord& c, int s) { return openvdb::Coord(c.x() * s, c.y() * s, c.z() * s); };
    return origin + scaled(top, int(Middle::DIM)) + scaled(middle, int(Leaf::DIM)) + leaf;
}
} // namespace vdb_order

/// Whether \p a comes before \p b in a MaskTree's iteration order.
inline bool vdb_order_less(const openvdb::Coord& a, const openvdb::Coord& b)
{
    const openvdb::Coord oa = vdb_order::origin(a), ob = vdb_order::origin(b);
    return oa < ob || (oa == ob && vdb_order::offsets(a) < vdb_order::offsets(b));
}

/// \p voxels, each once, sorted by vdb_order_less: 64-bit keys (the rank of the voxel's top
/// node among those touched, then its offsets) sorted as integers.
inline std::vector<openvdb::Coord> sorted_in_vdb_order(const std::vector<openvdb::Coord>& voxels)
{
    std::vector<openvdb::Coord> origins; // the top nodes touched, each once, in root order
    for (const openvdb::Coord& c : voxels) {
        const openvdb::Coord o = vdb_order::origin(c);
        if (origins.empty() || origins.back() != o) origins.push_back(o); // runs: neighbours share a node
    }
    std::sort(origins.begin(), origins.end());
    origins.erase(std::unique(origins.begin(), origins.end()), origins.end());
    // Keys in parallel and a parallel sort: equal keys are the same voxel, so the sorted list
    // is the same however the sort splits it.
    constexpr std::size_t grain = 4096;
    std::vector<std::uint64_t> keys(voxels.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, voxels.size(), grain), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const openvdb::Coord& c = voxels[i];
            const auto rank = std::uint64_t(std::lower_bound(origins.begin(), origins.end(), vdb_order::origin(c)) - origins.begin());
            keys[i] = rank << vdb_order::kOffsetBits | vdb_order::offsets(c);
        }
    });
    tbb::parallel_sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    std::vector<openvdb::Coord> out(keys.size());
    const std::uint64_t offset_mask = (std::uint64_t(1) << vdb_order::kOffsetBits) - 1;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, keys.size(), grain), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i)
            out[i] = vdb_order::voxel(origins[keys[i] >> vdb_order::kOffsetBits], keys[i] & offset_mask);
    });
    return out;
}

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
/// (a quarter of a megabyte zeroed, and paged in, per top-level node touched, per thread)
/// however few voxels it holds, which dominates a small volume's whole run; a small volume
/// around the origin touches eight top-level nodes.
constexpr std::size_t kSortedVoxelSetMarks = std::size_t(1) << 16;

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
        out.coords = sorted_in_vdb_order(out.coords);
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
