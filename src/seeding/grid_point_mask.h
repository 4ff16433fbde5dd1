#pragma once
// Internal: G's grid points as an OpenVDB mask, which the voxel-bound repairs add to and the
// tetrahedra read (they must not insert a grid point twice). Most runs never ask for it, and on
// a small volume the tree costs more than the whole layer, so it is built on first use from G's
// list, unless the protective layer was built as a mask already (octree/voxel_set.h).
#include <openvdb/openvdb.h>

#include <utility>
#include <vector>

namespace isodel::mesher {

class GridPointMask {
public:
    GridPointMask() = default;
    /// \p built: G as a mask, or null; \p points: G's grid points (kept only when \p built is null).
    GridPointMask(openvdb::MaskGrid::Ptr built, const std::vector<openvdb::Coord>& points) : mask_(std::move(built))
    {
        if (!mask_) points_ = points;
    }
    /// The mask, built now if it was not yet.
    openvdb::MaskGrid& get()
    {
        if (!mask_) {
            mask_ = openvdb::MaskGrid::create();
            auto acc = mask_->getAccessor();
            for (const auto& g : points_) acc.setValueOn(g);
            points_ = {};
        }
        return *mask_;
    }

private:
    openvdb::MaskGrid::Ptr mask_;
    std::vector<openvdb::Coord> points_;
};

} // namespace isodel::mesher
