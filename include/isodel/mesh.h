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
/// The function being meshed and its level set (one convention in the mesher, verify and the
/// tests; read more in octree/sample_field.h):
///  - F is the trilinear interpolant of the samples placed at their OpenVDB index points
///    (sample (i,j,k) at index (i,j,k)), mapped to world coordinates by the grid's transform;
///    inactive voxels read through the grid (background / tile values).
///  - Sigma = {F = v}, v = MeshOptions::isovalue. The inside is the side of v that
///    MeshOptions::inside names ({F > v} for Inside::Above, {F < v} for Inside::Below; default
///    Below for level-set grids, Above otherwise); M's triangles face the outside.
///  - Tie rule: a sample equal to v counts as above v (Sigma is the limit of {F = v - d},
///    d -> 0+). isodel meshes {F = v*} with v* just below v when a sample or saddle equals v
///    (v* = v otherwise); MeshStats::effective_isovalue reports v*.
///  - Beyond the active bounding box grown by one voxel F is on the outside side, so Sigma is a
///    set of closed surfaces.
#include <isodel/block_transport.h>
#include <isodel/interrupt.h>
#include <isodel/stats.h>
#include <isodel/surface_mesh.h>
#include <isodel/volume.h>

#include <openvdb/openvdb.h>

#include <array>
#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace isodel {

/// DELVOLMESH (paper Section 4.1): which tetrahedra of Del(E u G u N u G') to return.
/// Inside: the region {F inside v}, bounded by M. Outside: the rest of the grid's box (the active
/// bounding box grown by one voxel, enlarged to hold the protective layer; with graded spacing
/// its extent is then rounded up to a multiple of the largest spacing). Both: both, tagged.
enum class TetRegion { None, Inside, Outside, Both };

/// DELVOLMESH: how far apart the points it adds off Sigma (G') are, on a uniform grid.
/// Graded: spacing growing with the distance from the protective layer G in powers of two (1
/// voxel next to it with the default grading; see MeshOptions::tet_grading, tet_size), so the
/// tet count follows the surface, not the volume.
/// Uniform: every sample. On an adaptive grid G' is the leaf corners either way.
enum class TetSpacing { Graded, Uniform };

/// The smallest MeshOptions::block_voxels: the collar of cubic voxels.
constexpr int kMinBlockVoxels = 4;

