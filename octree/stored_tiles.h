#pragma once
// Internal: the tiles of a tree above the leaf level that hold something other than the
// background: active tiles, and inactive tiles of another value (a level set's inside). An
// inactive tile of the background value reads exactly as the background does, which every
// consumer accounts for on its own (sample_field.cpp, edge_crossings.cpp), so it is skipped.
//
// Why not the tree's value iterator: an internal node of the top level has 32^3 slots, nearly
// all inactive background tiles in a sparse or small grid, and the tree-level iterator costs
// tens of instructions per slot. Here a slot costs a mask test and a compare, read from the
// node's own table.
#include <openvdb/openvdb.h>

namespace isodel::octree {

namespace detail {

template <typename Node, typename Fn>
void for_each_stored_tile_below(const Node& node, const typename Node::ValueType& background, const Fn& fn)
{
    const auto* table = node.getTable();
    const auto& children = node.getChildMask();
    const auto& active = node.getValueMask();
    for (openvdb::Index i = 0; i < Node::NUM_VALUES; ++i) {
        // A word of 64 slots without children or active tiles (most of a sparse grid's top
        // nodes): only a value other than the background can make one of them count.
        if (i % 64 == 0 && children.template getWord<openvdb::Index64>(i / 64) == 0 &&
            active.template getWord<openvdb::Index64>(i / 64) == 0) {
            bool all_background = true;
            for (openvdb::Index j = i; j < i + 64; ++j) all_background &= table[j].getValue() == background;
            if (all_background) {
                i += 63;
                continue;
            }
        }
        if (children.isOn(i)) {
            if constexpr (Node::LEVEL > 1) for_each_stored_tile_below(*table[i].getChild(), background, fn);
            continue; // a leaf: its values are voxels, not tiles
        }
        const auto& value = table[i].getValue();
        const bool on = active.isOn(i);
        if (!on && value == background) continue;
        fn(openvdb::CoordBBox::createCube(node.offsetToGlobalCoord(i), Node::ChildNodeType::DIM), value, on);
    }
}

} // namespace detail

/// Calls \p fn(bbox, value, active) for every tile of \p tree above the leaf level that is
/// active or whose value differs from the background, in no particular order (callers fold
/// the tiles with order-free operations: minima, maxima, sets).
template <typename TreeT, typename Fn>
void for_each_stored_tile(const TreeT& tree, const Fn& fn)
{
    const auto& root = tree.root();
    const auto& background = tree.background();
    for (auto it = root.cbeginValueAll(); it; ++it) {
        if (!it.isValueOn() && *it == background) continue;
        fn(openvdb::CoordBBox::createCube(it.getCoord(), TreeT::RootNodeType::ChildNodeType::DIM), *it, it.isValueOn());
    }
    for (auto it = root.cbeginChildOn(); it; ++it) detail::for_each_stored_tile_below(*it, background, fn);
}

} // namespace isodel::octree
