#pragma once
// Internal: the cells around a vertex, gathered so that several threads may do it at once.
// CGAL's incident_cells marks the cells it visits inside the triangulation itself, so two
// threads gathering overlapping stars would race on those marks; this walk keeps its marks in
// its own output. The mesher's checks gather the stars of tens of thousands of vertices per
// round, and serially that was a third of a round's time on two threads.
#include "mesher/delaunay.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <vector>

namespace isodel::mesher {

/// The cells incident to \p v (infinite ones included) in \p out, in an order that depends only
/// on the triangulation's connectivity (a walk from v->cell()). Read-only: threads may gather
/// stars of one triangulation concurrently while nothing modifies it. Dimension 3 only.
inline void gather_star(Vertex_handle v, std::vector<Cell_handle>& out)
{
    out.clear();
    out.push_back(v->cell());
    // A star has a few dozen cells: a linear search of the list is cheaper than a set.
    for (std::size_t i = 0; i < out.size(); ++i) {
        const Cell_handle c = out[i];
        const int iv = c->index(v);
        for (int j = 0; j < 4; ++j) {
            if (j == iv) continue;
            const Cell_handle n = c->neighbor(j); // shares the face opposite j, which contains v
            if (std::find(out.begin(), out.end(), n) == out.end()) out.push_back(n);
        }
    }
}

/// Calls f(i, cells) for every i in [begin, end), in parallel, with cells the star of
/// vertices[i] (gather_star); f may run concurrently for different i.
template <class F>
void for_each_star(const std::vector<Vertex_handle>& vertices, std::size_t begin, std::size_t end, F&& f)
{
    tbb::enumerable_thread_specific<std::vector<Cell_handle>> stars;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, 64), [&](const tbb::blocked_range<std::size_t>& r) {
        auto& cells = stars.local();
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            gather_star(vertices[i], cells);
            f(i, cells);
        }
    });
}

} // namespace isodel::mesher
