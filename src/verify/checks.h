#pragma once
// Internal to verify: one function per check, each in its own .cpp (see verify_surface.cpp for
// how they combine into the report).
#include "verify/trilinear_field.h"

#include <isodel/surface_mesh.h>
#include <isodel/verify.h>

#include <vector>

namespace isodel::verify {

/// Check 1 (reference_topology.cpp).
ReferenceTopologyReport reference_topology(const TrilinearField& field, int refine, int max_refine, double budget);

/// Check 2, combinatorial part (mesh_topology.cpp). \p tri_component receives, per triangle, the
/// index of its component in report.components. \throw InvalidInput index out of range.
MeshTopologyReport mesh_topology(const SurfaceMesh& mesh, std::vector<int>& tri_component);

/// Check 2, orientation against the field (mesh_orientation.cpp): sets inward_components, outward.
void check_outward(const TrilinearField& field, const SurfaceMesh& mesh,
                   const std::vector<int>& tri_component, MeshTopologyReport& rep);

/// Check 2, CGAL self-intersection test (self_intersection.cpp).
void check_self_intersections(const SurfaceMesh& mesh, MeshTopologyReport& rep);

/// Check 3 (hausdorff.cpp). \p eps in world units (> 0).
HausdorffReport hausdorff(const TrilinearField& field, const SurfaceMesh& mesh, double eps, int sigma_refine);

/// Check 4 (delaunay_conformity.cpp).
DelaunayReport delaunay_conformity(const SurfaceMesh& mesh);

/// Check 5 (triangle_quality.cpp).
QualityReport triangle_quality(const SurfaceMesh& mesh);

} // namespace isodel::verify
