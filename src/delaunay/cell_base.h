#pragma once
// Internal: the Delaunay cell type of the mesher's triangulation (delaunay.h): CGAL's Delaunay
// cell plus two caches the mesher's checks read far more often than the cell changes, and the
// inside/outside label of DELVOLMESH's flood fill.
//
// Facet marks (one byte, in what was the cell's padding). Every insertion destroys its
// conflict region, and the cache must drop the records of the facets of those cells: without
// the marks that would be a key computation and a hash lookup per facet, ~60 per inserted point,
// nearly all of them for facets without a record. The marks are a superset: set on both cells
// of a facet when its record enters the cache, and forgotten only with the cell (a new cell
// starts unmarked). While a record stays in the cache, both of its facet's cells live
// (destroying either erases it), so a recorded facet is marked wherever it is seen; records
// dropped otherwise (FacetCache::reset) only leave marks without records.
//
// The Voronoi vertex (circumcenter.h's robust circumcentre, 24 bytes and a state byte). Every
// check of a round reads the Voronoi vertices around the facets and vertices it looks at: the
// facet records, loop scan, disk certificates and grid-cell checks would otherwise each compute
// the same cell's circumcentre again, round after round. The mesher never changes a live
// cell's vertices or their points (insertion and removal make new cells; a new cell starts
// with an empty cache), so the first value computed stays the cell's. Threads may fill the
// cache concurrently: the first to claim it writes it, and readers take it only once it is
// published (acquire/release), others compute it themselves meanwhile (the same bits: the
// computation depends only on the cell's vertices).
//
// The region label and restricted sides (region_labels.h), two bytes also in the padding:
// written by the inside/outside flood fill of DELVOLMESH over a triangulation that no longer
// changes, and read right after it. In the cell, the fill follows neighbour pointers only; with
// the labels in an array, every step would have to find a cell's index from its address (a
// binary search over all cells per step, scattered in memory).
#include <CGAL/Delaunay_triangulation_cell_base_3.h>

#include <atomic>
#include <cstdint>

namespace isodel::mesher {

template <class GT, class Cb = CGAL::Delaunay_triangulation_cell_base_3<GT>>
class CellWithCaches : public Cb {
public:
    using Vertex_handle = typename Cb::Vertex_handle;
    using Cell_handle = typename Cb::Cell_handle;

    template <class TDS2>
    struct Rebind_TDS {
        using Cb2 = typename Cb::template Rebind_TDS<TDS2>::Other;
        using Other = CellWithCaches<GT, Cb2>;
    };

    CellWithCaches() = default;
    CellWithCaches(Vertex_handle v0, Vertex_handle v1, Vertex_handle v2, Vertex_handle v3) : Cb(v0, v1, v2, v3) {}
    CellWithCaches(Vertex_handle v0, Vertex_handle v1, Vertex_handle v2, Vertex_handle v3, Cell_handle n0,
                   Cell_handle n1, Cell_handle n2, Cell_handle n3)
        : Cb(v0, v1, v2, v3, n0, n1, n2, n3)
    {
    }
    // A copy is a new cell: CGAL's copy keeps the combinatorics, and the caches start empty.
    CellWithCaches(const CellWithCaches& o) : Cb(o) {}
    CellWithCaches& operator=(const CellWithCaches& o)
    {
        Cb::operator=(o);
        marks_ = 0;
        region_ = 0;
        restricted_sides_ = 0;
        cc_state_.store(kEmpty, std::memory_order_relaxed);
        return *this;
    }

    /// Whether facet \p i (opposite vertex i) may have a record.
    bool facet_marked(int i) const { return (marks_ >> i) & 1u; }
    /// Cache bookkeeping, not geometry: const, so a cache can mark cells of a const triangulation.
    void mark_facet(int i) const { marks_ = std::uint8_t(marks_ | (1u << i)); }

    /// The cell's circumcentre: computed by \p compute (returning a CGAL point) the first time,
    /// then the stored value.
    template <class Compute>
    auto cached_circumcenter(Compute&& compute) const -> decltype(compute())
    {
        using P = decltype(compute());
        if (cc_state_.load(std::memory_order_acquire) == kReady) return P(cc_[0], cc_[1], cc_[2]);
        const P p = compute();
        std::uint8_t expected = kEmpty;
        if (cc_state_.compare_exchange_strong(expected, kWriting, std::memory_order_acq_rel)) {
            cc_[0] = p.x();
            cc_[1] = p.y();
            cc_[2] = p.z();
            cc_state_.store(kReady, std::memory_order_release);
        }
        return p;
    }

    /// The region of the cell (region_labels.h): 0 not labelled, 1 inside, 2 outside.
    std::int8_t region_label() const { return region_; }
    void set_region_label(std::int8_t l) { region_ = l; }
    /// Whether side \p i (the facet opposite vertex i) is a facet of M, as set by
    /// set_restricted_sides() for the flood fill.
    bool restricted_side(int i) const { return (restricted_sides_ >> i) & 1u; }
    void set_restricted_sides(std::uint8_t bits) { restricted_sides_ = bits; }
    void add_restricted_side(int i) { restricted_sides_ = std::uint8_t(restricted_sides_ | (1u << i)); }

private:
    static constexpr std::uint8_t kEmpty = 0, kWriting = 1, kReady = 2;
    mutable std::uint8_t marks_ = 0;
    mutable std::atomic<std::uint8_t> cc_state_{kEmpty};
    std::int8_t region_ = 0;
    std::uint8_t restricted_sides_ = 0;
    mutable double cc_[3] = {0, 0, 0};
};

} // namespace isodel::mesher
