#pragma once
// Internal: Del(E u G), the mesher's first triangulation (paper Section 4, step 3). It is the
// largest single insertion of a run (E, G and the thin-tube points at once: G alone holds every
// sample of a block around each crossed cell, Theorem 2), so it uses CGAL's parallel insertion
// when more than one thread may run.
#include "delaunay/delaunay.h"

#include <isodel/interrupt.h>

#include <utility>
#include <vector>

namespace isodel::mesher {

/// Makes \p dt the Delaunay triangulation of \p points (each with its id and kind). With one
/// thread allowed (tbb::global_control), CGAL's spatially sorted sequential insertion; with
/// more, its parallel insertion (Parallel_tag, a spatial lock grid) into a triangulation of
/// the concurrent type, which is then copied into \p dt. The triangulation is the same either
/// way: CGAL's symbolic perturbation defines Del uniquely even for the cospherical points of
/// the grid, whatever the order of insertion. What may differ is where cells are stored,
/// which nothing downstream depends on (vertex ids and facet keys order every result).
/// \p scope, when given, is polled as the points go in (throws isodel::Cancelled); the parallel
/// insertion is one CGAL call and is not polled.
void build_initial_delaunay(Delaunay& dt, const std::vector<std::pair<Point, VertexInfo>>& points,
                            const InterruptScope* scope = nullptr);

} // namespace isodel::mesher
