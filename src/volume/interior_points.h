#pragma once
// Internal: G', the grid points DELVOLMESH adds to fill the volume (paper Section 4.1): the
// sample points strictly inside (phi > 0) and/or strictly outside (phi < 0) that are not already
// in the protective layer G. G separates Sigma from them (Theorem 3), so their Voronoi cells miss
// Sigma and Del|Sigma, hence M, is unchanged by their insertion (volume_mesh.h checks this).
// The outside region is bounded: its points are those of the box B = the field's domain (active
// bounding box grown by one voxel) grown by one more voxel -- Sigma lies inside B (see
// include/isodel/mesh.h) -- enlarged to hold G; then conv(E u G u N u G') = B.
//
// Graded spacing keeps only a subset of those samples: a nested family of lattices, finer next
// to G. Any subset leaves M unchanged for the same reason the whole set does: a point of Sigma
// whose nearest site is in E u G u N with all of G' present still has it with fewer G' points.
#include <isodel/mesh.h>

#include "octree/adaptive_grid.h"
#include "octree/sample_field.h"

#include <openvdb/openvdb.h>

#include <vector>

namespace isodel::mesher {

/// Graded G' (MeshOptions::tet_spacing == Graded): a sample at chessboard distance d voxels
/// from G is kept when it lies on the lattice of spacing 2^l anchored at the box's lowest
/// corner, 2^l the largest power of two with 2^l <= 1 + grading * d and l <= max_level, lowered
/// to the largest level a sample of the unrounded box (volume_box) can reach.
struct GradedSpacing {
    double grading = 0.5;
    int max_level = 3;
};

/// The largest lattice level for MeshOptions::tet_size (world units, 0 = 8 voxels) on voxels of
/// edge \p voxel: floor(log2(tet_size / voxel)), clamped to [0, 10].
int graded_max_level(double tet_size, double voxel);

/// Index-space box whose grid points bound the outside region; with \p spacing its extent is
/// grown to a multiple of the largest spacing, so its far faces hold lattice points too.
openvdb::CoordBBox volume_box(const octree::SampleField& field, const openvdb::MaskGrid& g_mask,
                              const GradedSpacing* spacing = nullptr);

/// The grid points (index coordinates) of G' for \p region, in z-major raster order
/// (deterministic; volume_mesh.cpp re-sorts them for insertion).
/// \pre region != TetRegion::None
/// With \p adaptive, only leaf corners inside the domain (adaptive_points.h): coarse leaves give
/// large tetrahedra, and \p spacing is ignored. With \p spacing (uniform grids), the graded
/// subset described at GradedSpacing; without, every sample.
std::vector<openvdb::Coord> interior_points(const octree::SampleField& field, const openvdb::MaskGrid& g_mask,
                                            TetRegion region,
                                            const octree::AdaptiveGrid::Reader* adaptive = nullptr,
                                            const GradedSpacing* spacing = nullptr);

} // namespace isodel::mesher
