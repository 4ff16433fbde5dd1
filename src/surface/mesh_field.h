#pragma once
// Internal: DELSURFMESH on a SampleField (mesh_field.cpp), the entry point shared by the
// public mesh_isosurface overloads and partitioned meshing (partitioned_meshing.h).
#include "closed_ball/closed_ball.h"
#include "delaunay/delaunay.h"
#include "octree/adaptive_grid.h"
#include "octree/sample_field.h"

#include <isodel/interrupt.h>
#include <isodel/mesh.h>

#include <array>
#include <vector>

namespace isodel::mesher {

/// A point known before the run: partitioned meshing hands the blocks' points to the merge
/// (with tetrahedra) and between blocks.
struct SeedPoint {
    std::array<double, 3> p; ///< world coordinates
    PointKind kind;          ///< Topology or Geometry
};

struct FieldRun {
    const octree::SampleField* field = nullptr;
    /// With an adaptive grid, field reads its exact resampling on the finest lattice and the
    /// point sets follow the leaves (adaptive_points.h).
    const octree::AdaptiveGrid* adaptive = nullptr;
    /// Inserted with E and G into the first triangulation, then checked like every point.
    std::vector<SeedPoint> seeds;
    /// A block of partitioned meshing: E, G and the tube and shoulder seeds come from the cells
    /// inside this box of samples only (scanned through field clipped to it); field is read
    /// unclipped everywhere else.
    const openvdb::CoordBBox* point_box = nullptr;
    /// When set: every vertex of Del(E u G u N) once M is final (before the tetrahedra's G'),
    /// world coordinates, in insertion (id) order (final_points.h).
    std::vector<std::array<double, 3>>* final_points = nullptr;
};

/// This process's peak resident memory so far (MeshStats::peak_memory_bytes).
std::size_t peak_memory_bytes();

/// The side that is inside: options.inside, else Below for level sets and Above otherwise.
Inside inside_side(const openvdb::FloatGrid& grid, const MeshOptions& options);

/// DELSURFMESH (paper Fig. 3) on run.field; the exceptions of mesh_isosurface.
MeshResult mesh_field(const FieldRun& run, const MeshOptions& options, Interrupter* interrupter);

} // namespace isodel::mesher
