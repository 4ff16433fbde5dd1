#pragma once
// Partitioned meshing after the paper's Fig. 8 (Section 6), without a global merge: the volume
// is cut into blocks; each block meshes its core and a protective collar (block_mesher.h),
// concurrently with the others; the blocks exchange the points they insert until no block
// inserts any more; each block then hands out the restricted facets it owns, and the mesh is
// their union, vertices merged along the seams by their (identical) coordinates.
//
// Why it is the global mesh (docs/partitioned.md proves it): at the end every block holds,
// inside its trusted box, exactly the global point set P; a facet whose two Delaunay balls lie
// there is therefore a facet of Del(P) with the same dual Voronoi edge, restricted exactly when
// it is restricted in Del(P). Every facet is owned by one block (the one whose own region holds
// its smallest vertex). A block that owns a restricted facet whose ball leaves its trusted box
// refuses it, and the partition is redone with a wider collar (bounded, then GuaranteeViolated).
// The assembled surface is also checked to be closed, each edge in two triangles of opposite
// orientation, before it is returned.
//
// Why the checks are the global ones (Theorems 2 and 3): the Voronoi cell of an E or N point is
// trapped by G within r voxels of its cell, so every violation, and the point that fixes it,
// depends only on points and samples within a few voxels; each violation is fixed by the block
// whose own region holds its candidate point, and its neighbours receive the point.
//
// With tetrahedra, the blocks' points (E, G and the exchanged N) are merged into one Delaunay
// triangulation for DELVOLMESH, whose loop re-checks every guarantee there first.
#include "surface/block_mesher.h"
#include "surface/block_partition.h"
#include "surface/mesh_field.h"

#include <openvdb/openvdb.h>

#include <array>
#include <functional>
#include <vector>

namespace isodel::mesher {

/// The first protective collar, in voxels per axis, for \p field: 2r + 4 with r the layer radius
/// (the trusted margin r + 2, and two voxels of Voronoi cells beyond the core).
std::array<int, 3> collar_voxels(const octree::SampleField& field);

/// Rounds of point exchange before the run is given up (GuaranteeViolated).
constexpr int kMaxExchangeRounds = 64;
/// Times the collar grows by two voxels when an owned facet's ball leaves its block.
constexpr int kMaxCollarGrowths = 3;

/// The collar after \p growth growths (0 <= growth <= kMaxCollarGrowths): collar_voxels(field),
/// two voxels wider per growth.
std::array<int, 3> grown_collar(const octree::SampleField& field, int growth);

/// Blocks of \p block_voxels cells per axis covering the cells of field.domain(), in
/// lexicographic (z, y, x) order (blocks_of(cubic_cuts(...))).
/// \throw InvalidInput block_voxels < 1, or more than kMaxBlocks blocks
inline std::vector<BlockSpec> partition_domain(const octree::SampleField& field, int block_voxels,
                                               const std::array<int, 3>& collar)
{
    return blocks_of(cubic_cuts(field, block_voxels), collar);
}

/// Assembles the blocks' triangles into one indexed mesh: vertices by first appearance (blocks
/// in order), triangles ordered as extract_surface orders them. Returns false, leaving \p mesh
/// empty, unless every edge lies in exactly two triangles of opposite orientation.
bool assemble_surface(const std::vector<BlockSurface>& parts, SurfaceMesh& mesh);

/// What partitioned meshing decides from the whole volume before a block meshes: where the
/// blocks are cut and, when several processes share them, each block's work for the deal
/// (BlockRanks::deal), one list per collar width tried (kMaxCollarGrowths + 1 of them).
struct PartitionPlan {
    BlockCuts cuts;
    std::vector<std::vector<double>> work; ///< empty when the blocks are not dealt
};

/// Each block's work (block_work of \p crossings) at every collar width the run may try, one
/// list per growth: PartitionPlan::work.
std::vector<std::vector<double>> block_work_per_collar(const octree::SampleField& field, const BlockCuts& cuts,
                                                       const std::vector<octree::EdgePoint>& crossings);

/// The plan from \p field itself (its grid-edge crossings for the balanced cuts and the work).
PartitionPlan plan_partition(const octree::SampleField& field, const MeshOptions& options, bool deal);

/// The field the blocks of this process read: called with their boxes before they are built
/// (again after the collar grows); it must read every sample of those boxes as the whole
/// volume's field does and stay alive until the next call. Called with no box, it must return
/// the whole field (tetrahedra merge every block's points on one triangulation).
using BlockFieldSource = std::function<const octree::SampleField&(const std::vector<openvdb::CoordBBox>& boxes)>;

/// Partitioned DELSURFMESH as described above (TBB tasks, one per block), on \p field.
/// Output depends on the partition (options.block_voxels or block_count), never on the thread or
/// process count.
MeshResult mesh_partitioned(const octree::SampleField& field, const MeshOptions& options, Interrupter* interrupter);

/// The same with the plan made beforehand and the samples from \p source; \p frame gives
/// what does not depend on the samples (transform, domain, level), its grid may be empty. The
/// mesh is mesh_partitioned(field, ...)'s when the plan is plan_partition(field, ...)'s and the
/// source reads field's samples.
MeshResult mesh_partitioned(const octree::SampleField& frame, const PartitionPlan& plan, const BlockFieldSource& source,
                            const MeshOptions& options, Interrupter* interrupter);

} // namespace isodel::mesher
