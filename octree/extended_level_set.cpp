#include "octree/extended_level_set.h"

#include <openvdb/tools/LevelSetTracker.h>

#include <cstdint>

namespace isodel::octree {

openvdb::FloatGrid::Ptr extend_level_set(const openvdb::FloatGrid& grid, int voxels)
{
    if (voxels < 1 || grid.getGridClass() != openvdb::GRID_LEVEL_SET || !grid.hasUniformVoxels()) return nullptr;
    // A level set stored densely (every voxel of its active box active) has no band to extend
    // within the box, the only nodes coarse cells read beyond the input's samples being the
    // domain's one-voxel ring; dilating it would cost a pass over the whole box and only give
    // those ring nodes other values, which the certificate would check like any corner value.
    if (std::uint64_t(grid.activeVoxelCount()) == grid.evalActiveVoxelBoundingBox().volume()) return nullptr;
    auto out = grid.deepCopy();
    openvdb::tools::LevelSetTracker<openvdb::FloatGrid> tracker(*out);
    tracker.dilate(voxels);
    // The new voxels keep their values but not their active state: the domain rule
    // (sample_field.h) reads the input's active bounding box.
    openvdb::MaskGrid added(false);
    added.tree().topologyUnion(out->tree());
    added.tree().topologyDifference(grid.tree());
    auto acc = out->getAccessor();
    for (auto it = added.cbeginValueOn(); it; ++it) {
        if (it.isVoxelValue()) {
            acc.setActiveState(it.getCoord(), false);
            continue;
        }
        const openvdb::CoordBBox b = it.getBoundingBox();
        for (auto c = b.begin(); c; ++c) acc.setActiveState(*c, false);
    }
    return out;
}

} // namespace isodel::octree
