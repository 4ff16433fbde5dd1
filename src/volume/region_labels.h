#pragma once
// Internal: inside/outside labels of the Delaunay cells, by flood fill across facets, flipping
// the label across restricted facets and starting outside at the infinite cells.
//
// Why a flood fill and not the sign of F at each cell's Voronoi vertex: the labels must agree with
// M exactly -- the inside region's boundary must be M, facet for facet -- and the fill gives that
// by construction: the label changes across a facet iff the facet is in M. Its only precondition
// is that M is a boundary mod 2 (every edge of M in an even number of M's triangles, true for the
// closed 2-manifold Theorem 1 delivers), and it is checked: a cell reached with two different
// labels is an inconsistency, thrown as GuaranteeViolated. The sign of F at a Voronoi vertex can
// disagree with M where a Voronoi edge meets Sigma twice; tests/volume/test_volume_mesh.cpp
// compares the two.
#include "delaunay/delaunay.h"
#include "closed_ball/restricted_facets.h"

namespace isodel::mesher {

/// Labels every cell of \p dt, the infinite ones too: afterwards Cell::region_label() is 1
/// inside M and 2 outside (cell_base.h keeps the label in the cell). Valid until \p dt changes.
/// \throw GuaranteeViolated the restricted facets do not bound a region
void label_regions(Delaunay& dt, const FacetCache& cache);

} // namespace isodel::mesher
