#pragma once
// Internal: the last clause of CBP_VC (paper Section 4.1): Vor(p) n Sigma must not be a surface
// of positive genus with a disk removed. closed_ball.cpp checks that the boundary of
// Vor(p) n Sigma is one curve, and Theorem 5 says that suffices for trilinear F on cubic
// voxels. It does not: the Voronoi cell of an E point can hold a torus minus a disk (sampled
// Euler characteristic -1) while every Voronoi edge and facet is a closed ball, and M is then one
// handle short (tests/closed_ball/test_handle_inside_voronoi_cell.cpp). The theorem's proof counts
// voxels, but a Voronoi cell spans parts of four voxels and a handle needs no closed loop on a
// voxel face.
//
// Certificate. If some direction d has d . grad F > 0 everywhere on Vor(p) n Sigma, a line
// parallel to d meets Vor(p) n Sigma at most once (Vor(p) is convex, and between two crossings
// in the direction of d, F would have to cross v downwards, where d . grad F <= 0). So
// Vor(p) n Sigma is a graph over its projection along d: a planar surface, which is a disk when
// its boundary is one curve. We take d = grad F(p) and prove the sign on boxes, cell by cell.
// In one cell each partial derivative of the trilinear F is bilinear in the other two
// coordinates, so d . grad F is multilinear and, like F itself, takes its extremes on an
// axis-aligned box at the box's corners: the corner values are exact bounds. A box is settled
// when F has one sign at its corners (no Sigma in it), or all corners are closer to one
// Delaunay neighbour than to p (outside Vor(p)), or d . grad F > 0 at every corner; otherwise it
// is split in eight, down to kMaxDepth. The argument holds in index coordinates (an affine
// image of world space, where Vor(p) is still convex).
//
// Fallback. A cell the certificate cannot settle (a disk that folds over itself relative to
// every direction tried, the tip of a thin tube, a blob around one sample: common near a
// molecular surface's small features) gets its Euler characteristic counted on a sample of Sigma
// at 1/16 voxel (cell_surface_euler.h). chi < 0 is a handle: a violation. chi >= 0 passes
// (chi 0 and 2 are left to the other checks; see voronoi_cell_disks.cpp).
//
// Limits: the sample misses handles thinner than 1/16 voxel, and a handle beside a second
// piece in the same cell (chi -1 + 1 = 0).
//
// Violation: of the points of Sigma found on the sign-changing edges of the unsettled boxes (F
// is linear along an axis-parallel segment in one cell), the one inside Vor(p) farthest from p
// is inserted - the paper's rule for CBP_VC. A vertex that passes stays passed: Voronoi cells
// only shrink as points are inserted, and a subset of a graph is a graph (of a planar surface,
// planar).
#include "closed_ball/closed_ball.h"
#include "octree/sample_field.h"

#include <vector>

namespace isodel::mesher {

struct VoronoiCellDiskStats {
    std::size_t certified = 0;  ///< vertices whose cell was certified in this call
    std::size_t sampled = 0;    ///< not certified, but Sigma n Vor(p) sampled has chi >= 0
    std::size_t unresolved = 0; ///< a handle (chi < 0) with no point of Sigma found to insert, or
                                ///< in a cell smaller than min_extent
    std::size_t directions = 0; ///< directions tried, over all vertices checked (none for a cell left
                                ///< unresolved before any: unbounded, or no normal at p)
};

/// Checks the surface vertices in \p pending (in order); returns one candidate per vertex whose
/// cell is not certified and keeps exactly the uncertified vertices in \p pending (newly
/// inserted surface vertices must be appended by the caller). A Voronoi cell reaching less than
/// \p min_extent (world) from its site is not refined further: it counts as unresolved (the
/// mesher passes the face slabs' half-width: Sigma' has no wedge sharper than that scale).
std::vector<Candidate> voronoi_cell_disk_violations(const Delaunay& dt, const octree::SampleField& field,
                                                    std::vector<Vertex_handle>& pending, double min_extent,
                                                    VoronoiCellDiskStats* stats = nullptr);

} // namespace isodel::mesher
