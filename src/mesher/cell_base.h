#pragma once
// Internal: the Delaunay cell type of the mesher's triangulation (delaunay.h): CGAL's Delaunay
// cell plus one byte, in what was the cell's padding (72 bytes either way), marking which of
// its four facets may have a record in the facet cache (restricted_facets.h).
//
// Every insertion destroys its conflict region, and the cache must drop the records of the
// facets of those cells: without the marks that was a key computation and a hash lookup per
// facet, ~60 per inserted point, nearly all of them for facets without a record. The marks are
// a superset: set on both cells of a facet when its record enters the cache, and forgotten
// only with the cell (a new cell starts unmarked). While a record stays in the cache, both of
// its facet's cells live (destroying either erases it), so a recorded facet is marked wherever
// it is seen; records dropped otherwise (FacetCache::reset) only leave marks without records.
#include <CGAL/Delaunay_triangulation_cell_base_3.h>

#include <cstdint>

namespace isodel::mesher {

template <class GT, class Cb = CGAL::Delaunay_triangulation_cell_base_3<GT>>
class CellWithFacetMarks : public Cb {
public:
    using Vertex_handle = typename Cb::Vertex_handle;
    using Cell_handle = typename Cb::Cell_handle;

    template <class TDS2>
    struct Rebind_TDS {
        using Cb2 = typename Cb::template Rebind_TDS<TDS2>::Other;
        using Other = CellWithFacetMarks<GT, Cb2>;
    };

    CellWithFacetMarks() = default;
    CellWithFacetMarks(Vertex_handle v0, Vertex_handle v1, Vertex_handle v2, Vertex_handle v3) : Cb(v0, v1, v2, v3) {}
    CellWithFacetMarks(Vertex_handle v0, Vertex_handle v1, Vertex_handle v2, Vertex_handle v3, Cell_handle n0,
                       Cell_handle n1, Cell_handle n2, Cell_handle n3)
        : Cb(v0, v1, v2, v3, n0, n1, n2, n3)
    {
    }

    /// Whether facet \p i (opposite vertex i) may have a record.
    bool facet_marked(int i) const { return (marks_ >> i) & 1u; }
    /// Cache bookkeeping, not geometry: const, so a cache can mark cells of a const triangulation.
    void mark_facet(int i) const { marks_ = std::uint8_t(marks_ | (1u << i)); }

private:
    mutable std::uint8_t marks_ = 0;
};

} // namespace isodel::mesher
