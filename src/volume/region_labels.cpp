#include "volume/region_labels.h"

#include <isodel/errors.h>

#include <sstream>
#include <vector>

namespace isodel::mesher {

void label_regions(Delaunay& dt, const FacetCache& cache)
{
    std::vector<Cell_handle> stack;
    for (auto c = dt.all_cells_begin(); c != dt.all_cells_end(); ++c) {
        c->set_restricted_sides(0);
        c->set_region_label(dt.is_infinite(c) ? 2 : 0);
        if (c->region_label() == 2) stack.push_back(c);
    }
    // The restricted facets as a bit per cell side, on both cells of each: the fill then reads
    // the cell it stands on instead of hashing every facet with an E/N vertex (a hash lookup
    // per step of the fill, over every cell of the triangulation).
    for (const auto& e : cache.active())
        if (e.record->crossings == 1) {
            const Facet m = dt.mirror_facet(e.facet);
            e.facet.first->add_restricted_side(e.facet.second);
            m.first->add_restricted_side(m.second);
        }
    std::size_t conflicts = 0;
    while (!stack.empty()) {
        const Cell_handle c = stack.back();
        stack.pop_back();
        const std::int8_t l = c->region_label();
        for (int i = 0; i < 4; ++i) {
            // Facets on the convex hull (one infinite cell) have unbounded Voronoi edges and are
            // never restricted: only facets between finite cells can flip the label.
            const std::int8_t want = c->restricted_side(i) ? std::int8_t(3 - l) : l;
            const Cell_handle n = c->neighbor(i);
            if (n->region_label() == 0) {
                n->set_region_label(want);
                stack.push_back(n);
            } else if (n->region_label() != want) {
                ++conflicts;
            }
        }
    }
    if (conflicts) {
        std::ostringstream os;
        os << "DELVOLMESH: the surface mesh does not bound a region (" << conflicts / 2
           << " facets where the inside/outside flood fill disagrees)";
        throw GuaranteeViolated(os.str());
    }
}

} // namespace isodel::mesher
