#pragma once
// Internal: points on the thinnest tubes the trilinear Sigma has. When both samples of a grid
// edge are on one side and all four neighbours across the edge are on the other, the level set
// around the edge is a tube whose cross-section is a diamond with its corners on the four faces
// through the edge. To first order the Voronoi edge of the edge's end sample and two of its
// E points runs along such a tube exactly on Sigma, so whether it crosses is decided by
// rounding and the tube can pinch off in M (seen on random volumes and on samples equal to the
// isovalue). Like the paper's shoulder points for tunnels inside a cell (Section 4.1, after
// Lopes and Brodlie), we seed the tube with the four points where Sigma crosses the lines from
// the edge's midpoint across the four faces (F is linear on those lines: exact roots), when all
// four lie within half a voxel of the edge. They are N points of the topology phase.
#include "octree/sample_field.h"

#include <vector>

namespace isodel::mesher {

/// Index-space points on thin tubes around the lower-corner edges of \p crossed_cells.
std::vector<openvdb::Vec3d> thin_tube_points(const octree::SampleField& field,
                                             const std::vector<openvdb::Coord>& crossed_cells);

} // namespace isodel::mesher
