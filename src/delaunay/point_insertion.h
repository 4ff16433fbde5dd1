#pragma once
// Internal: inserting a batch of candidate points into the triangulation. Candidates come in a
// deterministic order; one is skipped when it lies closer than half its own spacing to a point
// accepted earlier in the same batch, so one violation seen by several Voronoi edges does not
// put clusters of points into one spot (the next round checks again anyway).
#include "closed_ball/closed_ball.h"
#include "closed_ball/restricted_facets.h"

#include <vector>

namespace isodel::mesher {

struct InsertionResult {
    std::vector<Vertex_handle> inserted;
};

InsertionResult insert_candidates(Delaunay& dt, FacetCache& cache, std::vector<Candidate> candidates,
                                  std::uint32_t& next_id, double cell_size);

} // namespace isodel::mesher
