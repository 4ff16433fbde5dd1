#pragma once
// Internal: DELSURFMESH step 5, output Del(E u G u N)|Sigma as an indexed, consistently oriented
// triangle mesh (normals toward the outside region), plus its topology per component.
#include "closed_ball/restricted_facets.h"

#include <isodel/mesh.h>

namespace isodel::mesher {

/// \p vertex_ids, when given: the Delaunay vertex id of each of M's vertices, in index order.
SurfaceMesh extract_surface(const Delaunay& dt, const FacetCache& cache, std::vector<std::uint32_t>* vertex_ids = nullptr);

/// The deterministic triangle order, independent of the triangulation's memory layout: by
/// sorted vertex indices (distinct for distinct triangles).
void sort_triangles(SurfaceMesh& mesh);

/// Components of a closed triangle mesh with their Euler characteristic and genus.
std::vector<ComponentTopology> surface_topology(const SurfaceMesh& mesh);

} // namespace isodel::mesher