/// The function MeshOptions::adaptive meshes.
enum class AdaptiveField {
    /// The certified octree's coarse interpolant, within adaptive_share x eps of the input's
    /// level set and isotopic to it; the mesher gets the rest of eps.
    Coarse,
    /// The input's own interpolant with the whole eps: the octree supplies only the point sets
    /// E and G, coarse where each component of Sigma still crosses a leaf edge (f strictly
    /// monotone along two axes around the leaf). adaptive_share is not used.
    Input
};

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
    /// With tets: the dihedral range the tets M pins down are held to. The tets phase never
    /// changes M, so a tet with a face on M still out of [tet_min_dihedral_deg,
    /// tet_max_dihedral_deg] after the improvement is held by that face: the face's surface
    /// point (a point of Sigma) is inserted and the pipeline runs again, every guarantee checked
    /// again (as for facet_angle_deg), up to 3 more runs (MeshStats::tet_sliver_stop). Off at 0
    /// and 180 (the default), and M is then the mesh of the same run without tets; 12 and 165
    /// with facet_angle_deg = 25 is the setting docs/tetrahedra.md measures.
    double tet_min_dihedral_deg = 0;
    double tet_max_dihedral_deg = 180;
    TetSpacing tet_spacing = TetSpacing::Graded; ///< G' on a uniform grid (TetSpacing)
    /// Graded G': a sample at chessboard distance d voxels from G (d >= 1) is kept when it lies
    /// on the lattice of spacing 2^l (counted from the box's lowest corner), 2^l the largest
    /// power of two with 2^l <= 1 + tet_grading * d and 2^l voxels <= tet_size, and l no larger
    /// than any sample of the box can reach. Nested lattices, so the points of a coarser zone are
    /// also points of the finer ones. > 0; at 1 or more, the samples next to G are already 2
    /// voxels apart.
    double tet_grading = 0.5;
    /// Graded G': the largest spacing in world units, counted in smallest voxel edges and
    /// rounded down to a power of two of them, from 1 to 1024 (tets there have edges up to about
    /// sqrt(3) times it); 0 = 8 voxels.
    double tet_size = 0;
    /// Partitioned meshing (paper Fig. 8), dense grids: > 0 cuts the domain into blocks of this
    /// many voxels per axis and meshes each block with a protective collar concurrently; the
    /// blocks exchange the points they insert and each hands out the triangles it owns
    /// (src/surface/partitioned_meshing.h, docs/partitioned.md). 0 = one block. Same guarantees
    /// either way. At least kMinBlockVoxels: each block is meshed with a collar of 6 voxels or
    /// more on each side, so smaller blocks repeat the same work many times over. At most 10^6
    /// blocks.
    int block_voxels = 0;
    /// Partitioned meshing into this many blocks of about equal work instead of cubes (0 = off;
    /// not with block_voxels): the count is factored into blocks per axis so that the cut faces,
    /// whose collars are meshed twice, are smallest (2 blocks: two slabs of the longest axis),
    /// and the cuts are placed where the grid-edge crossings split evenly. One block per process
    /// or thread spends the least on collars. The mesh depends on the count, not on who meshes
    /// the blocks. Blocks are at least kMinBlockVoxels wide.
    int block_count = 0;
    /// With block_voxels or block_count: the processes the blocks are spread over
    /// (block_transport.h), or null for this process's threads. Not with tets.
    BlockTransport* transport = nullptr;
    /// With block_voxels or block_count: hold at most one block per thread in memory. After
    /// each pass a block keeps only its owned facets and its points and frees its triangulation; when a
    /// neighbour's points arrive it is built again from E, G and its points and checked again
    /// in full. Lowers the peak memory of the processes holding several blocks, at the cost of
    /// the rebuilds. The full checks may insert other points than the kept block's incremental
    /// ones (the same guarantees); the mesh does not depend on the thread or process count.
    bool release_blocks = false;
    /// Check the surface with isodel's verifier (include/isodel/verify.h: topology against an
    /// independent computation of Sigma's, the eps bound, a closed oriented 2-manifold without
    /// self-intersections, Delaunay conformity) before returning it; when it fails,
    /// mesh_isosurface throws GuaranteeViolated saying why, so a wrong mesh is never returned.
    /// So does a reference topology the verifier cannot settle (near-critical data). Costs one
    /// full verification on top of the meshing (its own reference topology of Sigma).
    bool certify = false;
    /// Certified adaptive meshing (docs/adaptive.md): build an octree from the input and eps,
    /// coarse wherever a per-cell certificate proves the coarse level set isotopic to the input's
    /// and within adaptive_share x eps of it, and mesh on its leaves with the rest of eps. The
    /// guarantees I-III hold against the input's Sigma (certify checks them there). Dense input
    /// only, without block_voxels or block_count.
    bool adaptive = false;
    double adaptive_share = 0.5; ///< share of eps the coarsening may spend, in (0, 1)
    int adaptive_k = 1;          ///< level difference of touching leaves, in [1, 4]
    int adaptive_max_level = 5;  ///< coarsest leaf 2^level voxels, in [0, 15]
    /// The coarsening must pay for the share of eps it takes from the mesher: when the certified
    /// octree removes less than this share of the input's grid-edge crossings (the E points,
    /// and with them about as many closed-ball points), the surface is meshed on the input's
    /// own grid with the whole eps instead, exactly as without adaptive (AdaptiveStats says
    /// which). In [0, 1); 0 meshes on the octree whenever it has a coarse leaf.
    double adaptive_min_saving = 0.1;
    /// Which function an adaptive run meshes (docs/adaptive.md).
    AdaptiveField adaptive_field = AdaptiveField::Coarse;
};

