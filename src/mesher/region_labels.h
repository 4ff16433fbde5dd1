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

/// Dense indices 0..n-1 of the triangulation's cells (the infinite ones too), in container
/// order. CGAL's Compact_container::index() walks the container's list of blocks, which grows as
/// the square root of the number of cells: ~1000 comparisons per call for a few million cells.
/// Here the cells' addresses form runs of consecutive slots, found once, and a lookup is a
/// binary search over them. Valid until the triangulation changes.
class CellIndex {
public:
    explicit CellIndex(const Delaunay& dt);
    std::size_t operator()(Cell_handle c) const;
    std::size_t size() const { return size_; }

private:
    struct Run {
        std::uintptr_t first; ///< address of the run's first cell
        std::size_t begin;    ///< its index
        std::size_t length;   ///< cells in the run
    };
    std::vector<Run> runs_; ///< sorted by address
    std::size_t size_ = 0;
};

/// Labels of the cells: 1 inside, 2 outside (the infinite cells too).
struct RegionLabels {
    CellIndex index;
    std::vector<std::int8_t> label; ///< by index(cell)
    std::int8_t operator()(Cell_handle c) const { return label[index(c)]; }
};

/// \throw GuaranteeViolated the restricted facets do not bound a region
RegionLabels region_labels(const Delaunay& dt, const FacetCache& cache);

} // namespace isodel::mesher
