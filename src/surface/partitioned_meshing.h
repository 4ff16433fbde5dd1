#pragma once
// Partitioned meshing after the paper's Fig. 8 (Section 6): the volume is cut into blocks; each
// block is meshed on its own, with a protective collar of voxels around it, concurrently with
// the others; their points are merged into one Delaunay triangulation.
//
// Why a collar suffices (Theorems 2 and 3): the Voronoi cell of an E or N point is trapped by G
// within r voxels of the point's cell (r = the protective layer's radius, 1 on cubic voxels),
// so every decision about a point of the block's core - which Voronoi edges, facets and cells
// meet Sigma, and where - depends only on the samples and points within about 2r + 1 voxels
// of the core. A block therefore sees Sigma through a SampleField clipped to core + collar
// (collar 2r + 2 voxels; beyond it F is "outside", which closes Sigma along the box, far from
// the core). It fixes only violations whose point lies within one voxel of its core
// (FieldRun::keep): refining the collar, or the creases where the clipped Sigma meets the box,
// is a neighbour's work or nobody's. It stops when nothing is left to fix there, or when its
// last candidates are vertices already (a neighbour's violation seen from the edge), and keeps
// only the points it inserted inside its core.
//
// Why the merge has no seams: the merge is not a stitching of block surfaces. It runs the
// whole DELSURFMESH loop (closed ball, then eps) on Del(E u G u N_blocks) over the full field,
// so every guarantee is checked on the merged triangulation; what the blocks could not see
// (points of a neighbour's core within the collar) shows up as the few violations along the
// block faces, which the merge fixes like any other (PartitionStats::seam_points). The merge
// costs one Delaunay triangulation plus one full pass of checks, which can eat up what the
// blocks save (docs/architecture.md, "Partitioned meshing"); the blocks carry the refinement.
//
// Self-contained blocks (so they can later run on separate machines): a block's input is its
// box of samples (BlockSpec::box) with the field's level v* and outside value, and its
// output is a list of points (mesh_block); nothing else is shared.
#include "surface/mesh_field.h"

#include <openvdb/openvdb.h>

#include <array>
#include <vector>

namespace isodel::mesher {

struct BlockSpec {
    std::array<int, 3> index{};  ///< position in the block lattice
    openvdb::CoordBBox core;     ///< the cells the block owns (lower corners, inclusive)
    openvdb::CoordBBox box;      ///< the samples it reads: core's samples grown by the collar
    /// The points it keeps, in index space: own_lo <= q < own_hi per axis. The core's cells,
    /// unbounded on the domain's outer faces (points on the ring belong to the outermost blocks).
    openvdb::Vec3d own_lo, own_hi;
};

/// The protective collar, in voxels per axis, for \p field: 2r + 2 with r the layer radius.
std::array<int, 3> collar_voxels(const octree::SampleField& field);

/// Partitions of more blocks than this are refused: every block costs a task and a clipped
/// field even when empty, so a tiny block size on a large box would run for hours.
constexpr double kMaxBlocks = 1e6;

/// Blocks of \p block_voxels cells per axis covering the cells of field.domain(), in
/// lexicographic (z, y, x) order.
/// \throw InvalidInput block_voxels < 1, or more than kMaxBlocks blocks
std::vector<BlockSpec> partition_domain(const octree::SampleField& field, int block_voxels,
                                        const std::array<int, 3>& collar);

/// Meshes \p block alone (the surface phase of DELSURFMESH on field clipped to block.box) and
/// returns the N points its loops inserted in the cells of block.core, in insertion order.
/// \p interrupter is only asked wasInterrupted() (blocks run concurrently).
std::vector<SeedPoint> mesh_block(const octree::SampleField& field, const BlockSpec& block,
                                  const MeshOptions& options, Interrupter* interrupter = nullptr);

/// Partitioned DELSURFMESH: blocks concurrently (TBB), then the merge described above.
/// Output depends on options.block_voxels, never on the thread count.
MeshResult mesh_partitioned(const octree::SampleField& field, const MeshOptions& options, Interrupter* interrupter);

} // namespace isodel::mesher
