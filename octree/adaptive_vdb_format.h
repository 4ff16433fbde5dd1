#pragma once
/// \file adaptive_vdb_format.h
/// The adaptive grid as a .vdb file, readable by stock OpenVDB tools (vdb_print lists it):
///  - the sample grid under its own name (e.g. "density"), float precision, with metadata
///      isodel_adaptive (int, format version 1), isodel_k (int), isodel_levels (int, incl. 0),
///      isodel_tolerance (double), isodel_source (string), isodel_domain_min/max (vec3i);
///  - one MaskGrid "level_<l>" per level l = 1..L (voxel o >> l on = leaf of size 2^l at o; its
///    transform is the sample transform scaled by 2^l so it is drawn in place). Level 0 is
///    implied (unit cells not covered by coarser leaves), so a uniform volume stores no mask.
/// Also the conversions between the public AdaptiveVolume and the internal AdaptiveGrid.
#include "octree/adaptive_grid.h"

#include <isodel/adaptive.h>

namespace isodel::octree {

constexpr int kAdaptiveFormatVersion = 1;

/// Shares the volume's grids (no copy).
AdaptiveGrid to_adaptive_grid(const AdaptiveVolume& v);
/// True when \p g carries the isodel_adaptive marker.
bool is_adaptive_sample_grid(const openvdb::GridBase& g);

} // namespace isodel::octree
