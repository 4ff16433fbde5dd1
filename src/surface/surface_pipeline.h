#pragma once
// Internal: DELSURFMESH up to the refinement loop (paper Fig. 3, steps 1-3) on one field, with
// the loop ready to run: E and G (seeding/initial_points.h), Del(E u G) (delaunay/), and the
// refiner (refiner.h) over them. mesh_field runs it once for the whole field; partitioned
// meshing keeps one per block alive across its rounds of point exchange (block_mesher.h).
#include "delaunay/delaunay.h"
#include "octree/adaptive_grid.h"
#include "octree/sample_field.h"
#include "seeding/initial_points.h"
#include "surface/mesh_field.h"
#include "surface/refiner.h"

#include <isodel/interrupt.h>
#include <isodel/mesh.h>

#include <cstdint>
#include <memory>

namespace isodel::mesher {

class SurfacePipeline {
public:
    /// Steps 1-3 on run.field with face slabs for options' eps; \p keep: which violations the
    /// refiner fixes, \p near: which elements it checks (RefinerInput; all when empty).
    /// Stage seconds go to st.seconds ("points", "delaunay").
    /// When Sigma crosses no grid edge (empty()) there is no triangulation and no refiner.
    /// \p options and \p st must outlive the pipeline (the refiner reads and counts there).
    SurfacePipeline(const FieldRun& run, const MeshOptions& options, CandidateFilter keep, CandidateFilter near,
                    MeshStats& st, Interrupter* interrupter);
    // The refiner points into the members (field, mask, triangulation): never copied or moved.
    SurfacePipeline(const SurfacePipeline&) = delete;
    SurfacePipeline& operator=(const SurfacePipeline&) = delete;

    bool empty() const { return !refiner_; }
    /// F' (the run's field with the face slabs the mesher reads).
    const octree::SampleField& field() const { return field_; }
    const octree::AdaptiveGrid::Reader* leaves() const { return leaves_.get(); }
    Delaunay& dt() { return dt_; }
    const Delaunay& dt() const { return dt_; }
    Refiner& refiner() { return *refiner_; }
    const Refiner& refiner() const { return *refiner_; }
    /// G's grid points (the voxel-bound repairs add to them).
    GridPointMask& g_mask() { return ip_.g_mask; }
    /// Vertex ids below this are E, G and seeds; the loops' points come after.
    std::uint32_t first_inserted() const { return first_inserted_; }

private:
    octree::SampleField field_;
    std::unique_ptr<octree::AdaptiveGrid::Reader> leaves_;
    InitialPoints ip_;
    Delaunay dt_;
    std::uint32_t first_inserted_ = 0;
    std::unique_ptr<Refiner> refiner_;
};

} // namespace isodel::mesher
