#include "surface/partitioned_meshing.h"
#include "surface/thread_limit.h"

#include "octree/edge_crossings.h"
#include "octree/protective_layer.h"
#include "surface/block_ranks.h"
#include "surface/surface_extraction.h"

#include <isodel/errors.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <string>
#include <exception>
#include <memory>
#include <mutex>
#include <sstream>

namespace isodel::mesher {
namespace {

using Clock = std::chrono::steady_clock;

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
    return {2 * r[0] + 4, 2 * r[1] + 4, 2 * r[2] + 4};
}

std::array<int, 3> grown_collar(const octree::SampleField& field, int growth)
{
    std::array<int, 3> collar = collar_voxels(field);
    for (int& c : collar) c += 2 * growth;
    return collar;
}

std::vector<std::vector<double>> block_work_per_collar(const octree::SampleField& field, const BlockCuts& cuts,
                                                       const std::vector<octree::EdgePoint>& crossings)
{
    std::vector<std::vector<double>> work;
    for (int growth = 0; growth <= kMaxCollarGrowths; ++growth)
        work.push_back(block_work(blocks_of(cuts, grown_collar(field, growth)), crossings));
    return work;
}

namespace {

using Blocks = std::vector<std::unique_ptr<BlockMesher>>;

/// Runs \p work(i) for this process's blocks in parallel, one task per block, polling
/// cancellation; then agrees with the other processes on whether any failed (BlockRanks::agree).
template <class Work>
void for_my_blocks(const BlockRanks& ranks, std::size_t n, SharedInterrupter& shared, Work&& work)
{
    std::exception_ptr failure;
    const std::vector<std::size_t> mine = ranks.mine(n);
    try {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mine.size(), 1), [&](const auto& range) {
            for (std::size_t k = range.begin(); k != range.end(); ++k) {
                const std::size_t i = mine[k];
                try {
                    work(i);
                } catch (const GuaranteeViolated& e) {
                    throw GuaranteeViolated("block " + std::to_string(i) + ": " + e.what());
                }
                if (shared.poll(-1)) throw Cancelled("interrupted");
            }
        });
    } catch (...) {
        failure = std::current_exception();
    }
    ranks.agree(failure);
}

/// Every block's new points, from every process: (block, x, y, z, kind) per point, in block order.
std::vector<std::vector<SeedPoint>> gather_new_points(Blocks& blocks, const BlockRanks& ranks)
{
    const std::size_t n = blocks.size();
    std::vector<double> mine;
    for (std::size_t i : ranks.mine(n))
        for (const SeedPoint& s : blocks[i]->take_new_points())
            mine.insert(mine.end(), {double(i), s.p[0], s.p[1], s.p[2], double(int(s.kind))});
    const std::vector<double> all = ranks.all_gather(mine);
    std::vector<std::vector<SeedPoint>> fresh(n);
    for (std::size_t k = 0; k + 4 < all.size(); k += 5)
        fresh[std::size_t(all[k])].push_back(SeedPoint{{all[k + 1], all[k + 2], all[k + 3]}, PointKind(int(all[k + 4]))});
    return fresh;
}

