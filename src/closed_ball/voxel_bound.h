#pragma once
// Internal: measuring Theorem 2's bound. The cells a Voronoi cell meets are counted as the cells
// overlapped by the index-space bounding box of its Voronoi vertices (an upper bound on the
// true count): unit cells on a uniform grid, leaves on an adaptive one (adaptive_points.h). A
// cell with an infinite neighbour is unbounded (-1): a hole in G.
#include "delaunay/delaunay.h"
#include "octree/adaptive_grid.h"
#include "octree/sample_field.h"

#include <vector>

namespace isodel::mesher {

/// The unit cells overlapped by the bounding box of Vor(v); false when Vor(v) is unbounded.
bool voronoi_cell_box(const Delaunay& dt, Vertex_handle v, const octree::SampleField& field,
                      openvdb::CoordBBox& cells);

/// Cells met by Vor(v) (see above): unit cells, or leaves of \p adaptive when it is given;
/// -1 when unbounded.
int voronoi_cell_count(const Delaunay& dt, Vertex_handle v, const octree::SampleField& field,
                       const octree::AdaptiveGrid::Reader* adaptive = nullptr);

/// voronoi_cell_count of every vertex of \p vertices, in their order: the boxes in parallel
/// (stars by gather_star, so threads share no visit marks), the leaf counts serially (one
/// adaptive reader). \p dt must not change meanwhile.
std::vector<int> voronoi_cell_counts(const Delaunay& dt, const std::vector<Vertex_handle>& vertices,
                                     const octree::SampleField& field,
                                     const octree::AdaptiveGrid::Reader* adaptive = nullptr);

} // namespace isodel::mesher
