#pragma once
/// \file stats.h
/// What a meshing run did and measured (MeshResult::stats, include/isodel/mesh.h; the CLI's
/// --stats writes it as JSON with to_json), and the topology of one surface component, which the
/// mesher (MeshStats::components) and the verifier (include/isodel/verify.h) both report.
/// Plain structs only.
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace isodel {

/// Topology of one connected component of a closed surface mesh.
struct ComponentTopology {
    int euler = 0;            ///< Euler characteristic V - E + F
    int genus = 0;            ///< (2 - euler) / 2
    std::size_t triangles = 0;
};

/// What partitioned meshing did (MeshOptions::block_voxels or block_count > 0).
struct PartitionStats {
    int blocks = 0;                       ///< blocks of the partition
    int collar_voxels = 0;                ///< collar width (the widest axis), after any growth
    int collar_growths = 0;               ///< times the collar grew (an owned facet's ball left its block)
    int exchange_rounds = 0;              ///< rounds of point exchange until no block inserted a point
    std::size_t exchanged_points = 0;     ///< points a block received that were new to it (summed)
    std::size_t block_rebuilds = 0;       ///< MeshOptions::release_blocks: blocks built again from their points
    std::size_t block_points = 0;         ///< N points the blocks inserted
    std::size_t seam_points = 0;          ///< with tetrahedra: N points the merged triangulation added
    int processes = 1;                    ///< processes the blocks ran on (MeshOptions::transport)
    std::size_t max_process_peak_memory_bytes = 0; ///< the largest peak memory of one process
    /// mesh_isosurface_file: the most samples one process held from the file at once (its slab
    /// of the first pass, or its blocks' boxes), and what a whole read holds: both in samples
    /// held in memory, 512 per 8^3 leaf of values.
    std::uint64_t max_process_samples_read = 0, file_samples = 0;
};

/// Quality and size of the tetrahedral mesh (all figures over the returned tetrahedra).
struct TetStats {
    std::size_t vertices = 0, tets_inside = 0, tets_outside = 0;
    std::size_t g_prime = 0;              ///< grid points G' added (Section 4.1)
    /// Grid points (G or G') next to M removed after M was final, their Voronoi cells proven
    /// to miss Sigma (M unchanged): the slivers between an E point and its edge's sample.
    std::size_t grid_points_removed = 0;
    double volume_inside = 0, volume_outside = 0; ///< world units cubed, sums of tet volumes
    double volume_enclosed_by_surface = 0;        ///< of M, by the divergence theorem
    double min_dihedral_deg = 0, max_dihedral_deg = 0;
    double max_radius_edge = 0;           ///< circumradius / shortest edge, worst tet
    /// The same two figures over the tets with no vertex on M (grid-point tets: the bad
    /// elements of DELVOLMESH all touch M, see src/volume/tet_quality.h).
    double min_dihedral_deg_off_surface = 0, max_radius_edge_off_surface = 0;
    std::size_t tets_touching_surface = 0;
    std::size_t tets_below_10deg = 0;     ///< tets with a dihedral angle under 10 degrees
    std::vector<std::size_t> dihedral_histogram; ///< 18 bins of 10 degrees, 6 angles per tet
    /// Quality improvement (MeshOptions::improve_tets): the smallest dihedral angle of the
    /// Delaunay tets before it, vertices moved, vertices removed (edge collapses), vertices
    /// inserted (next to slivers of M) and flips made (the figures above are after).
    double min_dihedral_deg_delaunay = 0;
    std::size_t vertices_moved = 0, vertices_removed = 0, vertices_inserted = 0, flips = 0;
    double improvement_seconds = 0; ///< part of MeshStats::seconds["tets"]
    /// MeshStats::seconds["tets"] by step: insert_g_prime, conformity_checks (M unchanged and
    /// Theorem 3 for G'), crowding_points, region_labels, numbering, improvement, quality.
    std::map<std::string, double> seconds;
};

/// What certified adaptive meshing did (MeshOptions::adaptive); eps = coarsening + meshing.
struct AdaptiveStats {
    bool used = false;
    double eps_coarsening_world = 0; ///< the coarsening's budget, adaptive_share x eps
    double distance_world = 0;       ///< the largest certified distance (at most the budget); 0 when
                                     ///< the surface was meshed on the input's grid
    double eps_meshing_world = 0;    ///< eps - distance_world: the mesher's bound to the coarse Sigma
    std::vector<std::uint64_t> leaves_per_level; ///< of the grid meshed, level 0 first (one level on the input's grid)
    std::size_t cells_certified = 0; ///< unit cells the certificate was required of (0 when not built)
    std::size_t repair_rounds = 0, repair_splits = 0; ///< of the construction (0 when not built)
    std::size_t e_uniform = 0;  ///< grid-edge crossings of the input's grid
    std::size_t e_octree = 0;   ///< crossings of the octree's leaf edges (e_uniform when not built)
    std::size_t e_removable = 0; ///< the bound on what it could remove, before building (0 when
                                 ///< not computed: MeshOptions::adaptive_min_saving 0)
    bool meshed_on_octree = false; ///< false: the input's grid was meshed (the octree saved too little,
                                   ///< MeshOptions::adaptive_min_saving, or has no coarse leaf)
};

/// Why the triangle-quality pass (MeshOptions::facet_angle_deg) stopped.
enum class FacetAngleStop {
    Off,        ///< facet_angle_deg is 0: the pass did not run
    Met,        ///< every restricted facet has its smallest angle at or above the bound
    PointBound, ///< it inserted its bound of points (2 |E| + 10^4)
    NoProgress  ///< its remaining candidates are vertices already
};

/// "" (Off), "met", "point bound", "no progress": the words of the --stats JSON.
inline const char* to_string(FacetAngleStop stop)
{
    switch (stop) {
    case FacetAngleStop::Met: return "met";
    case FacetAngleStop::PointBound: return "point bound";
    case FacetAngleStop::NoProgress: return "no progress";
    case FacetAngleStop::Off: break;
    }
    return "";
}

/// Why the runs against the bad tets M pins down (MeshOptions::tet_min_dihedral_deg) stopped.
enum class TetSliverStop {
    Off,     ///< no tets, or no dihedral range
    Met,     ///< no tet with a face on M is out of the range
    RunBound ///< the last of its runs still left some
};

/// "" (Off), "met", "run bound": the words of the --stats JSON.
inline const char* to_string(TetSliverStop stop)
{
    switch (stop) {
    case TetSliverStop::Met: return "met";
    case TetSliverStop::RunBound: return "run bound";
    case TetSliverStop::Off: break;
    }
    return "";
}

/// What a run did and measured; serialised by to_json (include/isodel/mesh.h) and the CLI's --stats.
struct MeshStats {
    std::size_t e_points = 0, g_points = 0, n_topology = 0, n_geometry = 0, snapped = 0;
    /// With MeshOptions::facet_angle_deg: points it inserted (also counted in n_geometry), and
    /// why it stopped (Off without it).
    std::size_t n_facet_angle = 0;
    FacetAngleStop facet_angle_stop = FacetAngleStop::Off;
    /// With tets and a dihedral range (MeshOptions::tet_min_dihedral_deg): the points of Sigma
    /// inserted to free the bad tets M pinned down, the extra runs of the pipeline that took, and
    /// why it stopped.
    std::size_t n_tet_sliver = 0;
    int tet_sliver_runs = 0;
    TetSliverStop tet_sliver_stop = TetSliverStop::Off;
    std::size_t vertices = 0, triangles = 0;
    int rounds = 0;
    double effective_isovalue = 0.0; ///< v* (include/isodel/mesh.h: the tie rule)
    double eps_world = 0.0;
    /// Seconds per phase: read, points, delaunay, voxel_bound, closed_ball, refine, extract,
    /// tets, write, total (and blocks, the concurrent block phase of partitioned meshing;
    /// certify with MeshOptions::certify; resample for an adaptive input read densely;
    /// adaptive_grid with MeshOptions::adaptive).
    std::map<std::string, double> seconds;
    /// seconds["closed_ball"] + seconds["refine"] by step, over all rounds (the rest is
    /// bookkeeping): grid_cells (Theorem 3: Voronoi cells of G points), facet_records (crossings
    /// of the Voronoi edges of new facets), violation_scan (CBP_VE, CBP_VF, CBP_VC, paper eps),
    /// facet_loops (loops inside Voronoi facets), cell_disks (Sigma in a Voronoi cell is a disk),
    /// hausdorff (both one-sided distances per facet), creases, facet_angle, insertion (CGAL's
    /// insertions of N and of voxel-bound repairs) and voxel_bound_n (the voxel bound measured
    /// on the new points' Voronoi cells).
    std::map<std::string, double> refinement_seconds;
    std::size_t peak_memory_bytes = 0;
    /// Voxel bound (Theorem 2): the most cells a Voronoi cell of an E / N point met, and the
    /// bound it is held to.
    int max_cells_e = 0, max_cells_n = 0, bound_e = 4, bound_n = 27;
    std::size_t bound_repairs = 0;       ///< grid points added where a Voronoi cell left its bound
    std::vector<ComponentTopology> components;
    TetStats tets;                        ///< filled when MeshOptions::tets != None
    PartitionStats partition;             ///< filled by partitioned meshing
    AdaptiveStats adaptive;               ///< filled when MeshOptions::adaptive
    /// MeshOptions::certify: 1 when the mesh was verified, 0 without certify. It never exceeds
    /// 1: Sigma' has no knife-edge creases (octree/face_slabs.h), so there is no crease parameter
    /// a second meshing could vary, and a failed verification is final.
    int certify_attempts = 0;
};

} // namespace isodel
