#pragma once
// Internal: the tiles of a tree above the leaf level that hold something other than the
// background: active tiles, and inactive tiles of another value (a level set's inside). An
// inactive tile of the background value reads exactly as the background does, which every
// consumer accounts for on its own (sample_field.cpp, edge_crossings.cpp), so it is skipped.
//
// Why not the tree's value iterator: an internal node of the top level has 32^3 slots, nearly
// all inactive background tiles in a sparse or small grid, and the tree-level iterator costs
// tens of instructions per slot. Here a slot costs two mask tests and a compare, read from the
// node's own table, and only the slots whose boxes meet the caller's region are read: a small
// volume's node holds 32,768 slots of which it meets one or a few, and reading them all was a
// fixed cost of every run, whatever the volume's size.
#include <openvdb/openvdb.h>

#include <algorithm>
#include <cstdint>

namespace isodel::octree {

namespace detail {

/// The slots of a node with \p origin along one axis whose children's boxes meet [lo, hi]:
/// first and last, first > last when none does.
template <typename Node>
void slots_meeting(std::int64_t origin, std::int64_t lo, std::int64_t hi, int& first, int& last)
{
    constexpr std::int64_t child = Node::ChildNodeType::DIM, slots = std::int64_t(1) << Node::LOG2DIM;
    const std::int64_t a = lo - origin, b = hi - origin;
    if (b < 0 || a >= slots * child) {
        first = 1, last = 0;
        return;
    }
    first = int(std::max<std::int64_t>(a, 0) / child);
    last = int(std::min<std::int64_t>(b / child, slots - 1));
}

template <typename Node, typename Fn>
void for_each_stored_tile_below(const Node& node, const typename Node::ValueType& background,
                                const openvdb::CoordBBox& region, const Fn& fn)
{
    const auto* table = node.getTable();
    const auto& children = node.getChildMask();
    const auto& active = node.getValueMask();
    const openvdb::Coord& o = node.origin();
    int first[3], last[3];
    for (int a = 0; a < 3; ++a) slots_meeting<Node>(o[a], region.min()[a], region.max()[a], first[a], last[a]);
    constexpr openvdb::Index L = Node::LOG2DIM;
    for (int x = first[0]; x <= last[0]; ++x)
        for (int y = first[1]; y <= last[1]; ++y)
            for (int z = first[2]; z <= last[2]; ++z) {
                const openvdb::Index i = (openvdb::Index(x) << 2 * L) + (openvdb::Index(y) << L) + openvdb::Index(z);
                if (children.isOn(i)) {
                    if constexpr (Node::LEVEL > 1)
                        for_each_stored_tile_below(*table[i].getChild(), background, region, fn);
                    continue; // a leaf: its values are voxels, not tiles
                }
                const auto& value = table[i].getValue();
                const bool on = active.isOn(i);
                if (!on && value == background) continue;
                fn(openvdb::CoordBBox::createCube(node.offsetToGlobalCoord(i), Node::ChildNodeType::DIM), value, on);
            }
}

} // namespace detail

/// Calls \p fn(bbox, value, active) for every tile of \p tree above the leaf level that meets
/// \p region and is active or holds a value other than the background, in no particular order
/// (callers fold the tiles with order-free operations: minima, maxima, sets). The work follows
/// the nodes' slots that meet \p region, not the nodes' whole tables.
template <typename TreeT, typename Fn>
void for_each_stored_tile(const TreeT& tree, const openvdb::CoordBBox& region, const Fn& fn)
{
    if (region.empty()) return;
    const auto& root = tree.root();
    const auto& background = tree.background();
    for (auto it = root.cbeginValueAll(); it; ++it) {
        if (!it.isValueOn() && *it == background) continue;
        const auto b = openvdb::CoordBBox::createCube(it.getCoord(), TreeT::RootNodeType::ChildNodeType::DIM);
        if (b.hasOverlap(region)) fn(b, *it, it.isValueOn());
    }
    for (auto it = root.cbeginChildOn(); it; ++it)
        if (it->getNodeBoundingBox().hasOverlap(region)) detail::for_each_stored_tile_below(*it, background, region, fn);
}

} // namespace isodel::octree
