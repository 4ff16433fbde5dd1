#pragma once
// Internal: DELSURFMESH's point sets on an adaptive (octree) grid (paper Section 4.2, Property IV).
//
// F is the adaptive interpolant (octree/interpolant.h). The mesher evaluates it through its exact
// resampling on the finest lattice (octree/resample.h): a trilinear leaf restricted to a unit
// sub-cell is the trilinear function of the sub-cell's corners, so segment walks, Theorem 3
// checks and the epsilon refinement read the same F as on the leaves, and `isodel verify` checks
// the mesh against that same resampled grid. What follows the leaves is the point set, which is
// where decimation pays:
//  - E: the crossings on leaf edges only (a unit edge inside a leaf's face or cell is not an
//    edge of the adaptive grid). On a leaf edge F is linear, so these are the leaf edges' exact
//    crossings.
//  - G: the corners of every crossed leaf and of every leaf touching it (the uniform layer
//    [c-1, c+2]^3 of protective_layer.h, in leaf adjacency), r rings of leaves where the voxels
//    need r > 1 (sheared lattices), and beyond the domain the unit lattice as on a uniform grid.
//  - G' (tetrahedra): the leaf corners only, so coarse leaves give large tetrahedra.
//  - The voxel bound counts leaves: the paper's Theorem 2 bounds the Voronoi cell of an E point
//    by 3k+1 cells on an octree whose touching leaves differ by at most k levels. A cell over
//    its bound is a hole in G, repaired by the unit-lattice points around the point (after which
//    the uniform argument holds: 4 unit cells, so at most 4 leaves).
#include "octree/adaptive_grid.h"

#include <openvdb/openvdb.h>

#include <array>
#include <vector>

namespace isodel::mesher {

/// True when the unit edge from \p lower along \p axis lies on an edge of a leaf (or outside the
/// domain, where the grid is the unit lattice).
bool on_leaf_edge(const octree::AdaptiveGrid::Reader& r, const openvdb::Coord& lower, int axis);

/// G: the corners of the leaves within \p rings leaf rings of the leaves holding
/// \p crossed_unit_cells, plus the unit-lattice block [u - r, u + 1 + r] of every crossed unit
/// cell for the part of it beyond the domain. In OpenVDB's deterministic order.
std::vector<openvdb::Coord> adaptive_protective_layer(const octree::AdaptiveGrid& g,
                                                      const std::vector<openvdb::Coord>& crossed_unit_cells,
                                                      const std::array<int, 3>& radius);

/// Leaves overlapping the unit cells of \p cells (inclusive box of unit-cell origins); unit
/// cells beyond the domain count one each. O(leaves x levels), not O(unit cells).
int leaves_in_box(const octree::AdaptiveGrid::Reader& r, const openvdb::CoordBBox& cells);

/// True when sample \p n is a corner of some leaf (always beyond the domain).
bool is_leaf_node(const octree::AdaptiveGrid::Reader& r, const openvdb::Coord& n);

} // namespace isodel::mesher
