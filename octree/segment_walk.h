#pragma once
/// \file segment_walk.h
/// Crossings of Sigma with a segment: walk the unit cells the segment passes through, in order,
/// restrict the cell's trilinear interpolant to the segment (a cubic), split it at its critical
/// points into monotone pieces and isolate each sign change by bisection (paper Section 5).
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

/// Knife-edge creases: the trilinear Sigma is only C0 across cell faces, and where F has a ridge
/// on a face the two sheets meet along the face at an arbitrarily small dihedral angle. A wedge
/// is scale invariant, so near its edge Voronoi edges cross both sheets at every scale and the
/// closed ball refinement would never end. Two consecutive crossings with a grid plane between
/// them (or within `separation` of one) are the two sheets of such a wedge's tip and cancel when
/// both lie within `trim` of the crease curve (Sigma on that plane, first-order distance), or when
/// they are closer than `separation` to each other. That meshes Sigma with the wedge's tip cut
/// off, which is isotopic to Sigma; `trim` (a fraction of eps) bounds how much of the tip goes,
/// `separation` (1e-4 voxel) only acts on wedges sharper than separation / trim radians.
/// Next to a face saddle whose neck is under 4 trims the crease curve's two branches pass within
/// a neck of each other; there the trim shrinks to a quarter neck, not below a quarter trim
/// (segment_walk.cpp, crease_trace). Zero tolerances keep every crossing. All in index units.
///
/// Not next to a critical grid edge: where both samples of a grid edge lie within
/// `critical_edge` of v and F turns back in both directions across the edge (a saddle, a needle
/// or a slot of Sigma along it: the four trilinear patches around the edge meet there, e.g.
/// cells/random_n16_s4), Sigma is not a wedge and cutting its thin parts changes its topology;
/// pairs within 4 trims of such an edge are kept (the `separation` rule still applies). A side
/// within `critical_edge` of v counts as turning either way. A single ridge across an edge near
/// v is an ordinary fin and is cut as usual.
struct CreaseTolerance {
    double separation = 0.0;
    double trim = 0.0;
    double critical_edge = 0.0; ///< |phi| of both samples below this (0: no such guard)
};

/// \p a, \p b in index space. Segments longer than max_cells cells report overflow and no roots.
SegmentCrossings segment_crossings(const SampleField::Reader& reader, const Vec3d& a,
                                   const Vec3d& b, int max_cells = 64,
                                   const CreaseTolerance& crease = CreaseTolerance());

/// phi at an index-space point (trilinear in its unit cell).
double phi_at(const SampleField::Reader& reader, const Vec3d& p);

} // namespace isodel::octree
