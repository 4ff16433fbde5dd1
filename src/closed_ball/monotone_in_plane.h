#pragma once
// Internal: a certificate that a Voronoi facet holds no closed loop of Sigma' (CBP_VF's second
// clause, paper Section 4.1; facet_loops.h) without scanning the facet.
//
// Claim. Let P be a plane of normal N and R a box. If some direction u != 0 with N . u = 0
// has u . grad F' >= 0 on every cell meeting R, then Sigma' n P n R holds no closed curve
// bounding a disk D in P n R on which F' is not zero. Proof: take q in D with F'(q) != 0, say
// F'(q) > 0 (otherwise use -u). F' is continuous and piecewise trilinear, so it does not
// decrease along the ray q + t u; the ray leaves D through its boundary curve, where F' = 0 <
// F'(q). A Voronoi facet lies in its bounding box, so the scan of facet_loops.cpp may skip it.
//
// The direction is found axis by axis, exactly. On a unit cell the k-derivative of the
// trilinear F is bilinear in the other two coordinates, so its extremes over the closed cell are
// the four k-edge differences of the samples; their signs (exact: the sign of a difference of
// doubles) give s_k, the weak sign of dF/dx_k on all cells, when they agree. F' = F o phi with
// phi non-decreasing on each axis (face_slabs.h), so dF'/dx_k has the weak sign s_k too. Then
// u = sum a_k s_k e_k with a_k >= 0 on signed axes has u . grad F' = sum a_k s_k dF'/dx_k >= 0,
// and one of them is orthogonal to N iff some signed axis has N_k = 0, or two signed axes i, j
// have s_i N_i > 0 > s_j N_j. On a smooth surface this holds for facets dual to Delaunay edges
// along Sigma (N nearly tangent to Sigma), and fails for those across it (N nearly normal),
// where a cap of Sigma can indeed meet the facet in a loop.
#include "octree/sample_field.h"

#include <optional>

namespace isodel::mesher {

/// A direction u != 0 with N . u = 0 (up to rounding of its two nonzero components) along which
/// F' does not decrease on any cell meeting the box [lo, hi] (index space); none when the
/// edge-difference signs give none (see the file comment). Reads the corners of every cell of
/// the box until the signs left cannot give one.
std::optional<octree::Vec3d> monotone_direction_in_plane(const octree::SampleField::Reader& reader,
                                                         const octree::Vec3d& lo, const octree::Vec3d& hi,
                                                         const octree::Vec3d& N);

} // namespace isodel::mesher
