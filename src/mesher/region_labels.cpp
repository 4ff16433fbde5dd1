#include "mesher/region_labels.h"

#include <isodel/errors.h>

#include <sstream>
#include <unordered_set>

namespace isodel::mesher {

std::vector<std::int8_t> region_labels(const Delaunay& dt, const FacetCache& cache)
{
    std::unordered_set<FacetKey, FacetKeyHash> restricted;
    for (const auto& e : cache.active())
        if (e.record->crossings == 1) restricted.insert(e.key);
    const auto& cells = dt.tds().cells();
    std::vector<std::int8_t> label(cells.capacity(), 0);
    std::vector<Cell_handle> stack;
    for (auto c = dt.all_cells_begin(); c != dt.all_cells_end(); ++c)
        if (dt.is_infinite(c)) {
            label[cells.index(c)] = 2;
            stack.push_back(c);
        }
    std::size_t conflicts = 0;
    while (!stack.empty()) {
        const Cell_handle c = stack.back();
        stack.pop_back();
        const std::int8_t l = label[cells.index(c)];
        for (int i = 0; i < 4; ++i) {
            const Cell_handle n = c->neighbor(i);
            // Facets on the convex hull (one infinite cell) have unbounded Voronoi edges and are
            // never restricted; only facets between finite cells can flip the label.
            // FacetCache only records facets with an E/N vertex: skip the hash lookup for the rest.
            bool flip = false;
            if (!dt.is_infinite(c) && !dt.is_infinite(n)) {
                const auto vs = facet_vertices(Facet(c, i));
                if (vs[0]->info().on_surface() || vs[1]->info().on_surface() || vs[2]->info().on_surface())
                    flip = restricted.count(facet_key(Facet(c, i))) > 0;
            }
            const std::int8_t want = flip ? std::int8_t(3 - l) : l;
            std::int8_t& ln = label[cells.index(n)];
            if (ln == 0) {
                ln = want;
                stack.push_back(n);
            } else if (ln != want) {
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
    return label;
}

} // namespace isodel::mesher
