#pragma once
// Internal: DELSURFMESH steps 1-2 (paper Section 4), the points of the first triangulation:
// G, the protective layer of grid points around the crossed cells (octree/protective_layer.h;
// from the leaves on an adaptive grid, adaptive_points.h); E, the crossings of Sigma with grid
// edges (octree/edge_crossings.h; with --snap, those gathered around a sample give way to it,
// snap_edge_points.h); the thin-tube and tunnel-shoulder seeds of N (thin_tubes.h,
// tunnel_shoulders.h); and the seeds a run is handed (partitioned meshing's blocks).
#include "delaunay/delaunay.h"
#include "seeding/grid_point_mask.h"
#include "surface/mesh_field.h"
#include "octree/adaptive_grid.h"
#include "octree/protective_layer.h"
#include "octree/sample_field.h"

#include <isodel/interrupt.h>
#include <isodel/mesh.h>

#include <openvdb/openvdb.h>

#include <memory>
#include <utility>
#include <vector>

namespace isodel::mesher {

struct InitialPoints {
    /// G, then E, then the tube and shoulder seeds, then the run's seeds; ids 0, 1, ... in this
    /// order (the deterministic key of every later decision).
    std::vector<std::pair<Point, VertexInfo>> points;
    octree::ProtectiveLayer layer;               ///< G and its voxel bounds
    GridPointMask g_mask;                        ///< G's grid points (the repairs add to it)
    std::vector<openvdb::Coord> crossed_cells;   ///< lower corners of the cells Sigma crosses
};

/// The points of Del(E u G) for \p field (its face slabs already set). \p leaves: the reader
/// of \p adaptive (both null on a dense grid); \p use_snap: MeshOptions::snap. Fills st's e_points, g_points, bound_e, bound_n,
/// snapped and counts the seeds in n_topology / n_geometry.
/// \p cells_within (a block of partitioned meshing): only the crossings on edges inside it and
/// the crossed cells inside it count, so \p field may be clipped to it (SampleField's clipping
/// constructor), and the false crossings where its Sigma closes along the clip leave no points.
InitialPoints initial_points(const octree::SampleField& field, const octree::AdaptiveGrid* adaptive,
                             const octree::AdaptiveGrid::Reader* leaves, bool use_snap, double snap_radius,
                             const std::vector<SeedPoint>& seeds, MeshStats& st, Interrupter* interrupter,
                             const openvdb::CoordBBox* cells_within = nullptr);

} // namespace isodel::mesher