/// Exchanges points until no block receives one (partitioned_meshing.h); returns the rounds.
/// \p inserted collects the N points the blocks inserted, round by round in block order.
int exchange_points(Blocks& blocks, const std::vector<BlockSpec>& specs,
                    const BlockRanks& ranks, SharedInterrupter& shared, PartitionStats& ps,
                    std::vector<SeedPoint>& inserted, bool release)
{
    const std::size_t n = blocks.size();
    std::vector<std::vector<std::size_t>> near(n);
    for (std::size_t j : ranks.mine(n)) near[j] = neighbours(specs, j);
    for (int round = 1;; ++round) {
        const std::vector<std::vector<SeedPoint>> fresh = gather_new_points(blocks, ranks);
        for (const auto& list : fresh)
            for (const SeedPoint& s : list)
                if (s.kind == PointKind::Topology || s.kind == PointKind::Geometry) inserted.push_back(s);
        // Each of this process's blocks: its neighbours' new points, in block order.
        std::vector<std::vector<SeedPoint>> inbox(n);
        double sent = 0;
        for (std::size_t j : ranks.mine(n)) {
            if (blocks[j]->empty()) continue;
            for (std::size_t i : near[j])
                for (const SeedPoint& s : fresh[i])
                    if (blocks[j]->reads(s.p)) inbox[j].push_back(s);
            sent += double(inbox[j].size());
        }
        const double sent_everywhere = ranks.sum(sent);
        if (sent_everywhere == 0) return round - 1;
        if (round > kMaxExchangeRounds) {
            std::ostringstream os;
            os << "partitioned meshing: the blocks still exchanged " << sent_everywhere << " points after "
               << kMaxExchangeRounds << " rounds (bound: kMaxExchangeRounds)";
            throw GuaranteeViolated(os.str());
        }
        std::vector<std::size_t> added(n, 0);
        for_my_blocks(ranks, n, shared, [&](std::size_t j) {
            if (inbox[j].empty()) return;
            added[j] = blocks[j]->receive(inbox[j]);
            if (added[j]) blocks[j]->refine();
            if (release) blocks[j]->park();
        });
        double mine = 0;
        for (std::size_t a : added) mine += double(a);
        ps.exchanged_points += std::size_t(ranks.sum(mine));
    }
}

/// MeshOptions::release_blocks: the rebuilds of every process's blocks.
std::size_t count_rebuilds(const Blocks& blocks, const BlockRanks& ranks)
{
    double mine = 0;
    for (std::size_t i : ranks.mine(blocks.size())) mine += double(blocks[i]->rebuilds());
    return std::size_t(ranks.sum(mine));
}

/// The run's counts from all blocks of all processes: each inserted point and each own-region
/// E/G point counted once.
void sum_block_stats(const Blocks& blocks, const BlockRanks& ranks, MeshStats& st)
{
    // Sums first, then maxima, then the facet-angle verdict: one collective step.
    std::vector<double> mine(12, 0.0);
    const std::size_t n = blocks.size();
    for (std::size_t i : ranks.mine(n)) {
        const auto& b = blocks[i];
        if (b->empty()) continue;
        const MeshStats& s = b->stats();
        mine[0] += double(b->own_edge_points());
        mine[1] += double(b->own_grid_points());
        mine[2] += double(s.n_topology);
        mine[3] += double(s.n_geometry);
        mine[4] += double(s.n_facet_angle);
        mine[5] += double(s.bound_repairs);
        mine[6] = std::max(mine[6], double(s.rounds));
        mine[7] = std::max(mine[7], double(s.max_cells_e));
        mine[8] = std::max(mine[8], double(s.max_cells_n));
        mine[9] = double(s.bound_e);
        mine[10] = double(s.bound_n);
        mine[11] = std::max(mine[11], double(int(s.facet_angle_stop))); // Off < Met < the stops
    }
    const std::vector<double> all = ranks.all_gather(mine);
    std::vector<double> t(12, 0.0);
    for (std::size_t k = 0; k + 11 < all.size(); k += 12) {
        for (int j = 0; j < 6; ++j) t[j] += all[k + j];
        for (int j = 6; j < 12; ++j) t[j] = std::max(t[j], all[k + j]);
    }
    st.e_points = std::size_t(t[0]);
    st.g_points = std::size_t(t[1]);
    st.n_topology = std::size_t(t[2]);
    st.n_geometry = std::size_t(t[3]);
    st.n_facet_angle = std::size_t(t[4]);
    st.bound_repairs = std::size_t(t[5]);
    st.rounds = int(t[6]);
    st.max_cells_e = int(t[7]);
    st.max_cells_n = int(t[8]);
    st.bound_e = int(t[9]);
    st.bound_n = int(t[10]);
    st.facet_angle_stop = FacetAngleStop(int(t[11]));
}

