#include "octree/value_scan.h"

#include "octree/critical_values.h"
#include "octree/stored_tiles.h"

#include <openvdb/tree/LeafManager.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <array>

namespace isodel::octree {
namespace {

using openvdb::Coord;
using openvdb::CoordBBox;
using Tree = openvdb::FloatTree;
using LeafRange = openvdb::tree::LeafManager<const Tree>::LeafRange;

/// The leaves of \p tree meeting \p owned in parallel, each thread folding into its own copy of
/// \p scan.
template <typename Body>
void for_each_leaf(const Tree& tree, const CoordBBox& owned, ValueScan& scan, const Body& body)
{
    openvdb::tree::LeafManager<const Tree> leaves(tree);
    tbb::enumerable_thread_specific<ValueScan> local(scan);
    tbb::parallel_for(leaves.leafRange(), [&](const LeafRange& range) {
        ValueScan& mine = local.local();
        for (auto leaf = range.begin(); leaf; ++leaf)
            if (owned.hasOverlap(leaf->getNodeBoundingBox())) body(*leaf, mine);
    });
    for (const ValueScan& s : local) scan.join(s);
}

} // namespace

void scan_stored_values(const openvdb::FloatGrid& grid, const CoordBBox& lattice, bool ring_reads_background,
                        const CoordBBox& owned, ValueScan& scan)
{
    // F's samples that read the grid (sample_field.h): the lattice, and the ring around it when
    // the ring reads the background; beyond them every sample reads "outside", whatever is stored.
    CoordBBox samples = lattice;
    if (ring_reads_background) samples.expand(1);
    CoordBBox region = samples;
    region.intersect(owned);
    for_each_stored_tile(grid.tree(), region, [&](const CoordBBox&, float value, bool) { scan.consider(value); });
    for_each_leaf(grid.tree(), region, scan, [&](const Tree::LeafNodeType& leaf, ValueScan& mine) {
        for (auto v = leaf.cbeginValueAll(); v; ++v)
            if (region.isInside(v.getCoord())) mine.consider(*v);
    });
}

// Only faces and cells whose corners straddle v matter (otherwise a corner sample is nearer to v
// than the saddle), and only those with a corner on an active voxel. A bilinear face saddle
// exactly at v makes Sigma non-manifold just like a sample at v and follows the same rule; so
// does a cell's interior saddle.
void scan_critical_values(const openvdb::FloatGrid& grid, const CoordBBox& lattice, bool ring_reads_background,
                          const CoordBBox& owned, ValueScan& scan)
{
    const double v = scan.v;
    tbb::enumerable_thread_specific<openvdb::FloatGrid::ConstAccessor> accessors([&] { return grid.getConstAccessor(); });
    for_each_leaf(grid.tree(), owned, scan, [&](const Tree::LeafNodeType& leaf, ValueScan& mine) {
        auto& acc = accessors.local();
        for (auto it = leaf.cbeginValueOn(); it; ++it) {
            const Coord c = it.getCoord();
            if (!owned.isInside(c)) continue;
            // A face or cell reaching into a ring that reads as outside is not one of F's samples.
            const bool whole_cell = ring_reads_background || lattice.isInside(c.offsetBy(1));
            auto corner = [&](int n) { return c.offsetBy(n & 1, (n >> 1) & 1, (n >> 2) & 1); }; // bits x, y, z
            std::array<double, 8> f;
            for (int n = 0; n < 8; ++n) f[n] = acc.getValue(corner(n));
            for (int axis = 0; axis < 3; ++axis) {
                const int e1 = 1 << ((axis + 1) % 3), e2 = 1 << ((axis + 2) % 3);
                if (!ring_reads_background && !lattice.isInside(corner(e1 | e2))) continue;
                const double a = f[0], b = f[e1], cc = f[e2], d = f[e1 | e2];
                if (std::min({a, b, cc, d}) > v || std::max({a, b, cc, d}) < v) continue;
                double sv;
                if (face_saddle_value(a, b, cc, d, sv)) mine.critical(sv);
            }
            if (!whole_cell) continue;
            const auto [lo, hi] = std::minmax_element(f.begin(), f.end());
            if (*lo > v || *hi < v) continue;
            CellCritical points[2];
            const int np = cell_critical_points(f, points);
            for (int k = 0; k < np; ++k) mine.critical(points[k].value);
        }
    });
}

std::uint64_t active_voxels_in(const openvdb::FloatGrid& grid, const CoordBBox& owned)
{
    // Value masks and tiles only: a delay-loaded leaf's values stay on disk.
    std::uint64_t n = 0;
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) {
        const CoordBBox nb = leaf->getNodeBoundingBox();
        if (!owned.hasOverlap(nb)) continue;
        if (owned.isInside(nb)) {
            n += leaf->onVoxelCount();
            continue;
        }
        for (auto on = leaf->getValueMask().beginOn(); on; ++on)
            if (owned.isInside(leaf->offsetToGlobalCoord(on.pos()))) ++n;
    }
    for_each_stored_tile(grid.tree(), owned, [&](const CoordBBox& b, float, bool active) {
        if (!active) return;
        CoordBBox part = b;
        part.intersect(owned);
        if (!part.empty()) n += std::uint64_t(part.volume());
    });
    return n;
}

/// Samples held in memory by \p grid: its leaves whose values are loaded (a delay-loaded .vdb
/// loads a leaf when first read), 512 each.
std::uint64_t samples_in_memory(const openvdb::FloatGrid& grid)
{
    std::uint64_t n = 0;
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf)
        if (!leaf->buffer().isOutOfCore()) n += Tree::LeafNodeType::SIZE;
    return n;
}

} // namespace isodel::octree
