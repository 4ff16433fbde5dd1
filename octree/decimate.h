#pragma once
/// \file decimate.h
/// Bottom-up coarsening of a sampled volume into an adaptive grid (paper Property IV; the bound
/// of Section 4.2 keeps meshing affordable on the result). Public entry: isodel::decimate
/// (include/isodel/adaptive.h). The pieces are exposed for tests and the benchmark.
///
/// Level by level (l = 1, 2, ...), a parent cell P of size 2^l replaces its 8 children when
///  1. all 8 children are leaves of level l-1 and P lies in the domain;
///  2. P's trilinear interpolant (from its 8 corner samples) reproduces every original fine
///     sample of P's closed span within T (so errors do not accumulate across levels);
///  3. no protected node lies in P's closed span (--iso/--band, --importance);
///  4. no leaf touching P is finer than l - k (merging keeps the grid k-balanced, balance.h).
/// Hanging-node constraints (interpolant.h) can move a fine cell's corner by up to T, so the
/// error of the continuous interpolant is then measured on every fine sample, leaves over T
/// are split and the grid rebalanced, until the measured max error is <= T.
#include "octree/adaptive_grid.h"

#include <isodel/adaptive.h>

#include <vector>

namespace isodel::octree {

/// Sample nodes that must stay corners of level-0 cells: corners of cells crossed by {F = iso}
/// dilated by ceil(band) voxels (26-neighbourhood), plus the active voxels of the importance grid.
openvdb::MaskGrid::Ptr protected_nodes(const AdaptiveGrid& g, const DecimateOptions& opt);

/// Max |F - f| of the continuous interpolant of \p g against \p original over every sample in the
/// closed span of a coarse leaf (elsewhere F interpolates the samples exactly). Leaves whose
/// error exceeds \p tolerance are appended to \p over when given.
double measure_max_error(const AdaptiveGrid& g, const openvdb::FloatGrid& original,
                         double tolerance = 0, std::vector<CellId>* over = nullptr);

/// Copy of the samples keeping only those the interpolant reads (leaf corners that are not
/// hanging nodes), the rest set inactive to background and pruned; the active bounding box's
/// extreme voxels are kept so the domain rule of sample_field.h still gives g.domain().
openvdb::FloatGrid::Ptr prune_samples(const AdaptiveGrid& g);

} // namespace isodel::octree
