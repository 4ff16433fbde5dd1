#pragma once
/// \file mesh.h
/// DELSURFMESH: a surface mesh M of a level set Sigma = {F = v} of the trilinear interpolant F of a
/// sampled volume, with the paper's guarantees (Goswami, Gillette, Bajaj, Sections 4.1-4.3 and 5):
///  I.   M is homeomorphic to Sigma (closed ball property of Vor(E u G u N), Theorem 1);
///  II.  the two-sided Hausdorff distance between M and Sigma is at most eps (the paper's
///       circumcentre criterion, then local measurement: src/refinement/hausdorff_refinement.h);
///  III. M is a subcomplex of the Delaunay triangulation of its vertices;
///  IV.  the same on adaptive grids (see octree/).
///
/// The function being meshed (one convention in the mesher, verify and the tests):
///  - F is the trilinear interpolant of the samples at OpenVDB index points, mapped to world by
///    the grid's transform; inactive voxels read through the grid (background / tile values).
///  - A sample exactly equal to v counts as above v: Sigma is the limit of {F = v - d}, d -> 0+.
///    isodel meshes {F = v*} with v* = effective_isovalue(...) (see octree/sample_field.h).
///  - Beyond the active bounding box grown by one voxel F is on the outside side, so Sigma is a
///    set of closed surfaces.
#include <isodel/interrupt.h>
#include <isodel/surface_mesh.h>
#include <isodel/volume.h>

#include <openvdb/openvdb.h>

#include <array>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace isodel {

/// DELVOLMESH (paper Section 4.1): which tetrahedra of Del(E u G u N u G') to return.
/// Inside: the region {F inside v}, bounded by M. Outside: the rest of the grid's box (the active
/// bounding box grown by one voxel, enlarged to hold the protective layer). Both: both, tagged.
enum class TetRegion { None, Inside, Outside, Both };

struct MeshOptions {
    double isovalue = 0.0;               ///< v, in value units
    std::optional<Inside> inside;        ///< default: Below for level-set grids, Above otherwise
    double eps = 0.0;                    ///< Hausdorff bound in world units; 0 = use eps_voxels
    double eps_voxels = 0.5;             ///< ... in units of the smallest voxel edge
    bool snap = false;                   ///< Section 5: snap E points within eps/2 of a grid point
    int threads = 0;                     ///< 0 = all hardware threads; result does not depend on it
    std::size_t max_points = 0;          ///< cap on inserted points N; 0 = 100 x |E| + 10^6
    int max_rounds = 2000;               ///< cap on insertion rounds
    /// Triangle quality, optional (0 = off): after every guarantee holds, restricted facets
    /// whose smallest angle is under this many degrees get their surface point inserted (the
    /// guarantees are checked again after each insertion), as in Delaunay refinement of smooth
    /// surfaces (Boissonnat-Oudot). A high angle need not be reachable within the bound of
    /// 2 |E| + 10^4 points: E points a hair apart on the grid edges around one sample force
    /// graded refinement there, unlike on a smooth surface. Why it stopped:
    /// MeshStats::facet_angle_stop.
    double facet_angle_deg = 0;
    TetRegion tets = TetRegion::None;    ///< also build a tetrahedral mesh (DELVOLMESH)
    /// Improve the worst tets (smoothing and collapses of vertices off M, flips and edge removal
    /// within a region): M, the region tags and the volumes stay; the tets are no longer all
    /// Delaunay. false keeps Del(E u G u N u G') restricted to the region(s).
    bool improve_tets = true;
    /// Partitioned meshing (paper Fig. 8), dense grids: > 0 cuts the domain into blocks of this
    /// many voxels per axis, meshes each block with a protective collar concurrently, then
    /// merges their points in one Delaunay triangulation whose closed-ball and eps checks fix
    /// the seams (src/surface/partitioned_meshing.h). 0 = one block. Same guarantees either way.
    int block_voxels = 0;
    /// Check the surface with isodel's verifier (include/isodel/verify.h: topology against an
    /// independent computation of Sigma's, the eps bound, a closed oriented 2-manifold without
    /// self-intersections, Delaunay conformity) before returning it; when it fails,
    /// mesh_isosurface throws GuaranteeViolated saying why, so a wrong mesh is never returned.
    /// So does a reference topology the verifier cannot settle (near-critical data). Costs one
    /// full verification on top of the meshing (its own reference topology of Sigma).
    bool certify = false;
};

