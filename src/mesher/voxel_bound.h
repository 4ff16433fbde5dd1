#pragma once
// Internal: measuring Theorem 2's bound. The cells a Voronoi cell meets are counted as the cells
// overlapped by the index-space bounding box of its Voronoi vertices (an upper bound on the
// true count). A cell with an infinite neighbour is unbounded (-1): a hole in G.
#include "mesher/delaunay.h"
#include "octree/sample_field.h"

namespace isodel::mesher {

int voronoi_cell_count(const Delaunay& dt, Vertex_handle v, const octree::SampleField& field);

} // namespace isodel::mesher
