#pragma once
// Internal: how partitioned meshing (partitioned_meshing.h) cuts the domain into blocks. The
// blocks form a rectilinear lattice: per axis a list of cut positions, block x along that axis
// owning the cells between cut x and cut x + 1. Two ways to place the cuts:
//  - cubes of B voxels (MeshOptions::block_voxels), cut every B cells from the domain's corner;
//  - a given count of blocks of about equal work (MeshOptions::block_count): the count factored
//    into blocks per axis so that the cut faces are smallest (the collars, meshed twice, grow
//    with them), and along each cut axis the cuts placed where the grid-edge crossings, which
//    E, G, N and the checks grow with, split evenly. Two blocks are two slabs of the longest
//    axis, halved by their crossings: one block per process or thread wastes no collar on
//    blocks that would only be dealt to the same process anyway.
// Either way the partition depends on the volume and the option only, never on the thread or
// process count, and so does the mesh.
#include "octree/edge_crossings.h"
#include "octree/sample_field.h"
#include "surface/block_mesher.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace isodel::mesher {

/// Partitions of more blocks than this are refused: every block costs a task and a clipped
/// field even when empty, so a tiny block size on a large box would run for hours.
constexpr double kMaxBlocks = 1e6;

/// The block lattice's cut positions per axis: at[a][0] = the domain's first cell, increasing,
/// block x along axis a owns the cells with lower corners at[a][x] .. at[a][x + 1] - 1 (the last
/// block may reach past the domain; its own region is unbounded there anyway).
struct BlockCuts {
    std::array<std::vector<int>, 3> at;
};

/// Cuts every \p block_voxels cells from the domain's first cell.
/// \throw InvalidInput block_voxels < 1, or more than kMaxBlocks blocks
BlockCuts cubic_cuts(const octree::SampleField& field, int block_voxels);

/// \p count blocks of about equal work (the file comment): \p crossings are the field's E points
/// (edge_crossings), their lower sample's slice counted as the work of that slice. Every block is
/// at least kMinBlockVoxels cells wide along every axis.
/// \throw InvalidInput count < 1, or no factoring of count whose blocks are that wide
BlockCuts balanced_cuts(const octree::SampleField& field, int count, const std::vector<octree::EdgePoint>& crossings);

/// Per axis, the crossings whose lower sample lies in each slice of cells of \p domain (clamped to
/// its cells): what balanced_cuts weighs. Counts of parts of the crossings add up to the whole's.
using CrossingSlices = std::array<std::vector<std::int64_t>, 3>;
CrossingSlices crossing_slices(const openvdb::CoordBBox& domain, const std::vector<octree::EdgePoint>& crossings);

/// balanced_cuts from the counts per slice (crossing_slices) of a field with \p domain.
BlockCuts balanced_cuts(const openvdb::CoordBBox& domain, int count, const CrossingSlices& slices);

/// The blocks of \p cuts, in lexicographic (z, y, x) order, each core's samples grown by \p collar.
std::vector<BlockSpec> blocks_of(const BlockCuts& cuts, const std::array<int, 3>& collar);

/// The blocks whose boxes may read points of block \p i (a point of i lies in its own region):
/// every j whose box meets that region, in block order, without i itself.
std::vector<std::size_t> neighbours(const std::vector<BlockSpec>& specs, std::size_t i);

/// Each block's share of the work, the same on every process: the grid-edge crossings in its box
/// (E, and with it G and N, grow with them; the Delaunay triangulation and the checks follow the
/// points), plus one for a block's own set-up. Only for dealing blocks to processes.
std::vector<double> block_work(const std::vector<BlockSpec>& specs, const std::vector<octree::EdgePoint>& crossings);

} // namespace isodel::mesher
