// mesh_isosurface_file (include/isodel/mesh.h): partitioned meshing in which each process reads
// only part of the file. Two passes over the file, each process reading its share:
//  1. a slab of the lattice (one layer of samples more at its top, for the edges and cells that
//     cross into the next slab): its samples and face and cell saddles for the tie rule
//     (value_scan.h: minima, maxima and an "or", joined over the processes into the scan of the
//     whole volume, so every process meshes the same v* as one process on the whole file), then
//     the grid-edge crossings whose lower end it owns, counted per slice and per block box for
//     the balanced cuts and the deal (sums, joined likewise);
//  2. the boxes of its own blocks (the deal), whose samples are all a block reads
//     (SampleField(parent, clip) reads "outside" beyond its box).
// Every number the partition and the blocks depend on is then the one the whole volume gives, so
// the mesh is byte for byte the one of mesh_isosurface on the whole file.
#include "octree/edge_crossings.h"
#include "octree/sample_field.h"
#include "octree/value_scan.h"
#include "surface/block_ranks.h"
#include "surface/partitioned_meshing.h"
#include "surface/stage_clock.h"

#include <isodel/errors.h>
#include <isodel/mesh.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>

namespace isodel {
namespace {

using namespace mesher;
using openvdb::Coord;
using openvdb::CoordBBox;

/// \p fn() on every process; when one throws, every process throws (BlockRanks::agree), so that
/// none waits for a failed one at the next collective step.
template <class Fn>
auto on_every_process(const BlockRanks& ranks, Fn&& fn) -> decltype(fn())
{
    std::exception_ptr failure;
    decltype(fn()) out{};
    try {
        out = fn();
    } catch (...) {
        failure = std::current_exception();
    }
    ranks.agree(failure);
    return out;
}

Volume read_regions(const std::string& path, const ReadOptions& read, std::vector<CoordBBox> regions)
{
    ReadOptions part = read;
    part.regions = std::move(regions);
    return read_volume(path, part);
}

/// The samples process \p rank owns in the first pass: the layers z0 <= z < z1 of the lattice,
/// the first slab unbounded below and the last above (their rings).
CoordBBox owned_slab(const CoordBBox& lattice, int rank, int processes)
{
    const std::int64_t nz = std::int64_t(lattice.max().z()) - lattice.min().z() + 1;
    const auto layer = [&](int r) { return int(lattice.min().z() + nz * r / processes); };
    constexpr int lo = std::numeric_limits<int>::min(), hi = std::numeric_limits<int>::max();
    return CoordBBox(Coord(lo, lo, rank == 0 ? lo : layer(rank)),
                     Coord(hi, hi, rank == processes - 1 ? hi : layer(rank + 1) - 1));
}

/// What a whole read of the file would hold, as samples_in_memory counts: 512 per leaf (a
/// .vdb's from its topology, a dense file's covering its lattice).
std::uint64_t samples_of_whole_file(const Volume& head)
{
    using Leaf = openvdb::FloatTree::LeafNodeType;
    if (head.format == "vdb") return std::uint64_t(head.grid->tree().leafCount()) * Leaf::SIZE;
    std::uint64_t leaves = 1;
    for (int a = 0; a < 3; ++a)
        leaves *= std::uint64_t((head.lattice.max()[a] >> Leaf::LOG2DIM) - (head.lattice.min()[a] >> Leaf::LOG2DIM) + 1);
    return leaves * Leaf::SIZE;
}

/// What the first pass learns, joined over every process.
struct WholeVolume {
    octree::FieldSummary summary;
    CrossingSlices slices;                 ///< balanced_cuts' counts (block_count only)
    std::vector<std::vector<double>> work; ///< PartitionPlan::work (several processes only)
    std::uint64_t slab_samples = 0;        ///< this process's
};

/// The first pass (the file comment), collective.
WholeVolume first_pass(const std::string& path, const ReadOptions& read, const Volume& head, const MeshOptions& options,
                       Inside inside, const BlockRanks& ranks)
{
    const CoordBBox& lattice = head.lattice;
    const CoordBBox owned = owned_slab(lattice, ranks.rank(), ranks.size());
    CoordBBox region(Coord(lattice.min().x(), lattice.min().y(), std::max(owned.min().z(), lattice.min().z())),
                     Coord(lattice.max().x(), lattice.max().y(),
                           int(std::min<std::int64_t>(std::int64_t(owned.max().z()) + 1, lattice.max().z()))));
    if (owned.empty() || region.min().z() > region.max().z()) region = CoordBBox(); // no layer of its own
    const Volume slab =
        on_every_process(ranks, [&] { return read_regions(path, read, region.empty() ? std::vector<CoordBBox>{} : std::vector<CoordBBox>{region}); });
    WholeVolume out;

    // The tie rule's scan: this slab's part, then the whole volume's (SampleField's constructor).
    const double bg = slab.grid->background();
    const bool ring_reads_background = (inside == Inside::Above ? 1.0 : -1.0) * (bg - options.isovalue) < 0;
    octree::ValueScan scan(options.isovalue);
    octree::scan_stored_values(*slab.grid, lattice, ring_reads_background, owned, scan);
    octree::scan_critical_values(*slab.grid, lattice, ring_reads_background, owned, scan);
    const std::vector<double> scans = ranks.all_gather(
        {scan.vmin, scan.vmax, scan.tie ? 1.0 : 0.0, scan.gap, double(octree::active_voxels_in(*slab.grid, owned)),
         slab.value_min <= slab.value_max ? double(slab.value_min) : HUGE_VAL,
         slab.value_min <= slab.value_max ? double(slab.value_max) : -HUGE_VAL});
    octree::ValueScan whole(options.isovalue);
    double active = 0, sample_min = HUGE_VAL, sample_max = -HUGE_VAL;
    for (std::size_t k = 0; k + 6 < scans.size(); k += 7) {
        octree::ValueScan s(options.isovalue);
        s.vmin = scans[k], s.vmax = scans[k + 1], s.tie = scans[k + 2] != 0, s.gap = scans[k + 3];
        whole.join(s);
        active += scans[k + 4];
        sample_min = std::min(sample_min, scans[k + 5]);
        sample_max = std::max(sample_max, scans[k + 6]);
    }
    if (ring_reads_background || active < double(lattice.volume())) whole.consider(bg);
    // The readers' check of the isovalue first (check_isovalue), then the tie rule's.
    Volume range = head;
    range.value_min = float(sample_min), range.value_max = float(sample_max);
    on_every_process(ranks, [&] { return (check_isovalue(range, options.isovalue), 0); });
    out.summary = on_every_process(ranks, [&] {
        return octree::summarize_scan(whole, lattice, options.isovalue, slab.grid->getName());
    });

    // The crossings whose lower end this slab owns: the others read samples of other slabs. The
    // search runs on the slab and the layer above it (its edges' upper ends), clipped so that it
    // reads nothing beyond (a .vdb's other leaves are never loaded).
    const octree::SampleField field(slab.grid, options.isovalue, inside, out.summary);
    std::vector<octree::EdgePoint> mine;
    CoordBBox clip = field.domain();
    clip.min().z() = std::max(clip.min().z(), owned.min().z());
    clip.max().z() = int(std::min<std::int64_t>(clip.max().z(), std::int64_t(owned.max().z()) + 1));
    if (!owned.empty() && clip.min().z() <= clip.max().z())
        mine = octree::edge_crossings(octree::SampleField(field, clip)).points;
    mine.erase(std::remove_if(mine.begin(), mine.end(), [&](const octree::EdgePoint& e) { return !owned.isInside(e.lower); }),
               mine.end());
    const auto sum_over_processes = [&](const std::vector<double>& part) {
        const std::vector<double> all = ranks.all_gather(part);
        std::vector<double> total(part.size(), 0.0);
        for (std::size_t k = 0; k < all.size(); ++k) total[k % part.size()] += all[k];
        return total;
    };
    if (options.block_count > 0) {
        out.slices = crossing_slices(field.domain(), mine);
        std::vector<double> part;
        for (const auto& axis : out.slices) part.insert(part.end(), axis.begin(), axis.end());
        const std::vector<double> total = sum_over_processes(part);
        std::size_t k = 0;
        for (auto& axis : out.slices)
            for (std::int64_t& n : axis) n = std::int64_t(total[k++]);
    }
    out.slab_samples = octree::samples_in_memory(*slab.grid); // what the pass loaded
    if (ranks.size() > 1) {
        const BlockCuts cuts = options.block_count > 0 ? balanced_cuts(field.domain(), options.block_count, out.slices)
                                                       : cubic_cuts(field, options.block_voxels);
        for (std::vector<double> part : block_work_per_collar(field, cuts, mine)) {
            // block_work counts one for each block's set-up besides its crossings: once in the sum.
            for (double& w : part) w -= 1;
            std::vector<double> total = sum_over_processes(part);
            for (double& w : total) w += 1;
            out.work.push_back(std::move(total));
        }
    }
    return out;
}

} // namespace

MeshResult mesh_isosurface_file(const std::string& path, const ReadOptions& read, const MeshOptions& options,
                                Interrupter* interrupter)
{
    check_mesh_options(options);
    // The header alone for the formats read in part; the whole volume for the others.
    Volume head = on_every_process(BlockRanks(options.transport), [&] { return read_regions(path, read, {}); });
    return mesh_isosurface_file(std::move(head), read, options, interrupter);
}

MeshResult mesh_isosurface_file(Volume head, const ReadOptions& read, const MeshOptions& options,
                                Interrupter* interrupter)
{
    check_mesh_options(options);
    const BlockRanks ranks(options.transport);
    const auto t0 = std::chrono::steady_clock::now();
    const std::string path = head.path;
    const bool partitioned = options.block_voxels > 0 || options.block_count > 0;
    if (!head.partial || !partitioned || options.tets != TetRegion::None || options.certify) {
        if (head.partial) head = on_every_process(ranks, [&] { return read_volume(path, read); });
        on_every_process(ranks, [&] { return (check_isovalue(head, options.isovalue), 0); });
        return mesh_isosurface(*head.grid, options, interrupter);
    }
    const Inside inside = options.inside ? *options.inside : head.default_inside;
    WholeVolume whole;
    {
        InterruptScope scope(interrupter, "slabs");
        whole = first_pass(path, read, head, options, inside, ranks);
    }
    const octree::SampleField frame(head.grid, options.isovalue, inside, whole.summary);
    PartitionPlan plan;
    plan.cuts = options.block_count > 0 ? balanced_cuts(frame.domain(), options.block_count, whole.slices)
                                        : cubic_cuts(frame, options.block_voxels);
    plan.work = std::move(whole.work);
    const double t_slabs = seconds_since(t0);

    // The second pass: this process's blocks' boxes, read again when the collar grows.
    std::unique_ptr<octree::SampleField> blocks_field;
    std::uint64_t most_read = whole.slab_samples;
    const BlockFieldSource source = [&](const std::vector<CoordBBox>& boxes) -> const octree::SampleField& {
        // No box: this process has no block (more processes than blocks). The tetrahedra's
        // request for the whole field never comes: runs with them read the whole file above.
        if (blocks_field) most_read = std::max(most_read, octree::samples_in_memory(blocks_field->grid()));
        blocks_field.reset();
        const Volume part = read_regions(path, read, boxes);
        blocks_field = std::make_unique<octree::SampleField>(part.grid, options.isovalue, inside, whole.summary);
        return *blocks_field;
    };
    MeshResult r = mesh_partitioned(frame, plan, source, options, interrupter);
    if (blocks_field) most_read = std::max(most_read, octree::samples_in_memory(blocks_field->grid()));
    const std::vector<double> reads = ranks.all_gather({double(most_read)});
    r.stats.partition.max_process_samples_read = std::uint64_t(*std::max_element(reads.begin(), reads.end()));
    r.stats.partition.file_samples = samples_of_whole_file(head);
    r.stats.seconds["slabs"] = t_slabs;
    r.stats.seconds["total"] += t_slabs;
    return r;
}

} // namespace isodel