/// The owned triangles of every block, assembled on the first process; false (everywhere) when
/// a facet was refused or the union does not close up. The blocks are released once their
/// triangles are out, so that a process does not hold its triangulations and the mesh at once.
bool assemble_everywhere(Blocks& blocks, const BlockRanks& ranks, SharedInterrupter& shared, SurfaceMesh& mesh,
                         std::size_t& refused)
{
    const std::size_t n = blocks.size();
    std::vector<BlockSurface> parts(n);
    for_my_blocks(ranks, n, shared, [&](std::size_t i) {
        parts[i] = blocks[i]->owned_surface();
        blocks[i].reset();
    });
    double mine_refused = 0;
    std::vector<double> mine;
    for (std::size_t i : ranks.mine(n)) {
        mine_refused += double(parts[i].balls_outside);
        for (const WorldTriangle& t : parts[i].triangles) {
            mine.push_back(double(i));
            for (const auto& p : t) mine.insert(mine.end(), p.begin(), p.end());
        }
        parts[i] = BlockSurface();
    }
    refused = std::size_t(ranks.sum(mine_refused));
    if (refused) return false;
    std::vector<double> all = ranks.gather_to_first(mine);
    std::vector<double>().swap(mine);
    double closed = 0; // the first process's verdict, shared by the sum
    if (ranks.first()) {
        // In block order, whichever process meshed the block: the same mesh for any count.
        std::vector<BlockSurface> joined(n);
        std::vector<std::size_t> count(n, 0); // reserved, so that no list grows by doubling
        for (std::size_t k = 0; k + 9 < all.size(); k += 10) ++count[std::size_t(all[k])];
        for (std::size_t i = 0; i < n; ++i) joined[i].triangles.reserve(count[i]);
        for (std::size_t k = 0; k + 9 < all.size(); k += 10)
            joined[std::size_t(all[k])].triangles.push_back(WorldTriangle{{{all[k + 1], all[k + 2], all[k + 3]},
                                                                           {all[k + 4], all[k + 5], all[k + 6]},
                                                                           {all[k + 7], all[k + 8], all[k + 9]}}});
        std::vector<double>().swap(all); // the first process holds the whole mesh: one copy at a time
        closed = assemble_surface(joined, mesh) ? 1 : 0;
    }
    return ranks.sum(closed) == 1;
}

} // namespace

PartitionPlan plan_partition(const octree::SampleField& field, const MeshOptions& options, bool deal)
{
    // The grid-edge crossings place the balanced cuts and weigh the blocks dealt to processes;
    // they are not held while the blocks mesh.
    PartitionPlan plan;
    std::vector<octree::EdgePoint> crossings;
    if (options.block_count > 0 || deal) crossings = octree::edge_crossings(field).points;
    plan.cuts = options.block_count > 0 ? balanced_cuts(field, options.block_count, crossings)
                                        : cubic_cuts(field, options.block_voxels);
    if (deal) plan.work = block_work_per_collar(field, plan.cuts, crossings);
    return plan;
}

MeshResult mesh_partitioned(const octree::SampleField& field, const MeshOptions& options, Interrupter* interrupter)
{
    check_mesh_options(options);
    const ThreadLimit threads(options.threads);
    const PartitionPlan plan = plan_partition(field, options, BlockRanks(options.transport).size() > 1);
    const BlockFieldSource whole = [&](const std::vector<openvdb::CoordBBox>&) -> const octree::SampleField& {
        return field;
    };
    return mesh_partitioned(field, plan, whole, options, interrupter);
}

