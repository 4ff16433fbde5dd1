#pragma once
// Internal: sets of voxels (E's crossed cells, G) built in parallel and listed in a fixed order,
// the iteration order of an OpenVDB MaskTree holding them. That order is a function of the set
// alone (root table by coordinate, then child offsets, then voxel offsets), so per-thread masks
// joined by a topology union list the same voxels in the same order at any thread count, and a
// sorted list with the same order (vdb_order_less) lists them the same way without any tree,
// as does a bitmap over the set's box read block by block in that order (voxel_bitmap.h).
#include "octree/voxel_bitmap.h"
#include "octree/voxel_order.h"

#include <openvdb/openvdb.h>
#include <openvdb/tree/LeafManager.h>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace isodel::octree {

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
        for (std::size_t i = r.begin(); i != r.end(); ++i) keys[i] = vdb_order::key(origins, voxels[i]);
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
    enum class Built { Bitmap, Sorted, Masks };
    std::vector<openvdb::Coord> coords; ///< each voxel once, in vdb_order_less order
    openvdb::MaskGrid::Ptr mask;        ///< the same set when it was built in masks, else null
    Built built = Built::Sorted;        ///< which of the three ways made it (the list is the same)
};

/// Few marks are sorted rather than put in a tree: a MaskTree costs its internal nodes' tables
/// (a quarter of a megabyte zeroed, and paged in, per top-level node touched, per thread)
/// however few voxels it holds, which dominates a small volume's whole run; a small volume
/// around the origin touches eight top-level nodes.
constexpr std::size_t kSortedVoxelSetMarks = std::size_t(1) << 16;
/// A box of at most kBitmapVoxels voxels (16 MiB of bits), counted in whole 8^3 blocks as the
/// bitmap holds it, and at most kBitsPerMark voxels per mark (8 bytes per mark, less than a
/// sorted mark's coordinates), is marked as bits (voxel_bitmap.h): no sort, no tree, and every
/// thread marks.
constexpr std::uint64_t kBitmapVoxels = std::uint64_t(1) << 27, kBitsPerMark = 64;

/// The smallest box holding \p box_of(i) for every i in [0, n), found in parallel (a union of
/// boxes, the same in any order); empty when n is 0.
template <typename BoxOf>
openvdb::CoordBBox union_of_boxes(std::size_t n, const BoxOf& box_of)
{
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, n, 4096), openvdb::CoordBBox(),
        [&](const tbb::blocked_range<std::size_t>& r, openvdb::CoordBBox box) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) box.expand(box_of(i));
            return box;
        },
        [](openvdb::CoordBBox a, const openvdb::CoordBBox& b) {
            a.expand(b);
            return a;
        });
}

/// The union over i in [0, n) of the voxels \p mark(i, sink) sets on with sink.setValueOn(c),
/// about \p marks_per_item each, all inside \p bounds: as bits when \p bounds is small enough
/// (every thread marking one bitmap), else sorted on one thread when there are few marks, else
/// marked in parallel into per-thread masks joined by a topology union.
template <typename Mark>
VoxelSet voxel_set(std::size_t n, std::size_t marks_per_item, const openvdb::CoordBBox& bounds, const Mark& mark)
{
    VoxelSet out;
    if (n == 0 || bounds.empty()) return out;
    const std::uint64_t marks = std::uint64_t(n) * marks_per_item;
    const std::uint64_t bitmap_voxels = VoxelBitmap::voxels_covering(bounds);
    if (bitmap_voxels <= kBitmapVoxels && bitmap_voxels <= kBitsPerMark * marks) {
        out.built = VoxelSet::Built::Bitmap;
        VoxelBitmap bits(bounds);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 64), [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) mark(i, bits);
        });
        out.coords = bits.coords();
        return out;
    }
    if (marks <= kSortedVoxelSetMarks) {
        struct Sink {
            std::vector<openvdb::Coord>& to;
            void setValueOn(const openvdb::Coord& c) { to.push_back(c); }
        } sink{out.coords};
        for (std::size_t i = 0; i < n; ++i) mark(i, sink);
        out.coords = sorted_in_vdb_order(out.coords);
        return out;
    }
    out.built = VoxelSet::Built::Masks;
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
