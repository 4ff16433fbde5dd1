#pragma once
/// \file segment_walk.h
/// Crossings of Sigma' with a segment: walk the unit cells the segment passes through, in order,
/// and within each the slab/core boxes (face_slabs.h); restrict the box's trilinear function to
/// the segment (a cubic), split it at its critical points into monotone pieces and isolate each
/// sign change by bisection (paper Section 5).
///
/// Robustness: the sign at every breakpoint (cell boundary, critical point) is evaluated once
/// and reused by both neighbouring pieces, so a root on a cell face is found exactly once;
/// phi == 0 counts as inside (+). A touching double root is not a crossing (Sigma is the limit
/// of a transversal level set). The walk is bounded: it stops after max_cells cells and says so.
#include "octree/sample_field.h"

#include <vector>

namespace isodel::octree {

struct SegmentCrossings {
    /// Parameters t in (0,1) of the crossings along a + t (b - a), increasing.
    std::vector<double> t;
    bool inside_at_start = false, inside_at_end = false;
    int cells_visited = 0;
    bool overflow = false; ///< the segment passed through more than max_cells cells
};

/// \p a, \p b in (mesh) index space; F is read through the field's face slabs (face_slabs.h),
/// so these are the crossings of Sigma' (of Sigma when h = 0). Segments longer than max_cells
/// cells report overflow and no roots.
SegmentCrossings segment_crossings(const SampleField::Reader& reader, const Vec3d& a,
                                   const Vec3d& b, int max_cells = 64);

/// phi at an index-space point: F' (face_slabs.h), trilinear on each box of its unit cell.
double phi_at(const SampleField::Reader& reader, const Vec3d& p);

} // namespace isodel::octree
