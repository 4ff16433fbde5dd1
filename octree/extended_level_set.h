#pragma once
/// \file extended_level_set.h
/// Corner samples for coarse cells of a narrow-band level set (certified_coarsening.h).
///
/// A narrow-band level set stores signed distances only within a few voxels of Sigma and clamps
/// the rest to +-background. A coarse cell crossing Sigma has corners farther out than that, and
/// a clamped corner makes its interpolant wrong near Sigma, so the certificate refuses it: the
/// band's half-width, not the shape, would bound the cells at Sigma. Extending the distances
/// beyond the band (OpenVDB's LevelSetTracker::dilate, which solves the Eikonal equation on the
/// new voxels only) gives coarse cells honest corners. The extension is only a source of corner
/// values: the certificate still compares the coarse interpolant with the input's own samples,
/// so nothing is taken on trust.
#include <openvdb/openvdb.h>

namespace isodel::octree {

/// A copy of \p grid with the distances extended \p voxels layers beyond its narrow band; the
/// new voxels stay inactive (so the active bounding box, hence the domain, is the input's) and
/// the band's own values are unchanged. Null when \p grid is not a level set (GRID_LEVEL_SET
/// with uniform voxels), when it has no band to extend (every voxel of its active box active),
/// or \p voxels < 1.
openvdb::FloatGrid::Ptr extend_level_set(const openvdb::FloatGrid& grid, int voxels);

} // namespace isodel::octree
