#pragma once
// Internal: the quality figures of a tetrahedral mesh that DELVOLMESH (paper Section 4.1) reports
// (dihedral angle range and histogram, radius-edge ratio, region volumes), and the volume a
// closed surface mesh encloses, computed independently of any tetrahedra (divergence theorem),
// against which the inside volume is checked.
#include <isodel/mesh.h>

namespace isodel::mesher {

/// Signed volume of the tetrahedron (a, b, c, d): positive when (b-a, c-a, d-a) is right-handed,
/// CGAL's positive orientation.
double signed_tet_volume(const std::array<double, 3>& a, const std::array<double, 3>& b,
                         const std::array<double, 3>& c, const std::array<double, 3>& d);

/// Volume enclosed by a closed, outward oriented triangle mesh: sum of the signed volumes of the
/// cones from a reference point (the first vertex, to keep the terms small) to the triangles.
double enclosed_volume(const SurfaceMesh& mesh);

/// Fills counts, region volumes, dihedral range and histogram and the worst radius-edge ratio of
/// \p mesh into \p st (other fields untouched). Vertices with index < \p surface_vertices are
/// M's: the figures are also given over the tets with none of them. Where those join lattice
/// points of a grid with cubic voxels they are pieces of its cubes (min dihedral 35.26 deg =
/// atan(1/sqrt 2), radius-edge sqrt(3)/2). Not a bound: anisotropic voxels give flatter boxes
/// (smaller angles as the aspect ratio grows), and N points that are not vertices of M make
/// slivers with grid points. The worst elements touch M, where E points sit anywhere along
/// grid edges.
void measure_tet_quality(const TetMesh& mesh, std::size_t surface_vertices, TetStats& st);

} // namespace isodel::mesher
