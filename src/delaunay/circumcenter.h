#pragma once
// Internal: Voronoi vertices (circumcentres of Delaunay cells) computed robustly. EPICK builds
// them in double precision, which is fine for well-shaped cells but meaningless for the nearly
// flat cells that grid-symmetric E points produce (four points within rounding of a common
// circle): there the double result can land a voxel away, outside the Voronoi cells it bounds,
// breaking Theorem 2's trap. Such cells are recomputed with exact constructions (EPECK).
#include "delaunay/delaunay.h"

#include <algorithm>
#include <array>

namespace isodel::mesher {

Point robust_circumcenter(const Point& a, const Point& b, const Point& c, const Point& d);

/// The Voronoi vertex dual to \p c. The vertices are taken in id order, so the rounded result
/// does not depend on how the triangulation happens to store the cell (determinism). Computed
/// once per cell and kept in it (cell_base.h): the vertices' ids must be final when it is first
/// asked for (they are set right after each insertion, before any check runs).
inline Point robust_circumcenter(const Cell_handle& c)
{
    return c->cached_circumcenter([&c] {
        std::array<Vertex_handle, 4> v{c->vertex(0), c->vertex(1), c->vertex(2), c->vertex(3)};
        std::sort(v.begin(), v.end(), [](Vertex_handle a, Vertex_handle b) { return a->info().id < b->info().id; });
        return robust_circumcenter(v[0]->point(), v[1]->point(), v[2]->point(), v[3]->point());
    });
}

} // namespace isodel::mesher
