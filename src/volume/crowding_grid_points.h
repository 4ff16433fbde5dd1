#pragma once
// Internal: tetrahedron quality without touching M (DELVOLMESH, paper Section 4.1). An E point
// lies on a grid edge, often a small fraction of a voxel from the edge's sample; the sample stays
// in G to trap the E point's Voronoi cell (Theorem 2) and the tetrahedra joining the two are
// slivers and needles (such short edges are behind many of the worst tets). Once M is final the
// trap has done its job, and a grid point g can go:
//
// if Vor(g) does not meet Sigma, every point of Sigma keeps its nearest site when g is
// removed, so the restricted Voronoi diagram - hence M, its closed ball property and its
// surface points - is exactly unchanged. The same holds for removing any set of such points at
// once: a cell that grows absorbs only pieces of removed cells, which missed Sigma too.
//
// Certificate that Vor(g) misses Sigma (no sampling): Vor(g) is the convex hull of the
// circumcentres of g's cells; in index space its bounding box meets a few grid cells, and on
// the part of the box inside one cell F is trilinear in box coordinates, so its extrema are at
// that sub-box's 8 corners. All corners on g's side of v (>= v counts as above, the tie rule)
// proves it. Grid points on the convex hull (the box of the outside region) are kept.
#include "delaunay/delaunay.h"
#include "octree/sample_field.h"

#include <cstddef>
#include <vector>

namespace isodel::mesher {

/// The grid points of \p dt closer than \p reach (world units) to a vertex on M whose Voronoi
/// cell is certified to miss Sigma, in id order: all of them can go at once (above), through
/// FacetCache::remove so the cache stays current. Deterministic: certified on the unchanged
/// triangulation.
std::vector<Vertex_handle> crowding_grid_points(const Delaunay& dt, const octree::SampleField& field, double reach);

/// Whether the Voronoi cell of \p g misses Sigma, by the certificate above; \p cells are g's
/// incident cells. False when the cell is unbounded or its box spans more than \p max_cells
/// grid cells.
bool voronoi_cell_misses_sigma(const Delaunay& dt, Vertex_handle g, const std::vector<Cell_handle>& cells,
                               const octree::SampleField::Reader& reader, int max_cells = 64);

} // namespace isodel::mesher
