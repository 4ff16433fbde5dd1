#pragma once
// Internal: the bad tetrahedra M pins down (DELVOLMESH, paper Section 4.1), and the points of
// Sigma that free them.
//
// The tets phase keeps M: it moves, removes and inserts only vertices off M and flips only
// within a region (tet_improvement.h). A tet with a face on M whose dihedral range is still out
// of bounds after it is held by that face: four vertices of M nearly cocircular on a flat patch
// of Sigma, or a triangle of M whose shape no apex off M can make into a good tet. The only move
// that keeps M certified is the one of Delaunay refinement of a surface (Boissonnat-Oudot):
// insert the face's surface point, the centre on Sigma of an empty ball through the face's
// vertices, and check every guarantee again, as for MeshOptions::facet_angle_deg. M then has
// other triangles there, and the tets are built again (mesh_field.cpp).
#include "closed_ball/restricted_facets.h"

#include <isodel/surface_mesh.h>

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace isodel::mesher {

/// The smallest and largest dihedral angles of the tetrahedron (a, b, c, d), in degrees.
std::pair<double, double> dihedral_range_deg(const std::array<double, 3>& a, const std::array<double, 3>& b,
                                             const std::array<double, 3>& c, const std::array<double, 3>& d);

/// For each tet of \p tets with a face on M (tets.triangles) and a dihedral angle below
/// \p min_deg or above \p max_deg, the surface point of its face on M with the largest empty
/// surface ball (ties: the smallest facet key), each face once, in the order of the tets.
/// \p vertex_ids: the Delaunay id of each of M's vertices (extract_surface); \p cache: the
/// facet records of the triangulation M was extracted from.
std::vector<Point> surface_sliver_points(const TetMesh& tets, const std::vector<std::uint32_t>& vertex_ids,
                                         const FacetCache& cache, double min_deg, double max_deg);

} // namespace isodel::mesher
