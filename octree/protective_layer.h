#pragma once
/// \file protective_layer.h
/// G: the protective layer of grid points around Sigma (paper Section 4.1 step 2, Theorems 2, 3).
///
/// Our choice: every sample within r_a cells (per axis a) of a crossed cell, i.e. the samples of
/// the block of cells [C - r, C + r] around each crossed cell C. With r = 1 on cubic voxels this
/// is the paper's layer "twice as thick" as in 2D. Why the traps then hold:
///  - E point e on an a-edge of crossed cells: Vor(e) lies in the slab between the bisector
///    planes of e and the edge's endpoints (both in G), and within the 2 x 2 cells around the
///    edge, because every point y on the outer faces of those cells is within half a face
///    diagonal of a grid point of G but at least one voxel from e (Theorem 2, Lemma 1): 4 cells.
///    This needs lattice planes orthogonal to the edge; on a sheared lattice e is held to the
///    N-point block below (it lies in a crossed cell too).
///  - N point n in crossed cell C: a point y on the boundary of the block of (2r+1)^3 cells
///    around C is at distance >= r_a h_a from n (h_a: spacing of the lattice planes across axis
///    a) and within the face lattice's covering radius R_a of a G point on that face. r_a is the
///    smallest integer with r_a h_a > R_a, so y is closer to G than to n; Voronoi cells are
///    convex, so Vor(n) lies in the block: at most prod(2 r_a + 1) cells (27 on cubes).
///  - Theorem 3 (Voronoi facets and edges among grid points miss Sigma) holds for any superset
///    of the paper's single layer, since adding points only shrinks Voronoi elements.
#include "octree/sample_field.h"

#include <openvdb/openvdb.h>

#include <array>
#include <vector>

namespace isodel::octree {

struct ProtectiveLayer {
    std::array<int, 3> radius{1, 1, 1}; ///< r_a
    int bound_e = 4;                    ///< cells a Voronoi cell of an E point may meet (bound_n if sheared)
    int bound_n = 27;                   ///< ... of an N point
    std::vector<Coord> points;          ///< G, in deterministic order
    /// G as a mask when it was built as one (many crossed cells spread over a large box), else
    /// null: the mesher's set of grid points starts from it instead of building the same tree
    /// again, and builds it from \ref points when it is null.
    openvdb::MaskGrid::Ptr mask;
};

/// Per-axis layer radius for the transform of \p field (1 on cubic and mildly anisotropic voxels).
std::array<int, 3> layer_radius(const SampleField& field);

/// Whether the lattice axes of \p field's transform are mutually orthogonal (Theorem 2's 4-cell
/// trap for E points needs it; sheared maps get the N-point bound for E points too).
bool orthogonal_lattice(const SampleField& field);

/// G around \p crossed_cells (lower corners; an empty list gives the radius and bounds only).
ProtectiveLayer protective_layer(const SampleField& field, const std::vector<Coord>& crossed_cells);

} // namespace isodel::octree
