#pragma once
// Internal: snapping (paper Section 5, `--snap`). Where at least three E points on the grid
// edges of one sample g lie within the snap radius of g, they are replaced by g itself, which
// becomes a vertex of M: fewer points, and no cluster of E points a hair apart around g (the
// near-degenerate triangles and tetrahedra they make). Sigma passes through each of them, so
// d(g, Sigma) < radius. A sample whose six edges are all crossed is never snapped (Sigma may
// enclose it: see snap_edge_points.cpp).
//
// The paper snaps within eps. We use eps / 2: the refinement of hausdorff_refinement.h aims
// every sampled M -> Sigma distance below 0.7 eps, and a vertex up to eps off Sigma would leave
// that aim out of reach around it (endless insertions); at eps / 2 it stays reachable and M is
// still within eps of Sigma. The topology is unaffected by where the points sit: the closed ball
// property (Edelsbrunner and Shah) is checked on the actual points, on Sigma or not.
#include "octree/edge_crossings.h"
#include "octree/sample_field.h"

#include <functional>
#include <vector>

namespace isodel::mesher {

struct SnapResult {
    std::vector<char> snapped;                 ///< per E point: replaced by a grid point
    std::vector<openvdb::Coord> grid_points;   ///< the grid points that took their place, sorted
    bool is_snapped_grid_point(const openvdb::Coord& g) const;
};

/// \p radius in world units. An E point within the radius of both ends of its edge (eps above
/// two voxels) goes to the nearer one. With \p allowed, only grid points it accepts take E
/// points' places (on an adaptive grid: points of G, adaptive_points.h).
SnapResult snap_edge_points(const std::vector<octree::EdgePoint>& points, const octree::SampleField& field,
                            double radius, const std::function<bool(const openvdb::Coord&)>& allowed = {});

} // namespace isodel::mesher
