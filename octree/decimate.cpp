#include "octree/decimate.h"

#include "octree/balance.h"
#include "octree/interpolant.h"
#include "octree/sample_field.h"

#include <isodel/errors.h>

#include <openvdb/tools/Morphology.h>
#include <openvdb/tools/Prune.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>

namespace isodel::octree {

namespace {
void check_decimate_interrupt(Interrupter* intr, int percent)
{
    if (intr && intr->wasInterrupted(percent)) throw Cancelled("decimate: interrupted");
}

// Adds the active voxels of a typed grid, mapped into the sample index space, to \p out.
template <typename GridT>
bool add_active(const openvdb::GridBase& base, const openvdb::math::Transform& xf, openvdb::MaskGrid& out)
{
    const auto* g = dynamic_cast<const GridT*>(&base);
    if (!g) return false;
    const bool same = g->transform() == xf;
    auto acc = out.getAccessor();
    for (auto it = g->cbeginValueOn(); it; ++it) {
        CoordBBox b;
        it.getBoundingBox(b);
        for (auto c = b.begin(); c; ++c) {
            if (same) { acc.setValueOn(*c); continue; }
            const openvdb::Vec3d w = g->transform().indexToWorld(*c);
            const openvdb::Vec3d i = xf.worldToIndex(w);
            acc.setValueOn(Coord(int(std::lround(i.x())), int(std::lround(i.y())), int(std::lround(i.z()))));
        }
    }
    return true;
}

// Per-level view of the protected nodes: voxel o >> l on iff a protected node lies in the
// closed span of the level-l cell at o.
openvdb::MaskGrid::Ptr coarsen_protected(const openvdb::MaskGrid& prot, int l)
{
    auto out = openvdb::MaskGrid::create(false);
    auto acc = out->getAccessor();
    const int s = 1 << l;
    for (auto it = prot.cbeginValueOn(); it; ++it) {
        CoordBBox b;
        it.getBoundingBox(b);
        for (auto c = b.begin(); c; ++c) {
            const Coord n = *c, lo = align_down(n, l);
            const bool on[3] = {lo.x() == n.x(), lo.y() == n.y(), lo.z() == n.z()};
            for (int m = 0; m < 8; ++m) {
                if (((m & 1) && !on[0]) || ((m & 2) && !on[1]) || ((m & 4) && !on[2])) continue;
                const Coord o = lo.offsetBy((m & 1) ? -s : 0, (m & 2) ? -s : 0, (m & 4) ? -s : 0);
                acc.setValueOn(Coord(shift_down(o.x(), l), shift_down(o.y(), l), shift_down(o.z(), l)));
            }
        }
    }
    return out;
}

// Condition 2: P's trilinear interpolant reproduces every original sample of its span within T.
bool fits(const AdaptiveGrid::Reader& r, const CellId& p, double T)
{
    const int s = p.size();
    double c[8];
    for (int m = 0; m < 8; ++m)
        c[m] = r.sample(p.origin.offsetBy((m & 1) * s, ((m >> 1) & 1) * s, ((m >> 2) & 1) * s));
    const auto& tri = trilinear();
    const double inv = 1.0 / s;
    for (int k = 0; k <= s; ++k)
        for (int j = 0; j <= s; ++j)
            for (int i = 0; i <= s; ++i) {
                const double f = r.sample(p.origin.offsetBy(i, j, k));
                if (std::abs(tri.eval(c, Vec3d(i * inv, j * inv, k * inv)) - f) > T) return false;
            }
    return true;
}

std::vector<CellId> parent_candidates(const AdaptiveGrid& g, int l)
{
    std::vector<CellId> out;
    if (l == 1) {
        const CoordBBox cells = g.unit_cells();
        const Coord lo = align_down(cells.min(), 1);
        for (int z = lo.z(); z <= cells.max().z(); z += 2)
            for (int y = lo.y(); y <= cells.max().y(); y += 2)
                for (int x = lo.x(); x <= cells.max().x(); x += 2) out.push_back({Coord(x, y, z), 1});
        return out;
    }
    for (const CellId& c : g.leaves(l - 1)) out.push_back({align_down(c.origin, l), l});
    out.erase(std::unique(out.begin(), out.end()), out.end()); // leaves are sorted by origin
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}
} // namespace

openvdb::MaskGrid::Ptr protected_nodes(const AdaptiveGrid& g, const DecimateOptions& opt)
{
    auto prot = openvdb::MaskGrid::create(false);
    if (opt.iso) {
        const SampleField field(g.samples_ptr(), *opt.iso, Inside::Above);
        SampleField::Reader fr(field);
        auto acc = prot->getAccessor();
        for (const Coord& u : value_cells_sparse(g)) {
            double phi[8];
            fr.cell_corners(u, phi);
            bool pos = false, neg = false;
            for (double v : phi) (v > 0 ? pos : neg) = true;
            if (pos && neg)
                for (int m = 0; m < 8; ++m) acc.setValueOn(u.offsetBy(m & 1, (m >> 1) & 1, (m >> 2) & 1));
        }
        const int b = int(std::ceil(std::max(0.0, opt.band)));
        if (b > 0 && prot->activeVoxelCount() > 0)
            openvdb::tools::dilateActiveValues(prot->tree(), b, openvdb::tools::NN_FACE_EDGE_VERTEX,
                                               openvdb::tools::IGNORE_TILES);
    }
    if (opt.importance) {
        const auto& xf = g.samples().transform();
        const auto& im = *opt.importance;
        if (!add_active<openvdb::MaskGrid>(im, xf, *prot) && !add_active<openvdb::FloatGrid>(im, xf, *prot) &&
            !add_active<openvdb::BoolGrid>(im, xf, *prot) && !add_active<openvdb::DoubleGrid>(im, xf, *prot) &&
            !add_active<openvdb::Int32Grid>(im, xf, *prot))
            throw InvalidInput("importance grid '" + im.getName() + "': unsupported grid type " + im.type());
    }
    return prot;
}

double measure_max_error(const AdaptiveGrid& g, const openvdb::FloatGrid& original, double tolerance,
                         std::vector<CellId>* over)
{
    double worst = 0;
    std::mutex mu;
    for (int l = 1; l <= g.max_level(); ++l) {
        const auto leaves = g.leaves(l);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.size(), 64),
                          [&](const tbb::blocked_range<std::size_t>& rg) {
                              InterpolantReader ir(g);
                              auto acc = original.getConstAccessor();
                              double w = 0;
                              std::vector<CellId> bad;
                              for (std::size_t i = rg.begin(); i < rg.end(); ++i) {
                                  const CellId& c = leaves[i];
                                  double cv[8];
                                  ir.corners(c, cv);
                                  const double inv = 1.0 / c.size();
                                  double e = 0;
                                  for (auto it = c.nodes().begin(); it; ++it) {
                                      const Coord d = *it - c.origin;
                                      const double F = ir.local().eval(cv, Vec3d(d.x() * inv, d.y() * inv, d.z() * inv));
                                      e = std::max(e, std::abs(F - double(acc.getValue(*it))));
                                  }
                                  w = std::max(w, e);
                                  if (e > tolerance) bad.push_back(c);
                              }
                              std::lock_guard<std::mutex> lock(mu);
                              worst = std::max(worst, w);
                              if (over) over->insert(over->end(), bad.begin(), bad.end());
                          });
    }
    if (over) std::sort(over->begin(), over->end());
    return worst;
}

