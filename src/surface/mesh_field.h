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

/// A point of N known before the run: partitioned meshing's blocks hand theirs to the merge.
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
    /// Block mode: stop once the surface phase is done and append here the N points the closed
    /// ball and eps loops inserted, in insertion order; no surface, no tets. A field without
    /// crossings returns at once.
    std::vector<SeedPoint>* inserted = nullptr;
    /// Which violations this run fixes (by their candidate point); all when empty.
    CandidateFilter keep;
    /// When set: every vertex of Del(E u G u N) once M is final (before the tetrahedra's G'),
    /// world coordinates, in insertion (id) order (final_points.h).
    std::vector<std::array<double, 3>>* final_points = nullptr;
};

/// The side that is inside: options.inside, else Below for level sets and Above otherwise.
Inside inside_side(const openvdb::FloatGrid& grid, const MeshOptions& options);

/// DELSURFMESH (paper Fig. 3) on run.field; the exceptions of mesh_isosurface.
MeshResult mesh_field(const FieldRun& run, const MeshOptions& options, Interrupter* interrupter);

} // namespace isodel::mesher
