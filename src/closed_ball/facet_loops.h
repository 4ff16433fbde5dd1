#pragma once
// Internal: the second clause of CBP_VF (paper Section 4.1): a Voronoi facet violates the closed
// ball property when Sigma meets it in a closed loop in its interior. The edge-count test of
// closed_ball.cpp cannot see such a loop: no Voronoi edge on the facet's boundary crosses it.
// Section 4.3 names the two ways it happens with trilinear F: a tunnel inside one cell (handled
// by the shoulder-like seeds of thin_tubes.h) and a loop through several cells, which the paper
// leaves open. On real data the second one is a thin tube or needle of Sigma hugging a grid edge
// (e.g. a small void around one sample whose tip runs up a grid edge): it pierces a Voronoi
// facet and M pinches it off or drops its tip.
//
// Detection. A loop bounds a disk D in the facet on which F has the opposite sign of the facet's
// boundary, so F restricted to the facet plane has an extremum of that sign inside D. Inside one
// cell F restricted to a plane is smooth; where the plane crosses grid edges F is only C0 and
// extrema of a tube's cross-section sit there: F on a cross-section of a tube along a grid edge
// is extremal on the edge. So we evaluate F at every point where the facet's plane crosses a
// grid edge inside the facet polygon (and at the extrema of F along the lines where the plane
// crosses grid faces); a point with the opposite sign of the boundary proves Sigma meets the
// facet's interior away from its boundary. The crossing of Sigma on the way from that point to
// the facet's boundary is inserted (the farthest such crossing from the dual Delaunay edge, as
// the paper asks). Loops whose extremum lies strictly inside one cell are the in-cell tunnels.
//
// In a facet that an arc of Sigma also crosses, a grid-edge point counts as a witness when no
// straight path in the facet leads from it to a Voronoi vertex of its own sign without crossing
// Sigma (a strongly curved arc can make a point such a witness without a loop).
//
// Facets skipped. A facet whose box F' keeps one sign on (box_sign.h), and a facet whose plane
// holds a direction along which F' never decreases on its box (monotone_in_plane.h), hold no
// loop and are not scanned: on such a facet a curved arc no longer adds its witness.
#include "closed_ball/closed_ball.h"
#include "octree/sample_field.h"

#include <functional>
#include <vector>

namespace isodel::mesher {

/// Finds Voronoi facets (dual to Delaunay edges with an E/N endpoint) that Sigma meets in a
/// closed loop. The first scan covers every such facet, later ones only the facets changed by
/// the points reported through touched() since (and the ones violated last time), so repeated
/// scans cost in proportion to the insertions.
class FacetLoopScanner {
public:
    /// Candidates in a deterministic order (by the edge's vertex ids). \p max_cells bounds the
    /// grid cells a facet may span (the voxel bound); larger facets are skipped.
    std::vector<Candidate> scan(const Delaunay& dt, const octree::SampleField& field, int max_cells);

    /// Every vertex inserted into \p dt after the first scan must be reported here.
    void touched(Vertex_handle v) { touched_.push_back(v); }
    /// Scans only edges with an end in \p region (all when empty): partitioned meshing's blocks.
    void set_region(std::function<bool(const Point&)> region) { region_ = std::move(region); }
    /// Returns, and scans again, only loops whose candidate \p keep accepts: another block's
    /// loops wait until a vertex is touched near them.
    void set_keep(std::function<bool(const Point&)> keep) { keep_ = std::move(keep); }

private:
    bool first_ = true;
    std::vector<Vertex_handle> touched_;
    std::vector<std::pair<Vertex_handle, Vertex_handle>> flagged_;
    std::function<bool(const Point&)> region_;
    std::function<bool(const Point&)> keep_;
};

} // namespace isodel::mesher