openvdb::FloatGrid::Ptr prune_samples(const AdaptiveGrid& g)
{
    auto out = g.samples().deepCopy();
    const float bg = out->background();
    const CoordBBox active = g.samples().evalActiveVoxelBoundingBox();
    auto src = g.samples().getConstAccessor();
    auto acc = out->getAccessor();
    for (int l = 1; l <= g.max_level(); ++l)
        for (const CellId& c : g.leaves(l)) {
            const Coord hi = c.origin.offsetBy(c.size());
            for (auto it = c.nodes().begin(); it; ++it) {
                const Coord n = *it;
                const bool corner = (n.x() == c.origin.x() || n.x() == hi.x()) &&
                                    (n.y() == c.origin.y() || n.y() == hi.y()) &&
                                    (n.z() == c.origin.z() || n.z() == hi.z());
                if (!corner) acc.setValueOff(n, bg); // hanging or interior: never read
            }
        }
    if (!active.empty()) { // keep the domain rule: same active bounding box
        acc.setValueOn(active.min(), src.getValue(active.min()));
        acc.setValueOn(active.max(), src.getValue(active.max()));
    }
    openvdb::tools::prune(out->tree());
    return out;
}

} // namespace isodel::octree

namespace isodel {

using namespace isodel::octree;

DecimateResult decimate(const openvdb::FloatGrid& grid, const DecimateOptions& opt, Interrupter* intr)
{
    if (opt.k < 1) throw InvalidInput("decimate: --k must be >= 1");
    if (!(opt.tolerance >= 0)) throw InvalidInput("decimate: --tolerance must be >= 0");
    if (opt.max_level < 0 || opt.max_level > AdaptiveGrid::kMaxLevel)
        throw InvalidInput("decimate: max level must be in [0, 15]");
    const auto t0 = std::chrono::steady_clock::now();
    if (intr) intr->start("decimate");
    // Non-owning handle: the caller's grid outlives this call.
    openvdb::FloatGrid::ConstPtr orig(&grid, [](const openvdb::FloatGrid*) {});
    AdaptiveGrid ag(orig, opt.k);
    DecimateResult res;
    res.cells_before = ag.cell_count();
    res.memory_before = ag.memory_bytes();
    const auto prot = protected_nodes(ag, opt);
    const double T = opt.tolerance;

    for (int l = 1; l <= opt.max_level; ++l) {
        check_decimate_interrupt(intr, 80 * l / std::max(1, opt.max_level));
        const auto cand = parent_candidates(ag, l);
        const auto prot_l = coarsen_protected(*prot, l);
        std::vector<char> ok(cand.size(), 0);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cand.size(), 256),
                          [&](const tbb::blocked_range<std::size_t>& rg) {
                              AdaptiveGrid::Reader r(ag);
                              auto pacc = prot_l->getConstAccessor();
                              for (std::size_t i = rg.begin(); i < rg.end(); ++i) {
                                  const CellId& p = cand[i];
                                  if (pacc.isValueOn(Coord(shift_down(p.origin.x(), l), shift_down(p.origin.y(), l),
                                                           shift_down(p.origin.z(), l))))
                                      continue;
                                  if (!may_merge(r, p, opt.k)) continue;
                                  ok[i] = fits(r, p, T);
                              }
                          });
        if (!merge_flagged(ag, cand, ok)) break;
    }
    ag.trim_levels();
    res.balance_splits = balance(ag, opt.k); // merges respect k: expected 0, kept as a guard

    // Hanging-node constraints may push the continuous interpolant past T: split and rebalance.
    for (;;) {
        check_decimate_interrupt(intr, 90);
        std::vector<CellId> over;
        measure_max_error(ag, grid, T, &over);
        if (over.empty()) break;
        for (const CellId& c : over) ag.split(c);
        res.repair_splits += over.size();
        res.balance_splits += balance(ag, opt.k);
    }

    auto pruned = prune_samples(ag);
    ag.set_samples(pruned);
    res.max_error = measure_max_error(ag, grid); // on the stored (pruned) samples
    res.max_level_difference = max_level_difference(ag);
    res.cells_after = ag.cell_count();
    res.memory_after = ag.memory_bytes();
    res.histogram = ag.level_histogram();

    AdaptiveVolume& v = res.volume;
    v.samples = pruned;
    v.levels = ag.masks();
    v.domain = ag.domain();
    v.k = opt.k;
    v.tolerance = T;
    v.source = opt.source;
    res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (intr) intr->end();
    return res;
}

} // namespace isodel