/// What partitioned meshing did (MeshOptions::block_voxels > 0).
struct PartitionStats {
    int blocks = 0;                       ///< blocks holding crossings of Sigma
    int collar_voxels = 0;                ///< collar width (the widest axis)
    int blocks_failed = 0;                ///< blocks whose run stopped at a bound (merge redoes them)
    std::size_t block_points = 0;         ///< N points the blocks contributed to the merge
    std::size_t seam_points = 0;          ///< N points the merge inserted (seams)
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

/// Topology of one connected component of a closed surface mesh.
struct ComponentTopology {
    int euler = 0;
    int genus = 0;
    std::size_t triangles = 0;
};

/// What a run did and measured; serialised by the CLI's --stats.
struct MeshStats {
    std::size_t e_points = 0, g_points = 0, n_topology = 0, n_geometry = 0, snapped = 0;
    /// With MeshOptions::facet_angle_deg: points it inserted (also counted in n_geometry), and
    /// why it stopped: "met", "point bound" or "no progress" (candidates already vertices).
    std::size_t n_facet_angle = 0;
    std::string facet_angle_stop;
    std::size_t vertices = 0, triangles = 0;
    int rounds = 0;
    double effective_isovalue = 0.0;
    double eps_world = 0.0;
    /// Seconds per phase: read, points, delaunay, voxel_bound, closed_ball, refine, extract,
    /// tets, write, total (and blocks, the concurrent block phase of partitioned meshing;
    /// certify with MeshOptions::certify; resample for an adaptive input read densely).
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
    PartitionStats partition;             ///< filled when MeshOptions::block_voxels > 0
    /// MeshOptions::certify: 1 when the mesh was verified, 0 without certify. It never exceeds
    /// 1: Sigma' has no knife-edge creases (octree/face_slabs.h), so there is no crease parameter
    /// a second meshing could vary, and a failed verification is final.
    int certify_attempts = 0;
};

struct MeshResult {
    SurfaceMesh surface;
    /// With MeshOptions::tets: the tetrahedra of the chosen region(s). Its first
    /// surface.vertices.size() vertices are surface.vertices in the same order, and
    /// tets.triangles == surface.triangles, so the inside region's boundary is M index for index.
    TetMesh tets;
    MeshStats stats;
};

/// Checks \p options before any work: eps (or eps_voxels) positive and finite, threads,
/// max_rounds, max_points, block_voxels and facet_angle_deg in their ranges.
/// \throw InvalidInput naming the option and the value it refuses
void check_mesh_options(const MeshOptions& options);

/// \p stats as a JSON object (counts, phase seconds, peak memory, voxel bounds, topology).
std::string to_json(const MeshStats& stats);

/// Meshes {F = options.isovalue} of \p grid.
/// \throw InvalidInput isovalue outside the value range, empty grid, bad options
/// \throw GuaranteeViolated a stated bound stopped refinement (message names it)
/// \throw Cancelled the interrupter asked to stop
MeshResult mesh_isosurface(const openvdb::FloatGrid& grid, const MeshOptions& options,
                           Interrupter* interrupter = nullptr);

struct AdaptiveVolume; // include/isodel/adaptive.h

/// Meshes {F = options.isovalue} of the adaptive interpolant F of \p volume (Property IV; e.g.
/// from `isodel decimate`). E, G and the tetrahedra's G' follow the leaves, so coarse regions
/// get fewer points; the voxel bound is counted in leaves and held to 3k+1 for E points
/// (MeshStats::bound_e). F is evaluated through its exact resampling on the finest lattice,
/// which is also what `isodel verify` checks the result against. Same exceptions as above.
MeshResult mesh_isosurface(const AdaptiveVolume& volume, const MeshOptions& options,
                           Interrupter* interrupter = nullptr);

} // namespace isodel
