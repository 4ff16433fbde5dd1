#pragma once
// Internal: G', the grid points DELVOLMESH adds to fill the volume (paper Section 4.1): the
// sample points strictly inside (phi > 0) and/or strictly outside (phi < 0) that are not already
// in the protective layer G. G separates Sigma from them (Theorem 3), so their Voronoi cells miss
// Sigma and Del|Sigma, hence M, is unchanged by their insertion (volume_mesh.h checks this).
// The outside region is bounded: its points are those of the box B = the field's domain (active
// bounding box grown by one voxel) grown by one more voxel -- Sigma lies inside B (see
// include/isodel/mesh.h) -- enlarged to hold G; then conv(E u G u N u G') = B.
#include <isodel/mesh.h>

#include "octree/adaptive_grid.h"
#include "octree/sample_field.h"

#include <openvdb/openvdb.h>

#include <vector>

namespace isodel::mesher {

/// Index-space box whose grid points bound the outside region.
openvdb::CoordBBox volume_box(const octree::SampleField& field, const openvdb::MaskGrid& g_mask);

/// The grid points (index coordinates) of G' for \p region, in z-major raster order
/// (deterministic; volume_mesh.cpp re-sorts them for insertion).
/// \pre region != TetRegion::None
/// With \p adaptive, only leaf corners inside the domain (adaptive_points.h): coarse leaves give
/// large tetrahedra.
std::vector<openvdb::Coord> interior_points(const octree::SampleField& field, const openvdb::MaskGrid& g_mask,
                                            TetRegion region,
                                            const octree::AdaptiveGrid::Reader* adaptive = nullptr);

} // namespace isodel::mesher