MeshResult mesh_partitioned(const octree::SampleField& frame, const PartitionPlan& plan, const BlockFieldSource& source,
                            const MeshOptions& options, Interrupter* interrupter)
{
    const auto t0 = Clock::now();
    check_mesh_options(options);
    const ThreadLimit threads(options.threads);
    BlockRanks ranks(options.transport);
    const std::array<int, 3> r = octree::layer_radius(frame);
    // The block's points differ from the global ones only within r + 2 voxels of its box's inner
    // faces (docs/partitioned.md, Lemma 1): its trusted box lies inside that margin.
    const int margin = *std::max_element(r.begin(), r.end()) + 2;
    SharedInterrupter shared(interrupter);
    MeshResult result;
    MeshStats& st = result.stats;
    PartitionStats& ps = st.partition;
    std::vector<SeedPoint> inserted;
    for (int growth = 0;; ++growth) {
        const std::array<int, 3> collar = grown_collar(frame, growth);
        const std::vector<BlockSpec> specs = blocks_of(plan.cuts, collar);
        const std::size_t n = specs.size();
        if (ranks.size() > 1) ranks.deal(plan.work.at(std::size_t(growth)));
        std::vector<openvdb::CoordBBox> boxes;
        for (std::size_t i : ranks.mine(n)) boxes.push_back(specs[i].box);
        const octree::SampleField& field = source(boxes);
        Blocks blocks(n);
        // A block's refiner keeps its interrupter across the rounds: one per block, all sharing
        // the caller's through SharedInterrupter.
        std::vector<std::unique_ptr<BlockInterrupter>> interrupters(n);
        for (auto& bi : interrupters) bi = std::make_unique<BlockInterrupter>(shared);
        ps = PartitionStats();
        inserted.clear();
        {
            InterruptScope scope(interrupter, "blocks");
            for_my_blocks(ranks, n, shared, [&](std::size_t i) {
                blocks[i] = std::make_unique<BlockMesher>(field, specs[i], options, margin, interrupters[i].get());
                blocks[i]->refine();
                if (options.release_blocks) blocks[i]->park();
            });
            ps.exchange_rounds =
                exchange_points(blocks, specs, ranks, shared, ps, inserted, options.release_blocks);
        }
        sum_block_stats(blocks, ranks, st);
        ps.block_rebuilds = count_rebuilds(blocks, ranks);
        // A block whose last pass stopped on violations of its own region whose points are
        // vertices already cannot certify them: as in one run, the guarantee fails.
        std::vector<double> stalled;
        for (std::size_t i : ranks.mine(n))
            if (blocks[i]->stalled()) stalled.push_back(double(i));
        stalled = ranks.all_gather(stalled);
        if (!stalled.empty())
            throw GuaranteeViolated("partitioned meshing: block " + std::to_string(std::size_t(*std::min_element(
                                        stalled.begin(), stalled.end()))) +
                                    ": no progress (violations left whose candidates are all vertices already)");
        std::size_t refused = 0;
        if (!assemble_everywhere(blocks, ranks, shared, result.surface, refused)) {
            if (growth == kMaxCollarGrowths) {
                std::ostringstream os;
                os << "partitioned meshing: "
                   << (refused ? std::to_string(refused) + " owned facets' Delaunay balls leave their block"
                               : std::string("the blocks' facets do not close up along the seams"))
                   << " with a collar of " << collar[0] << " voxels (bound: " << kMaxCollarGrowths << " collar growths)";
                throw GuaranteeViolated(os.str());
            }
            continue;
        }
        ps.blocks = int(n);
        ps.collar_voxels = *std::max_element(collar.begin(), collar.end());
        ps.collar_growths = growth;
        ps.block_points = st.n_topology + st.n_geometry;
        break;
    }
    const double t_blocks = std::chrono::duration<double>(Clock::now() - t0).count();
    if (options.tets != TetRegion::None) {
        // DELVOLMESH on one triangulation of the blocks' points; its loop checks everything again.
        FieldRun merge;
        merge.field = &source({}); // the whole field: the tets need every sample (mesh_partitioned's contract)
        merge.seeds = std::move(inserted);
        MeshResult m = mesh_field(merge, options, interrupter);
        const std::size_t seam = m.stats.partition.seam_points;
        m.stats.partition = ps;
        m.stats.partition.seam_points = seam;
        m.stats.seconds["blocks"] = t_blocks;
        m.stats.seconds["total"] += t_blocks;
        return m;
    }
    st.effective_isovalue = frame.effective_isovalue();
    st.eps_world = options.eps > 0 ? options.eps : options.eps_voxels * frame.min_voxel_edge();
    st.vertices = result.surface.vertices.size();
    st.triangles = result.surface.triangles.size();
    st.components = surface_topology(result.surface);
    st.seconds["blocks"] = t_blocks;
    st.seconds["total"] = t_blocks;
    st.peak_memory_bytes = peak_memory_bytes();
    ps.processes = ranks.size();
    const std::vector<double> peaks = ranks.all_gather({double(st.peak_memory_bytes)});
    ps.max_process_peak_memory_bytes = std::size_t(*std::max_element(peaks.begin(), peaks.end()));
    return result;
}

} // namespace isodel::mesher
