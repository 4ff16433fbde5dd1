#pragma once
// Reference implementations on an adaptive grid, for the tests: point location, the leaf edges
// and their exact crossings with Sigma (E points), the protective layer G of crossed leaves, the
// leaves a segment crosses in order, and F restricted to a segment inside one leaf (a cubic for
// trilinear F, paper Section 4.3). Written independently of the mesher's own E and G on the
// leaves (src/seeding/adaptive_points.h), so that tests can compare the two; all are exact on a
// uniform grid (one level) and agree with the uniform-grid code there.
#include "octree/adaptive_queries.h"
#include "octree/interpolant.h"
#include "octree/sample_field.h"

#include <optional>
#include <vector>

namespace isodel::octree {

/// The leaf containing index-space point \p p (floor convention; points on the domain's upper
/// faces go to the last cell). nullopt outside the cells of the domain.
std::optional<CellId> leaf_containing(const AdaptiveGrid::Reader& r, const Vec3d& p);

/// A leaf edge: an edge of a leaf cell between two consecutive nodes (a coarse edge is split at
/// the corners of finer leaves lying on it). Values are the continuous interpolant at the nodes.
struct LeafEdge {
    Coord start;  ///< lower node
    int axis = 0; ///< 0, 1, 2
    int length = 1;
    double v0 = 0, v1 = 0; ///< F at start and at start + length * e_axis
    Coord end() const
    {
        Coord e = start;
        e[axis] += length;
        return e;
    }
};

/// The leaf edges on the 12 edges of \p c (each edge split at the nodes of all leaves around it).
std::vector<LeafEdge> leaf_edges(const InterpolantReader& r, const CellId& c);

/// An E point: where Sigma crosses a leaf edge. On an edge, trilinear F is linear, so the crossing
/// is exact: t = phi0 / (phi0 - phi1) (phi from SampleField::phi_of_value, Section 4.1 step 1).
struct AdaptiveEdgeCrossing {
    LeafEdge edge;
    double t = 0;  ///< in [0,1] along the leaf edge
    Vec3d point;   ///< index space
};

/// All E points of the adaptive grid, each leaf edge once, in deterministic order. Level-0 cells
/// are visited sparsely (value_cells_sparse), coarse leaves from their masks.
/// \p field must read the same samples (SampleField over g.samples_ptr()).
std::vector<AdaptiveEdgeCrossing> adaptive_edge_crossings(const AdaptiveGrid& g,
                                                         const SampleField& field);

/// True when the resolved corner phi values of \p c are not all of one sign (phi > 0 inside).
bool is_crossed(const InterpolantReader& r, const SampleField& field, const CellId& c);

/// G on the adaptive grid (Section 4.1 step 2): the nodes of every crossed leaf and of every leaf
/// touching one, the one-cell layer of protective_layer.h in leaf adjacency. Sorted, unique.
std::vector<Coord> adaptive_protective_layer(const AdaptiveGrid& g, const SampleField& field);

/// One leaf crossed by a segment a + t (b - a), for t in [t0, t1].
struct SegmentPiece {
    CellId cell;
    double t0 = 0, t1 = 0;
};

/// The leaves the segment passes through, in order of t, clipped to the domain's cells; the
/// pieces are contiguous (t1 of one = t0 of the next).
std::vector<SegmentPiece> walk_segment(const AdaptiveGrid::Reader& r, const Vec3d& a, const Vec3d& b);

/// F(a + t (b - a)) inside leaf \p c as a polynomial in t (valid for the t range where the
/// segment is in c): a cubic for the trilinear interpolant.
Cubic restrict_to_segment(const InterpolantReader& r, const CellId& c, const Vec3d& a, const Vec3d& b);

} // namespace isodel::octree
