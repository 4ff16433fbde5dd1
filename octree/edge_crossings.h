#pragma once
/// \file edge_crossings.h
/// E: the points where Sigma crosses grid edges (paper Section 4.1, step 1). On a cell edge the
/// trilinear interpolant is linear, so the crossing is exact: t = phi(a) / (phi(a) - phi(b)).
/// Samples are never exactly on v* (sample_field.h), so 0 < t < 1: E points never coincide
/// with grid points.
#include "octree/sample_field.h"

#include <openvdb/openvdb.h>

#include <array>
#include <functional>
#include <vector>

namespace isodel::octree {

struct EdgePoint {
    Vec3d index_pos; ///< position in index space (lower + t e_axis, rounded)
    Coord lower;     ///< lower endpoint of the grid edge
    int axis;        ///< 0,1,2: the edge runs from lower to lower + e_axis
    double t;        ///< the crossing's offset along the edge, 0 < t < 1 (the same wherever the edge is)
};

/// The four unit cells (by lower corner) around the edge from \p lower along \p axis.
inline std::array<Coord, 4> cells_around_edge(const Coord& lower, int axis)
{
    const int b = (axis + 1) % 3, c = (axis + 2) % 3;
    std::array<Coord, 4> cells;
    for (int q = 0; q < 4; ++q) {
        cells[q] = lower;
        cells[q][b] -= q & 1;
        cells[q][c] -= (q >> 1) & 1;
    }
    return cells;
}

struct EdgeCrossings {
    std::vector<EdgePoint> points;
    /// Cells (by lower corner) that Sigma passes through: the cells incident to a crossed edge.
    /// A trilinear cell whose corners all have one sign holds no part of Sigma (a multilinear
    /// function attains its extrema at the vertices), so these are all of them. Each once, in
    /// the iteration order of a MaskTree holding them (voxel_set.h).
    std::vector<Coord> crossed_cells;
};

/// Called on the calling thread between batches of blocks: \p done of \p total 8^3 blocks
/// (leaf nodes, and leaf-sized blocks at tile and domain faces) scanned. It may throw to cancel.
using BlockProgress = std::function<void(std::size_t done, std::size_t total)>;

/// All crossings on the edges of the sample lattice (domain grown by the outside ring), in
/// the order of a whole-box scan (z, y, x, axis).
EdgeCrossings edge_crossings(const SampleField& field, const BlockProgress& progress = {});

} // namespace isodel::octree
