#pragma once
// Internal: DELSURFMESH steps 4-5, the refinement loop (paper Fig. 3). Each round looks for
// violations class by class in a fixed priority order and inserts the candidates of the first
// class present, then looks again; the loop ends when every check passes (M is certified) or a
// stated bound stops it (GuaranteeViolated names the bound). The order, highest first:
//  1. Theorem 3 for grid points (grid_cell_check.h): first of all, before the facet table's
//     first scan, since these rounds insert most of N and need no facet records;
//  2. the facet table's classes (closed_ball.h: voxel-bound holes, CBP_VE, grid vertices,
//     CBP_VF, CBP_VC, the paper's eps criterion);
//  3. loops inside Voronoi facets (facet_loops.h, CBP_VF's second clause);
//  4. Sigma in each Voronoi cell a disk (voronoi_cell_disks.h, CBP_VC's last clause);
//  5. the measured Hausdorff distance, facets then creases (hausdorff_refinement.h);
//  6. optionally, the facet angle (MeshOptions::facet_angle_deg), after every guarantee holds.
// A class is asked only when every class before it found nothing, so the later, costlier
// checks run on a triangulation the earlier ones have settled.
#include "closed_ball/closed_ball.h"
#include "closed_ball/facet_loops.h"
#include "delaunay/delaunay.h"
#include "delaunay/point_insertion.h"
#include "octree/adaptive_grid.h"
#include "octree/sample_field.h"
#include "refinement/hausdorff_refinement.h"
#include "seeding/grid_point_mask.h"

#include <isodel/interrupt.h>
#include <isodel/mesh.h>

#include <openvdb/openvdb.h>

#include <array>
#include <cstdarg>
#include <cstdint>
#include <vector>

namespace isodel::mesher {

/// What the loop reads and where it counts (mesh_field.cpp sets it up).
struct RefinerInput {
    const octree::SampleField* field = nullptr;             ///< F', face slabs set
    const octree::AdaptiveGrid* adaptive = nullptr;         ///< null on a dense grid
    const octree::AdaptiveGrid::Reader* leaves = nullptr;   ///< adaptive's reader, or null
    GridPointMask* g_mask = nullptr;                        ///< G's grid points; repairs add to it
    std::array<int, 3> layer_radius{{1, 1, 1}};             ///< G's trap block radius per axis
    double eps = 0;          ///< the bound M is refined to against Sigma' (world)
    double snap_radius = 0;  ///< how far snapped vertices may be from Sigma' (0 without --snap)
    double slab_h_world = 0; ///< the face slabs' half-width in world units
    CandidateFilter keep;    ///< which violations this run fixes (all when empty)
    /// Which Voronoi elements this run checks, by their vertices (all when empty): a block of
    /// partitioned meshing checks those whose candidates may fall in its own region (keep).
    CandidateFilter near;
};

class Refiner {
public:
    /// \p crossed_cells: the cells Sigma crosses (the crease check samples them). \p next_id:
    /// the id the next inserted vertex gets.
    Refiner(Delaunay& dt, const RefinerInput& in, std::vector<openvdb::Coord> crossed_cells, const MeshOptions& options,
            MeshStats& stats, std::uint32_t next_id, Interrupter* interrupter);

    /// Theorem 2 measured on the first triangulation: the cells met by the Voronoi cells of
    /// E and N points, held to their bounds; points beyond them are repaired in the first round.
    void measure_voxel_bound();
    /// Rounds until every check passes (for the violations RefinerInput::keep selects). With
    /// \p stop_without_progress (a block of partitioned meshing) a round whose candidates are
    /// all vertices already ends the run instead of throwing, and returns false.
    /// \throw GuaranteeViolated at a bound.
    bool run(bool stop_without_progress = false);
    /// Partitioned meshing: inserts points a neighbouring block inserted (block_mesher.h) and
    /// hands them to the checks as this run's own would be, but measures no voxel bound for
    /// them (their own block does). Returns how many were not vertices already.
    std::size_t insert_received(const std::vector<std::pair<Point, PointKind>>& points);

    const FacetCache& cache() const { return cache_; }
    FacetCache& cache() { return cache_; } ///< the tets phase inserts G' through it
    std::uint32_t next_id() const { return next_id_; }
    /// The segment-walk bound of the Voronoi edge searches, in unit cells.
    int max_cells_walk() const { return max_cells_walk_; }

private:
    using Check = ViolationReport (Refiner::*)();
    ViolationReport grid_cells_and_facets(double& update_seconds);
    /// Theorem 3's violations (grid_cell_check.h) whose candidates keep accepts.
    std::vector<Candidate> grid_cell_candidates();
    ViolationReport facet_loops();
    ViolationReport cell_disks();
    ViolationReport hausdorff_distances();
    ViolationReport facet_angles();
    /// The classes after the facet table's, in priority order (the list is the order).
    static const Check kLaterChecks[4];

    /// Adds the grid points of the trap block around each vertex whose Voronoi cell left its
    /// bound (a hole in G): never a wider search.
    void repair_bound_holes();
    InsertionResult insert_batch(const std::vector<Candidate>& candidates, Violation kind);
    /// CBP_VE cascades are local: follows them on the facets the insertions changed; returns
    /// the points it inserted.
    std::size_t follow_voronoi_edge_cascade();
    void record_voxel_bound(Vertex_handle v, int cells, bool edge_point);
    bool is_near(const Vertex_handle& v) const { return !in_.near || in_.near(v->point()); }
    /// Surface facets with one crossing: the restricted facets of M.
    std::vector<const FacetCache::Entry*> restricted_facets() const;
    /// A trace line for the caller's log (Interrupter::log), formatted as printf does.
    void log(const char* format, ...) const __attribute__((format(printf, 2, 3)));

    Delaunay& dt_;
    RefinerInput in_;
    const MeshOptions& options_;
    MeshStats& st_;
    Interrupter* interrupter_;
    std::uint32_t next_id_;
    std::size_t max_points_;
    std::size_t max_angle_points_;
    int max_cells_walk_;
    double hash_cell_;
    double lattice_step_; ///< world step of the point lattice every candidate is rounded to
    FacetCache cache_;
    HausdorffRefinement hausdorff_;
    FacetLoopScanner loops_;
    ViolationFinder violations_;
    std::vector<Vertex_handle> over_bound_;   ///< vertices whose Voronoi cell left its bound
    std::vector<Vertex_handle> grid_pending_; ///< grid points whose Voronoi cell may meet Sigma
    std::vector<Vertex_handle> grid_deferred_; ///< ... where the point to insert is a neighbour's
    std::vector<Vertex_handle> disk_pending_; ///< surface vertices not yet certified a disk
};

} // namespace isodel::mesher
