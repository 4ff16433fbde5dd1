#pragma once
// Internal: sets of voxels (E's crossed cells, G) built in parallel and listed in a fixed order.
// A MaskGrid's iteration order is a function of its set of active voxels alone (root table by
// coordinate, then child offsets, then voxel offsets), so per-thread masks joined by a
// topology union list the same voxels in the same order at any thread count.
#include <openvdb/openvdb.h>
#include <openvdb/tree/LeafManager.h>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <cstddef>
#include <vector>

namespace isodel::octree {

/// The union over i in [0, n) of the voxels \p mark(i, accessor) sets on, marked in parallel.
/// \p mark sets voxels only with setValueOn (no tiles), which coords_of relies on.
template <typename Mark>
openvdb::MaskGrid::Ptr parallel_mask(std::size_t n, const Mark& mark)
{
    auto out = openvdb::MaskGrid::create();
    // Each tree costs its internal nodes' tables (~0.3 MB zeroed) however few voxels it holds:
    // few items are marked on one thread, into the result directly.
    if (n < 4096) {
        auto acc = out->getAccessor();
        for (std::size_t i = 0; i < n; ++i) mark(i, acc);
        return out;
    }
    tbb::enumerable_thread_specific<openvdb::MaskTree> local;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256), [&](const tbb::blocked_range<std::size_t>& r) {
        openvdb::tree::ValueAccessor<openvdb::MaskTree> acc(local.local());
        for (std::size_t i = r.begin(); i != r.end(); ++i) mark(i, acc);
    });
    for (auto& t : local) out->tree().topologyUnion(t);
    return out;
}

/// The active voxels of a mask without tiles, in its iteration order, listed in parallel: the
/// leaf manager holds the leaves in iteration order, and each leaf writes at its prefix offset.
inline std::vector<openvdb::Coord> coords_of(const openvdb::MaskTree& mask)
{
    if (mask.activeTileCount() > 0) { // not made by parallel_mask: list the tiles' voxels too
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

} // namespace isodel::octree
