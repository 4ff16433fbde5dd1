#pragma once
// Internal: the restricted Delaunay facets Del P|Sigma (paper Section 3): a facet is restricted
// when its dual Voronoi edge meets Sigma. For each facet with a surface vertex we compute the
// crossings of its Voronoi edge with Sigma by walking the few cells the edge passes through
// (octree/segment_walk.h): the edge lies in the Voronoi cell of its E/N vertex, which the
// protective layer traps in O(1) cells (Theorem 2). Facets among grid points only are skipped:
// their Voronoi edges miss Sigma (Theorem 3).
#include "mesher/delaunay.h"
#include "octree/sample_field.h"

#include <unordered_map>
#include <vector>

namespace isodel::mesher {

struct FacetRecord {
    std::uint16_t crossings = 0;  ///< transversal crossings of the Voronoi edge with Sigma
    bool overflow = false;        ///< the Voronoi edge is unbounded or left its cell bound
    Point surface_point;          ///< crossing farthest from the triangle's circumcentre
    double distance = 0;          ///< |surface_point - circumcentre of the triangle|
    Vector outward;               ///< along the Voronoi edge, from its inside end to its outside end
};

/// Crossings of the Voronoi edge dual to \p f with Sigma.
FacetRecord compute_facet_record(const Delaunay& dt, const Facet& f,
                                 const octree::SampleField::Reader& reader, int max_cells);

/// Cache of facet records keyed by vertex ids. A facet's Voronoi edge changes exactly when one
/// of its two cells is replaced; every new cell is incident to the inserted vertex, so after an
/// insertion of v the records to drop are those of the facets opposite v in v's new cells
/// (facets containing v are new keys).
class FacetCache {
public:
    /// Scans every finite facet with a surface vertex, computing missing records in parallel
    /// (deterministic: each record depends only on the triangulation). Drops stale entries.
    void update(const Delaunay& dt, const octree::SampleField& field, int max_cells);

    void invalidate_around(const Delaunay& dt, Vertex_handle v);

    struct Entry {
        Facet facet;
        FacetKey key;
        const FacetRecord* record;
    };
    /// Facets whose Voronoi edge meets Sigma or overflowed, in scan order (deterministic).
    const std::vector<Entry>& active() const { return active_; }
    std::size_t computed_last_update() const { return computed_; }

private:
    std::unordered_map<FacetKey, FacetRecord, FacetKeyHash> map_;
    std::vector<Entry> active_;
    std::size_t computed_ = 0;
};

} // namespace isodel::mesher
