#pragma once
// Internal: a set of voxels within a known box as one bit per voxel, marked from any number of
// threads and listed in a MaskTree's iteration order (voxel_set.h). The bits of each 8^3 block
// are laid out as an OpenVDB leaf's value mask (offset = x-major within the leaf), and the
// blocks are listed in the order a tree visits its leaves (top-level origin, then the offsets
// in the top and middle nodes), so the list is the one a mask of the same voxels gives, with
// no tree: no node tables to zero, no per-thread trees to join. The union of bits is the same
// whatever thread sets which, so the list is the same at any thread count.
#include "octree/voxel_order.h"

#include <openvdb/openvdb.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <bitset>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

namespace isodel::octree {

class VoxelBitmap {
public:
    /// Bits for every voxel of \p box (not empty), all clear; the box is widened to whole 8^3 blocks.
    explicit VoxelBitmap(const openvdb::CoordBBox& box)
        : lo_(box.min() & ~(kLeafDim - 1)), blocks_(blocks_covering(box)),
          count_(std::size_t(blocks_.x()) * blocks_.y() * blocks_.z()), words_(new std::atomic<std::uint64_t>[count_ * 8])
    {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count_ * 8, 1 << 14), [&](const auto& r) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) words_[i].store(0, std::memory_order_relaxed);
        });
    }

    /// The voxels a bitmap of \p box holds: its whole 8^3 blocks.
    static std::uint64_t voxels_covering(const openvdb::CoordBBox& box)
    {
        const openvdb::Coord b = blocks_covering(box);
        return std::uint64_t(b.x()) * std::uint64_t(b.y()) * std::uint64_t(b.z()) * (kLeafDim * kLeafDim * kLeafDim);
    }

    /// Sets voxel \p c (inside the box); safe from several threads at once. \throw
    /// std::logic_error for a voxel outside the box (a caller's bounds were wrong).
    void setValueOn(const openvdb::Coord& c)
    {
        const openvdb::Coord d = c - lo_;
        if (d.x() < 0 || d.y() < 0 || d.z() < 0 || (d.x() >> kLeafLog2) >= blocks_.x() ||
            (d.y() >> kLeafLog2) >= blocks_.y() || (d.z() >> kLeafLog2) >= blocks_.z())
            throw std::logic_error("voxel bitmap: a mark outside the box its caller gave");
        const std::size_t block = (std::size_t(d.x() >> kLeafLog2) * blocks_.y() + std::size_t(d.y() >> kLeafLog2)) * blocks_.z() +
                                  std::size_t(d.z() >> kLeafLog2);
        std::atomic<std::uint64_t>& word = words_[block * 8 + std::size_t(d.x() & (kLeafDim - 1))];
        const std::uint64_t bit = std::uint64_t(1) << (((d.y() & (kLeafDim - 1)) << kLeafLog2) | (d.z() & (kLeafDim - 1)));
        // Most marks repeat a voxel already set (neighbouring cells share their corners): a
        // load is cheaper than a locked read-modify-write.
        if (!(word.load(std::memory_order_relaxed) & bit)) word.fetch_or(bit, std::memory_order_relaxed);
    }

    /// The voxels set, in a MaskTree's iteration order (vdb_order_less), each once. Call after
    /// every mark has been made.
    std::vector<openvdb::Coord> coords() const
    {
        // The occupied blocks in the order a tree visits its leaves, by vdb_order::key.
        std::vector<std::size_t> count(count_);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count_, 256), [&](const auto& r) {
            for (std::size_t b = r.begin(); b != r.end(); ++b) {
                std::size_t n = 0;
                for (int w = 0; w < 8; ++w) n += std::bitset<64>(words_[b * 8 + w].load(std::memory_order_relaxed)).count();
                count[b] = n;
            }
        });
        // Every top-level origin between the box's two corners, in root order.
        const openvdb::Coord o0 = vdb_order::origin(lo_), o1 = vdb_order::origin(block_origin(count_ - 1));
        constexpr std::int64_t step = vdb_order::Top::DIM;
        std::vector<openvdb::Coord> origins;
        for (std::int64_t x = o0.x(); x <= o1.x(); x += step)
            for (std::int64_t y = o0.y(); y <= o1.y(); y += step)
                for (std::int64_t z = o0.z(); z <= o1.z(); z += step) origins.emplace_back(int(x), int(y), int(z));
        std::sort(origins.begin(), origins.end());
        std::vector<std::pair<std::uint64_t, std::size_t>> order; // (key, block)
        for (std::size_t b = 0; b < count_; ++b)
            if (count[b]) order.emplace_back(vdb_order::key(origins, block_origin(b)), b);
        std::sort(order.begin(), order.end());
        std::vector<std::size_t> first(order.size() + 1, 0);
        for (std::size_t i = 0; i < order.size(); ++i) first[i + 1] = first[i] + count[order[i].second];
        std::vector<openvdb::Coord> out(first.back());
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, order.size(), 64), [&](const auto& r) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) {
                const std::size_t b = order[i].second;
                const openvdb::Coord o = block_origin(b);
                std::size_t k = first[i];
                // Ascending bits are ascending leaf offsets: the leaf's own iteration order.
                for (int w = 0; w < 8; ++w)
                    for (std::uint64_t bits = words_[b * 8 + w].load(std::memory_order_relaxed); bits; bits &= bits - 1) {
                        const int bit = __builtin_ctzll(bits);
                        out[k++] = o.offsetBy(w, bit >> kLeafLog2, bit & (kLeafDim - 1));
                    }
            }
        });
        return out;
    }

private:
    static constexpr int kLeafLog2 = 3, kLeafDim = 1 << kLeafLog2;
    static_assert(vdb_order::Leaf::LOG2DIM == kLeafLog2, "blocks are OpenVDB leaves");

    /// The 8^3 blocks along each axis that \p box (not empty) meets.
    static openvdb::Coord blocks_covering(const openvdb::CoordBBox& box)
    {
        return (((box.max() & ~(kLeafDim - 1)) - (box.min() & ~(kLeafDim - 1))) >> kLeafLog2) + openvdb::Coord(1);
    }

    openvdb::Coord block_origin(std::size_t b) const
    {
        const std::size_t z = b % blocks_.z(), y = (b / blocks_.z()) % blocks_.y(), x = b / (std::size_t(blocks_.z()) * blocks_.y());
        return lo_.offsetBy(int(x) * kLeafDim, int(y) * kLeafDim, int(z) * kLeafDim);
    }

    openvdb::Coord lo_;     ///< the first block's origin
    openvdb::Coord blocks_; ///< blocks along each axis
    std::size_t count_;     ///< blocks in all
    std::unique_ptr<std::atomic<std::uint64_t>[]> words_; ///< 8 words (512 bits) per block
};

} // namespace isodel::octree
