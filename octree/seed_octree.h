#pragma once
/// \file seed_octree.h
/// An octree that supplies only the point sets E and G, while the mesher reads the input's own
/// interpolant f (MeshOptions::adaptive_field = AdaptiveField::Input, docs/adaptive.md "Seeds
/// from the octree, F from the input").
///
/// The certified octree of certified_coarsening.h meshes a coarse interpolant and pays for it
/// with a share of eps: on a smooth level set a trilinear leaf of edge h is off by about
/// h^2 / (4R), which stops the leaves at Sigma at 4 voxels at eps = 0.5 voxel. Here the level set
/// is never moved, so no eps is spent, and a leaf needs only what the mesher needs of its seeds:
/// every component of Sigma must cross a leaf edge (so that E has a point on it), as it does on
/// a grid of trilinear cells (the paper's E, Section 4.1, taken from the leaves of an octree as
/// Section 4.2 allows).
///
/// The certificate of a leaf L (seed_leaf_certified) holds when its span is off Sigma (every
/// sample node of the closed span of one strict sign; f is a convex combination of its corners
/// on each unit cell), or when f is strictly monotone along TWO axes d != e, each with its own
/// strict sign, on every band cell (corners not all of one strict sign) of L's span and its
/// one-cell rim. Then every component of Sigma n L meets an edge of L:
///  - on a unit cell, the d-derivative of a trilinear f is bilinear in the other two
///    coordinates, with its extremes at the four d-edge differences; so strict edge signs give
///    a strict derivative on the closed cell. With the rim, every point of Sigma in the closed L
///    has a neighbourhood of cells where f is strictly monotone along d and along e;
///  - so a segment in L parallel to d crosses Sigma at most once (consecutive crossings would
///    have the same direction, impossible between two sign changes), and no component of
///    Sigma n L is closed in L's interior: each meets a face of L;
///  - on every face of L one of d, e lies in the face, and the same argument along it shows
///    that Sigma n face has no closed curve: each curve ends on the face's boundary, an edge
///    of L.
/// Every component of Sigma therefore crosses a leaf edge: in a certified coarse leaf by the
/// above, in a unit cell because a trilinear function has no interior extremum on the cell or
/// its faces. Splitting a certified leaf (balance) keeps its children certified: their spans
/// and rims lie in the parent's. Nothing else of the mesher's guarantee rests on the octree;
/// its closed-ball and eps checks read f.
#include "octree/adaptive_grid.h"
#include "octree/sample_field.h"

#include <isodel/interrupt.h>

namespace isodel::octree {

/// The shape of the seed octree.
struct SeedOctreeOptions {
    int k = 1;         ///< level difference of touching leaves
    int max_level = 5; ///< coarsest leaf: 2^max_level voxels
};

/// The largest leaf edge, in voxels, that Sigma may cross: its span and rim are read into memory
/// ((edge + 3)^3 values). Leaves off Sigma may be coarser (up to SeedOctreeOptions::max_level).
constexpr int kMaxBandLeafVoxels = 64;

/// The certificate of parent cell \p p (see the file comment) on \p f; false for a parent that
/// Sigma crosses with an edge over kMaxBandLeafVoxels.
bool seed_leaf_certified(const SampleField::Reader& f, const CellId& p);

/// Builds the grid bottom-up: level by level, a parent whose eight children are leaves replaces
/// them when seed_leaf_certified accepts it and the grid stays k-balanced; then balance().
/// The corner samples are \p fine's (the mesher does not read them).
/// \throw Cancelled when \p interrupter asks to stop.
AdaptiveGrid seed_octree(const SampleField& fine, const SeedOctreeOptions& options, Interrupter* interrupter = nullptr);

} // namespace isodel::octree
