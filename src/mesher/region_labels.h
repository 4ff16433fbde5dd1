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
// disagree with M where a Voronoi edge meets Sigma twice; tests/mesher/test_volume_mesh.cpp
// compares the two.
#include "mesher/delaunay.h"
#include "mesher/restricted_facets.h"

#include <cstdint>
#include <vector>

namespace isodel::mesher {

/// Labels indexed by dt.tds().cells().index(cell): 1 inside, 2 outside (the infinite cells too).
/// \throw GuaranteeViolated the restricted facets do not bound a region
std::vector<std::int8_t> region_labels(const Delaunay& dt, const FacetCache& cache);

} // namespace isodel::mesher
