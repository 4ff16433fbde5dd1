#pragma once
// Internal: meshing that also hands back the final point set E u G u N, every vertex of the
// Delaunay triangulation once M is final. For the benchmarks (a bare Delaunay triangulation of
// the same points, tools/bench/compare_bench) and the closed ball audit (tools/qa/cbp_audit);
// not part of the public API, whose users want M, not the mesher's working set.
#include <isodel/interrupt.h>
#include <isodel/mesh.h>

#include <openvdb/openvdb.h>

#include <array>
#include <vector>

namespace isodel::mesher {

/// mesh_isosurface(grid, options, interrupter), and in \p points the final point set in
/// insertion (id) order, world coordinates. \throw InvalidInput with partitioned meshing
MeshResult mesh_keeping_points(const openvdb::FloatGrid& grid, const MeshOptions& options,
                               std::vector<std::array<double, 3>>& points, Interrupter* interrupter = nullptr);

} // namespace isodel::mesher
