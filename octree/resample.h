#pragma once
/// \file resample.h
/// Adaptive -> dense: the continuous interpolant sampled at every finest sample (isodel::resample
/// in include/isodel/adaptive.h). Exact for trilinear: inside a leaf of size 2^l, F is the
/// trilinear function of the leaf's (resolved) corners, and a trilinear function restricted to any
/// unit sub-cell is the trilinear function of that sub-cell's corner values, so the dense grid's
/// own trilinear interpolant equals the adaptive F everywhere (paper Section 2: any local
/// interpolant; Property IV: a mesh of the decimated volume can be checked on the dense one).
#include "octree/adaptive_grid.h"

namespace isodel::octree {

/// Dense samples of \p g: a copy of g.samples() with every node in the closed span of a coarse
/// leaf set to F. Nodes inside the original active bounding box (domain shrunk by one) holding a
/// non-background value become active; the others stay inactive with their value, so the domain
/// rule of sample_field.h gives g.domain() again and sparse inputs stay sparse.
openvdb::FloatGrid::Ptr resample_dense(const AdaptiveGrid& g);
/// The same, starting from a copy of \p base instead of g.samples(): nodes outside every coarse
/// leaf's closed span keep \p base's values, the rest come from the leaves' interpolant (which
/// reads its corners from g.samples()). Certified coarsening (certified_coarsening.h) passes the
/// input as \p base when the corners come from an extended level set (extended_level_set.h).
openvdb::FloatGrid::Ptr resample_dense(const AdaptiveGrid& g, const openvdb::FloatGrid& base);

} // namespace isodel::octree
