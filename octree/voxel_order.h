#pragma once
// Internal: a MaskTree's iteration order of voxels (root table by coordinate, then child
// offsets, then voxel offsets), a function of the set alone: the order in which G and E's
// crossed cells are listed (voxel_set.h), whatever builds the set.
#include <openvdb/openvdb.h>

#include <algorithm>
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
/// \p c's 64-bit key: the rank of its top-level origin among \p origins (sorted, holding it)
/// above its offsets. Keys sort as vdb_order_less, and voxel(origins[key >> kOffsetBits],
/// key & offset mask) gives \p c back.
inline std::uint64_t key(const std::vector<openvdb::Coord>& origins, const openvdb::Coord& c)
{
    const auto rank = std::uint64_t(std::lower_bound(origins.begin(), origins.end(), origin(c)) - origins.begin());
    return rank << kOffsetBits | offsets(c);
}
} // namespace vdb_order

/// Whether \p a comes before \p b in a MaskTree's iteration order.
inline bool vdb_order_less(const openvdb::Coord& a, const openvdb::Coord& b)
{
    const openvdb::Coord oa = vdb_order::origin(a), ob = vdb_order::origin(b);
    return oa < ob || (oa == ob && vdb_order::offsets(a) < vdb_order::offsets(b));
}

} // namespace isodel::octree