struct AdaptiveVolume; // include/isodel/adaptive.h

struct MeshResult {
    SurfaceMesh surface;
    /// With MeshOptions::tets: the tetrahedra of the chosen region(s). Its first
    /// surface.vertices.size() vertices are surface.vertices in the same order, and
    /// tets.triangles == surface.triangles, so the inside region's boundary is M index for index.
    TetMesh tets;
    MeshStats stats;
    /// With MeshOptions::adaptive: the certified octree the surface was meshed on (corner
    /// samples, one mask per level), so its interpolant can be saved (save_adaptive) and checked
    /// by `isodel verify` like a decimated file. The samples share the input's tree (or hold the
    /// extended distances of a narrow-band level set). Null otherwise.
    std::shared_ptr<const AdaptiveVolume> adaptive_grid;
};

/// Checks \p options before any work: eps (or eps_voxels) positive and finite, threads,
/// max_rounds, max_points, block_voxels, block_count, facet_angle_deg, the tet dihedral range and
/// the adaptive options in their ranges, and adaptive without partitioned meshing.
/// \throw InvalidInput naming the option and the value it refuses
void check_mesh_options(const MeshOptions& options);

/// \p stats as a JSON object (counts, phase seconds, peak memory, voxel bounds, topology), the
/// format of the CLI's --stats; facet_angle_stop is written as to_string(FacetAngleStop).
std::string to_json(const MeshStats& stats);

/// Meshes {F = options.isovalue} of \p grid.
/// \throw InvalidInput isovalue outside the value range, empty grid, bad options
/// \throw GuaranteeViolated a stated bound stopped refinement (message names it)
/// \throw Cancelled the interrupter asked to stop
MeshResult mesh_isosurface(const openvdb::FloatGrid& grid, const MeshOptions& options,
                           Interrupter* interrupter = nullptr);

/// Meshes {F = options.isovalue} of the volume in the file \p path, partitioned
/// (options.block_voxels or block_count), with each process of options.transport reading only
/// part of the file (docs/partitioned.md): first one slab of it, for the tie rule's level and the
/// crossings that place and weigh the blocks (every process learns the whole volume's numbers),
/// then only its own blocks' boxes. The mesh is byte for byte mesh_isosurface's on the whole
/// volume. Formats read in part: MRC/CCP4, raw and float .vdb grids (ReadOptions::regions);
/// others (.inr, double grids), and runs with tetrahedra or options.certify (which need every
/// sample), are read whole on every process and meshed as mesh_isosurface does. Same exceptions as mesh_isosurface, and the readers' (the
/// messages start with the path); every process throws when one does.
MeshResult mesh_isosurface_file(const std::string& path, const ReadOptions& read, const MeshOptions& options,
                                Interrupter* interrupter = nullptr);

/// The same from the file's \p header, read already on every process as read_volume reads it
/// with an empty ReadOptions::regions (the header alone for the formats read in part, the whole
/// volume for the others); `isodel mesh` reads it first for the file's default inside side.
/// Every process calls the same overload: the one above reads the header as a collective step.
MeshResult mesh_isosurface_file(Volume header, const ReadOptions& read, const MeshOptions& options,
                                Interrupter* interrupter = nullptr);


/// Meshes {F = options.isovalue} of the adaptive interpolant F of \p volume (Property IV; e.g.
/// from `isodel decimate`). E, G and the tetrahedra's G' follow the leaves, so coarse regions
/// get fewer points; the voxel bound is counted in leaves and held to 3k+1 for E points
/// (MeshStats::bound_e). F is evaluated through its exact resampling on the finest lattice,
/// which is also what `isodel verify` checks the result against. Same exceptions as above;
/// options.adaptive is refused (the volume is adaptive already).
MeshResult mesh_isosurface(const AdaptiveVolume& volume, const MeshOptions& options,
                           Interrupter* interrupter = nullptr);

} // namespace isodel
