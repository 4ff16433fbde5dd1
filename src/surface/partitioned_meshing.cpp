#include "surface/partitioned_meshing.h"
#include "surface/thread_limit.h"

#include "octree/protective_layer.h"

#include <isodel/errors.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <sstream>

namespace isodel::mesher {
namespace {

using Clock = std::chrono::steady_clock;

std::array<int, 3> block_count(const octree::SampleField& field, int block_voxels)
{
    const openvdb::CoordBBox& d = field.domain();
    std::array<int, 3> n{};
    // The cells of the domain have lower corners min .. max - 1.
    for (int a = 0; a < 3; ++a) n[a] = std::max(1, (d.max()[a] - d.min()[a] + block_voxels - 1) / block_voxels);
    return n;
}

/// Calls the user's interrupter from worker threads one at a time (OpenVDB interrupters are
/// not thread-safe). Blocks poll it through BlockInterrupter between their rounds, so a
/// cancellation stops every block promptly (TBB rethrows the first Cancelled to the caller).
class SharedInterrupter {
public:
    explicit SharedInterrupter(Interrupter* intr) : intr_(intr) {}
    bool poll(int percent)
    {
        if (!intr_) return false;
        std::lock_guard<std::mutex> lock(mutex_);
        return intr_->wasInterrupted(percent);
    }
    void log(const char* message)
    {
        if (!intr_) return;
        std::lock_guard<std::mutex> lock(mutex_);
        intr_->log(message);
    }

private:
    Interrupter* intr_;
    std::mutex mutex_;
};

/// What a block sees: no stages of its own, the shared cancellation.
class BlockInterrupter final : public Interrupter {
public:
    explicit BlockInterrupter(SharedInterrupter& shared) : shared_(shared) {}
    bool wasInterrupted(int) override { return shared_.poll(-1); }
    void log(const char* message) override { shared_.log(message); }

private:
    SharedInterrupter& shared_;
};

} // namespace

std::array<int, 3> collar_voxels(const octree::SampleField& field)
{
    const std::array<int, 3> r = octree::layer_radius(field);
    return {2 * r[0] + 2, 2 * r[1] + 2, 2 * r[2] + 2};
}

std::vector<BlockSpec> partition_domain(const octree::SampleField& field, int block_voxels,
                                        const std::array<int, 3>& collar)
{
    if (block_voxels < 1) throw InvalidInput("block size must be at least one voxel");
    const openvdb::Coord o = field.domain().min();
    const std::array<int, 3> n = block_count(field, block_voxels);
    const double count = double(n[0]) * n[1] * n[2];
    if (count > kMaxBlocks) {
        std::ostringstream os;
        os << "block size " << block_voxels << " cuts the domain into " << count << " blocks, more than " << kMaxBlocks
           << ": choose larger blocks";
        throw InvalidInput(os.str());
    }
    std::vector<BlockSpec> out;
    for (int z = 0; z < n[2]; ++z)
        for (int y = 0; y < n[1]; ++y)
            for (int x = 0; x < n[0]; ++x) {
                BlockSpec b;
                b.index = {x, y, z};
                const openvdb::Coord lo = o + openvdb::Coord(x * block_voxels, y * block_voxels, z * block_voxels);
                b.core = openvdb::CoordBBox(lo, lo.offsetBy(block_voxels - 1));
                // Samples of the core's cells are lo .. lo + B; the collar grows them.
                b.box = openvdb::CoordBBox(lo.offsetBy(-collar[0], -collar[1], -collar[2]),
                                           lo.offsetBy(block_voxels + collar[0], block_voxels + collar[1],
                                                       block_voxels + collar[2]));
                const int index[3] = {x, y, z};
                for (int a = 0; a < 3; ++a) {
                    b.own_lo[a] = index[a] == 0 ? -HUGE_VAL : lo[a];
                    b.own_hi[a] = index[a] == n[a] - 1 ? HUGE_VAL : lo[a] + block_voxels;
                }
                out.push_back(b);
            }
    return out;
}

std::vector<SeedPoint> mesh_block(const octree::SampleField& field, const BlockSpec& block, const MeshOptions& options,
                                  Interrupter* interrupter)
{
    openvdb::CoordBBox box = block.box;
    box.intersect(field.domain());
    if (box.empty()) return {};
    const octree::SampleField clipped(field, box);
    MeshOptions bo = options;
    bo.threads = 0; // the caller's limit holds; nested TBB work shares it
    bo.tets = TetRegion::None;
    bo.block_voxels = 0;
    // eps in world units, so a block does not rescale it (eps_voxels uses the same min edge anyway).
    if (bo.eps <= 0) bo.eps = options.eps_voxels * field.min_voxel_edge();
    std::vector<SeedPoint> inserted;
    FieldRun run;
    run.field = &clipped;
    run.inserted = &inserted;
    // The block fixes only violations at its core (grown by one voxel, so that what it keeps was
    // refined with its neighbourhood): the collar is there to trap the core's Voronoi cells,
    // and refining it (or the creases where the clipped Sigma meets the box) is a neighbour's
    // or nobody's work.
    const openvdb::Vec3d lo = block.core.min().asVec3d() - openvdb::Vec3d(1.0);
    const openvdb::Vec3d hi = block.core.max().asVec3d() + openvdb::Vec3d(2.0);
    run.keep = [&field, lo, hi](const Point& p) {
        const openvdb::Vec3d q = field.world_to_index({p.x(), p.y(), p.z()});
        return q[0] >= lo[0] && q[1] >= lo[1] && q[2] >= lo[2] && q[0] <= hi[0] && q[1] <= hi[1] && q[2] <= hi[2];
    };
    mesh_field(run, bo, interrupter);
    // Keep what the block owns (BlockSpec::own_lo/own_hi: its core's cells).
    std::vector<SeedPoint> owned;
    for (const SeedPoint& s : inserted) {
        const openvdb::Vec3d q = field.world_to_index({s.p[0], s.p[1], s.p[2]});
        bool mine = true;
        for (int a = 0; a < 3 && mine; ++a) mine = q[a] >= block.own_lo[a] && q[a] < block.own_hi[a];
        if (mine) owned.push_back(s);
    }
    return owned;
}

MeshResult mesh_partitioned(const octree::SampleField& field, const MeshOptions& options, Interrupter* interrupter)
{
    const auto t0 = Clock::now();
    const ThreadLimit threads(options.threads);
    const std::array<int, 3> collar = collar_voxels(field);
    const std::vector<BlockSpec> blocks = partition_domain(field, options.block_voxels, collar);
    std::vector<std::vector<SeedPoint>> points(blocks.size());
    std::vector<char> failed(blocks.size(), 0);
    SharedInterrupter shared(interrupter);
    std::atomic<int> done{0};
    {
        InterruptScope scope(interrupter, "blocks");
        // One task per block: blocks are independent, their results land in their own slot,
        // so the merge order (block index) does not depend on scheduling.
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks.size(), 1), [&](const auto& range) {
            BlockInterrupter block_interrupter(shared);
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
                try {
                    points[i] = mesh_block(field, blocks[i], options, &block_interrupter);
                } catch (const GuaranteeViolated& e) {
                    block_interrupter.log(("block " + std::to_string(i) + ": " + e.what()).c_str());
                    // A bound stopped the block: the merge's own loop does its work instead.
                    failed[i] = 1;
                }
                if (shared.poll(int(100.0 * ++done / double(blocks.size())))) throw Cancelled("interrupted");
            }
        });
    }
    const double t_blocks = std::chrono::duration<double>(Clock::now() - t0).count();

    FieldRun merge;
    merge.field = &field;
    for (auto& p : points) merge.seeds.insert(merge.seeds.end(), p.begin(), p.end());
    const std::size_t from_blocks = merge.seeds.size();
    MeshResult r = mesh_field(merge, options, interrupter);
    PartitionStats& ps = r.stats.partition;
    ps.blocks = int(blocks.size());
    ps.collar_voxels = *std::max_element(collar.begin(), collar.end());
    ps.blocks_failed = int(std::count(failed.begin(), failed.end(), 1));
    ps.block_points = from_blocks;
    r.stats.seconds["blocks"] = t_blocks;
    r.stats.seconds["total"] += t_blocks;
    return r;
}

} // namespace isodel::mesher
