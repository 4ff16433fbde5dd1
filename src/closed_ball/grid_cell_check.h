#pragma once
// Internal: Theorem 3 of the paper says the Voronoi cell of a protective grid point misses Sigma.
// That is true for the cells the layer normally gives them, but not near Sigma's smallest
// features: a sample barely inside the level set is wrapped by a blob whose six E points sit
// within a few hundredths of a voxel of it, and the box-shaped Voronoi cell of the sample pokes
// through the (concave, star-shaped) trilinear blob. No Voronoi edge crosses such a blob and it
// would vanish from M. So the mesher checks the theorem instead of assuming it: a grid point g
// whose Voronoi vertex lies on the other side of Sigma than g itself violates it, and the
// crossing of the segment from g to that vertex (a point of Sigma inside Vor(g), since the cell
// is convex) is inserted. Voronoi cells only shrink as points are added, so a grid point that
// passes once never needs checking again.
#include "closed_ball/closed_ball.h"
#include "octree/sample_field.h"

#include <vector>

namespace isodel::mesher {

/// Checks the grid points in \p pending (in order); returns one candidate per violating point and
/// keeps exactly those in \p pending for the next round.
std::vector<Candidate> grid_cell_violations(const Delaunay& dt, const octree::SampleField& field,
                                            std::vector<Vertex_handle>& pending, int max_cells);

} // namespace isodel::mesher
