#pragma once
// Internal: Voronoi vertices (circumcentres of Delaunay cells) computed robustly. EPICK builds
// them in double precision, which is fine for well-shaped cells but meaningless for the nearly
// flat cells that grid-symmetric E points produce (four points within rounding of a common
// circle): there the double result can land a voxel away, outside the Voronoi cells it bounds,
// breaking Theorem 2's trap. Such cells are recomputed with exact constructions (EPECK).
#include "mesher/delaunay.h"

namespace isodel::mesher {

Point robust_circumcenter(const Point& a, const Point& b, const Point& c, const Point& d);

inline Point robust_circumcenter(const Cell_handle& c)
{
    return robust_circumcenter(c->vertex(0)->point(), c->vertex(1)->point(), c->vertex(2)->point(),
                               c->vertex(3)->point());
}

} // namespace isodel::mesher
