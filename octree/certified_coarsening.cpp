#include "octree/certified_coarsening.h"

#include "octree/balance.h"
#include "octree/interpolant.h"
#include "octree/monotone_edges.h"
#include "octree/resample.h"

#include <isodel/errors.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <string>

namespace isodel::octree {

namespace {

// A quotient delta / g rounded in double; the margin keeps the comparison on the safe side of
// the rounding of two float differences and one division.
constexpr double kRoundingMargin = 1.0 + 1e-9;

// The distance a certified axis allows: delta / g voxels, at most one voxel (the certificate's
// path must stay inside the block) and within the budget in world units.
bool within_budget(double delta, double g, double edge, double budget_world, double& distance_world)
{
    const double voxels = delta / g * kRoundingMargin;
    distance_world = voxels * edge;
    return voxels <= 1.0 && distance_world <= budget_world;
}

// Condition for a parent P to replace its children during construction: P's own trilinear
// interpolant (from its corner samples) passes the certificate's tests on P's span and on the
// one-cell rim around it, or the span lies off Sigma (every node of one strict sign, so P's
// interpolant is of that sign too). The rim is there because certify_cell reads the 3x3x3 block
// around each cell, which reaches one cell past P: its fine edges enter the monotone axis and g
// (the rim's coarse values are not known yet and are taken as the input's). delta is measured
// on band cells only, as in certify_cell: off the band a narrow-band input is clamped, and its
// difference from the coarse interpolant there says nothing about Sigma. Hanging nodes and
// the neighbours' own coarsening are left to the repair rounds, which check the continuous
// interpolant itself, so this test decides how much is proposed, never what is trusted.
bool parent_certified(const SampleField::Reader& f, const SampleField::Reader& corners, const CellId& p,
                      const std::array<double, 3>& edges, double budget_world)
{
    const int s = p.size();
    bool pos = false, neg = false;
    for (int k = 0; k <= s && !(pos && neg); ++k)
        for (int j = 0; j <= s; ++j)
            for (int i = 0; i <= s; ++i) (f.phi(p.origin.offsetBy(i, j, k)) > 0 ? pos : neg) = true;
    if (!(pos && neg)) return true;

    // Nodes -1 .. s + 1 per axis: P's span and its rim.
    const int n = s + 3;
    const std::size_t nodes = std::size_t(n) * n * n;
    std::vector<double> fine(nodes), coarse(nodes);
    auto idx = [&](int i, int j, int k) { return (std::size_t(k + 1) * n + (j + 1)) * n + (i + 1); };
    double c[8];
    for (int m = 0; m < 8; ++m) c[m] = corners.phi(p.origin.offsetBy((m & 1) * s, ((m >> 1) & 1) * s, ((m >> 2) & 1) * s));
    const auto& tri = trilinear();
    const double inv = 1.0 / s;
    auto inside = [s](int i) { return i >= 0 && i <= s; };
    for (int k = -1; k <= s + 1; ++k)
        for (int j = -1; j <= s + 1; ++j)
            for (int i = -1; i <= s + 1; ++i) {
                const std::size_t q = idx(i, j, k);
                fine[q] = f.phi(p.origin.offsetBy(i, j, k));
                coarse[q] = inside(i) && inside(j) && inside(k) ? tri.eval(c, Vec3d(i * inv, j * inv, k * inv)) : fine[q];
            }
    // The unit cells either level set can meet (fine and coarse corners of both signs), delta
    // over the corners of P's own band cells.
    const int cells = s + 2;
    std::vector<char> band(std::size_t(cells) * cells * cells);
    auto cell = [cells](int i, int j, int k) { return (std::size_t(k + 1) * cells + (j + 1)) * cells + (i + 1); };
    double delta = 0;
    for (int k = -1; k <= s; ++k)
        for (int j = -1; j <= s; ++j)
            for (int i = -1; i <= s; ++i) {
                bool p2 = false, n2 = false;
                for (int m = 0; m < 8; ++m) {
                    const std::size_t q = idx(i + (m & 1), j + ((m >> 1) & 1), k + ((m >> 2) & 1));
                    for (double v : {fine[q], coarse[q]}) (v > 0 ? p2 : n2) = true;
                }
                band[cell(i, j, k)] = p2 && n2;
                if (!(p2 && n2) || i < 0 || j < 0 || k < 0 || i == s || j == s || k == s) continue;
                for (int m = 0; m < 8; ++m) {
                    const std::size_t q = idx(i + (m & 1), j + ((m >> 1) & 1), k + ((m >> 2) & 1));
                    delta = std::max(delta, std::abs(coarse[q] - fine[q]));
                }
            }
    for (int d = 0; d < 3; ++d) {
        Monotone mono;
        for (int m = 0; m < 8; ++m) // the four coarse d-edges, per unit length
            if (!(m & (1 << d))) mono.add((c[m | (1 << d)] - c[m]) * inv);
        for (int k = -1; k <= s && mono.ok; ++k)
            for (int j = -1; j <= s && mono.ok; ++j)
                for (int i = -1; i <= s && mono.ok; ++i) {
                    if (!band[cell(i, j, k)]) continue;
                    for (int m = 0; m < 8; ++m) {
                        if (m & (1 << d)) continue;
                        const int x = i + (m & 1), y = j + ((m >> 1) & 1), z = k + ((m >> 2) & 1);
                        mono.add(fine[idx(x + (d == 0), y + (d == 1), z + (d == 2))] - fine[idx(x, y, z)]);
                    }
                }
        double distance = 0;
        if (mono.ok && within_budget(delta, mono.min_abs, edges[d], budget_world, distance)) return true;
    }
    return false;
}

void check_coarsening_interrupt(Interrupter* intr, int percent)
{
    if (intr && intr->wasInterrupted(percent)) throw Cancelled("adaptive grid: interrupted");
}

// Bottom-up construction: level by level, every parent whose 8 children are leaves, which keeps
// the grid k-balanced, and which parent_certified accepts.
void coarsen_bottom_up(AdaptiveGrid& g, const SampleField& fine, const SampleField& corner_field,
                       const CoarseningBudget& budget, const std::array<double, 3>& edges, Interrupter* intr)
{
    for (int l = 1; l <= budget.max_level; ++l) {
        check_coarsening_interrupt(intr, 40 * l / std::max(1, budget.max_level));
        const auto cand = merge_candidates(g, l);
        std::vector<char> ok(cand.size(), 0);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cand.size(), 64),
                          [&](const tbb::blocked_range<std::size_t>& rg) {
                              AdaptiveGrid::Reader r(g);
                              SampleField::Reader f(fine), corners(corner_field);
                              for (std::size_t i = rg.begin(); i < rg.end(); ++i) {
                                  const CellId& p = cand[i];
                                  if (!may_merge(r, p, budget.k)) continue;
                                  ok[i] = parent_certified(f, corners, p, edges, budget.distance_world);
                              }
                          });
        if (!merge_flagged(g, cand, ok)) break;
    }
    g.trim_levels();
    balance(g, budget.k);
}

// sum over leaves of (8^level - 1) / 7: the most splits that can still happen.
double split_potential(const AdaptiveGrid& g)
{
    double total = 0;
    for (int l = 1; l <= g.max_level(); ++l)
        total += double(g.leaves(l).size()) * (std::pow(8.0, l) - 1) / 7;
    return total;
}

// The leaves a failing cell's repair splits: the coarsest of the leaves covering the unit cells
// u - 2 .. u + 2, which hold every value u's certificate reads (its block's nodes u - 1 .. u + 2,
// hanging-node constraints included). The coarsest leaf there is the likeliest cause of what the
// failure measures, delta at u's corners or the smallest edge difference g of its block, since a
// coarse interpolant's error grows with its cell; splitting the finer leaves beside it as well undid
// what the grid had certified at their level (a torus's level-1 leaves at Sigma beside refused
// level-2 ones), and a finer leaf that still fails is split in a later round. A changed cell has
// a corner inside some coarse leaf's span, so this is never empty for one and each failing
// round splits a leaf.
void coarsest_leaves_read(const AdaptiveGrid::Reader& r, const Coord& u, std::vector<CellId>& near,
                          std::vector<CellId>& out)
{
    near.clear();
    int top = 1;
    for (int z = -2; z <= 2; ++z)
        for (int y = -2; y <= 2; ++y)
            for (int x = -2; x <= 2; ++x)
                if (const auto leaf = r.leaf(u.offsetBy(x, y, z)); leaf && leaf->level > 0) {
                    near.push_back(*leaf);
                    top = std::max(top, leaf->level);
                }
    for (const CellId& c : near)
        if (c.level == top) out.push_back(c);
}

} // namespace

std::array<double, 3> voxel_edges(const SampleField& field)
{
    std::array<double, 3> e{};
    for (int a = 0; a < 3; ++a) {
        Vec3d d(0.0);
        d[a] = 1.0;
        e[a] = (field.index_to_world(d) - field.index_to_world(Vec3d(0.0))).length();
    }
    return e;
}

CellCertificate certify_cell(const SampleField::Reader& f, const SampleField::Reader& a, const Coord& u,
                             const std::array<double, 3>& edges, double budget_world)
{
    CellCertificate cert;
    // The block's 4 x 4 x 4 nodes, u - 1 .. u + 2, of both functions.
    double vf[4][4][4], va[4][4][4];
    for (int k = 0; k < 4; ++k)
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) {
                const Coord n = u.offsetBy(i - 1, j - 1, k - 1);
                vf[k][j][i] = f.phi(n);
                va[k][j][i] = a.phi(n);
            }
    double delta = 0;
    for (int m = 0; m < 8; ++m) {
        const int i = 1 + (m & 1), j = 1 + ((m >> 1) & 1), k = 1 + ((m >> 2) & 1);
        if (va[k][j][i] == 0) { // the mesher needs phi != 0 at every sample (sample_field.h)
            cert.failure = CertificateFailure::CoarseSampleAtLevel;
            return cert;
        }
        delta = std::max(delta, std::abs(vf[k][j][i] - va[k][j][i]));
    }
    // Band cells of the block: the only ones a level set {phi_t = 0} can meet.
    bool band[3][3][3];
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) {
                bool pos = false, neg = false;
                for (int m = 0; m < 8; ++m) {
                    const int x = i + (m & 1), y = j + ((m >> 1) & 1), z = k + ((m >> 2) & 1);
                    for (double v : {vf[z][y][x], va[z][y][x]}) (v > 0 ? pos : neg) = true;
                }
                band[k][j][i] = pos && neg;
            }
    for (int d = 0; d < 3; ++d) {
        Monotone mono;
        for (int k = 0; k < 3 && mono.ok; ++k)
            for (int j = 0; j < 3 && mono.ok; ++j)
                for (int i = 0; i < 3 && mono.ok; ++i) {
                    if (!band[k][j][i]) continue;
                    for (int m = 0; m < 8; ++m) { // the cell's four d-edges: corners with bit d clear
                        if (m & (1 << d)) continue;
                        const int x = i + (m & 1), y = j + ((m >> 1) & 1), z = k + ((m >> 2) & 1);
                        const int x1 = x + (d == 0), y1 = y + (d == 1), z1 = z + (d == 2);
                        mono.add(vf[z1][y1][x1] - vf[z][y][x]);
                        mono.add(va[z1][y1][x1] - va[z][y][x]);
                    }
                }
        double distance = 0;
        if (!mono.ok || mono.sign == 0) continue;
        if (!within_budget(delta, mono.min_abs, edges[d], budget_world, distance)) {
            if (!cert.ok) cert.failure = CertificateFailure::OverBudget;
            continue;
        }
        cert.failure = CertificateFailure::None;
        if (!cert.ok || distance < cert.distance_world) {
            cert.ok = true;
            cert.axis = d;
            cert.distance_world = distance;
        }
    }
    if (!cert.ok && cert.failure == CertificateFailure::None) cert.failure = CertificateFailure::NoMonotoneAxis;
    return cert;
}

std::vector<Coord> cells_to_certify(const AdaptiveGrid& g, const SampleField& fine, const SampleField& coarse)
{
    // A node differs only inside a coarse leaf's closed span (elsewhere the coarse field keeps the
    // input's samples), so a changed cell lies in the one-cell shell around some coarse leaf:
    // each leaf reads the nodes of its shell once and tests the cells there.
    std::vector<CellId> coarse_leaves;
    for (int l = 1; l <= g.max_level(); ++l) {
        const auto ls = g.leaves(l);
        coarse_leaves.insert(coarse_leaves.end(), ls.begin(), ls.end());
    }
    std::vector<Coord> out;
    std::mutex mu;
    const CoordBBox cells = g.unit_cells();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, coarse_leaves.size(), 16),
                      [&](const tbb::blocked_range<std::size_t>& rg) {
                          SampleField::Reader f(fine), a(coarse);
                          std::vector<Coord> local;
                          std::vector<double> vf, va;
                          for (std::size_t i = rg.begin(); i < rg.end(); ++i) {
                              const CellId& leaf = coarse_leaves[i];
                              const Coord lo = leaf.origin.offsetBy(-1);
                              const int n = leaf.size() + 3; // nodes per axis: lo .. lo + size + 2
                              vf.resize(std::size_t(n) * n * n);
                              va.resize(vf.size());
                              auto at = [n](int x, int y, int z) { return (std::size_t(z) * n + y) * n + x; };
                              for (int z = 0; z < n; ++z)
                                  for (int y = 0; y < n; ++y)
                                      for (int x = 0; x < n; ++x) {
                                          const Coord q = lo.offsetBy(x, y, z);
                                          vf[at(x, y, z)] = f.phi(q);
                                          va[at(x, y, z)] = a.phi(q);
                                      }
                              for (int z = 0; z + 1 < n; ++z)
                                  for (int y = 0; y + 1 < n; ++y)
                                      for (int x = 0; x + 1 < n; ++x) {
                                          const Coord u = lo.offsetBy(x, y, z);
                                          if (!cells.isInside(u)) continue;
                                          bool changed = false, pos = false, neg = false;
                                          for (int m = 0; m < 8; ++m) {
                                              const std::size_t q = at(x + (m & 1), y + ((m >> 1) & 1), z + ((m >> 2) & 1));
                                              changed |= vf[q] != va[q];
                                              for (double v : {vf[q], va[q]}) (v > 0 ? pos : neg) = true;
                                          }
                                          if (changed && pos && neg) local.push_back(u);
                                      }
                          }
                          std::lock_guard<std::mutex> lock(mu);
                          out.insert(out.end(), local.begin(), local.end());
                      });
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

std::size_t crossings_coarse_leaves_could_remove(const SampleField& fine, const std::vector<EdgePoint>& e,
                                                 const std::vector<Coord>& crossed_cells,
                                                 const CoarseningBudget& budget)
{
    if (budget.max_level < 1) return 0;
    std::vector<Coord> parents;
    parents.reserve(crossed_cells.size());
    for (const Coord& c : crossed_cells) parents.push_back(align_down(c, 1));
    std::sort(parents.begin(), parents.end());
    parents.erase(std::unique(parents.begin(), parents.end()), parents.end());
    const auto edges = voxel_edges(fine);
    std::vector<char> ok(parents.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, parents.size(), 256), [&](const tbb::blocked_range<std::size_t>& r) {
        const SampleField::Reader f(fine);
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
            const CellId p{parents[i], 1};
            CoordBBox span(p.origin, p.origin.offsetBy(2));
            ok[i] = fine.domain().isInside(span) && parent_certified(f, f, p, edges, budget.distance_world);
        }
    });
    const auto accepted = [&](const Coord& cell) {
        const auto it = std::lower_bound(parents.begin(), parents.end(), align_down(cell, 1));
        return it != parents.end() && *it == align_down(cell, 1) && ok[std::size_t(it - parents.begin())];
    };
    std::size_t n = 0;
    for (const EdgePoint& p : e) {
        const auto around = cells_around_edge(p.lower, p.axis);
        n += std::any_of(around.begin(), around.end(), accepted);
    }
    return n;
}

CertifiedGrid certified_coarsening(const SampleField& fine, const CoarseningBudget& budget, Interrupter* intr,
                                   openvdb::FloatGrid::ConstPtr corner_samples)
{
    if (budget.k < 1) throw InvalidInput("adaptive grid: k must be >= 1");
    if (budget.max_level < 0 || budget.max_level > AdaptiveGrid::kMaxLevel)
        throw InvalidInput("adaptive grid: max level must be in [0, 15]");
    const auto edges = voxel_edges(fine);
    if (!corner_samples) corner_samples = fine.grid_ptr();
    CertifiedGrid out{AdaptiveGrid(corner_samples, budget.k), nullptr};
    AdaptiveGrid& g = out.grid;
    if (g.domain() != fine.domain())
        throw InvalidInput("adaptive grid: the corner samples' domain differs from the input's");
    // The corners' field: the input's own unless they come from elsewhere (no second scan).
    std::optional<SampleField> extended;
    if (corner_samples != fine.grid_ptr()) {
        extended.emplace(corner_samples, fine.isovalue(), fine.inside(), fine.effective_isovalue());
    }
    coarsen_bottom_up(g, fine, extended ? *extended : fine, budget, edges, intr);

    // Repair rounds: check the certificate on the continuous interpolant, split around failures.
    const double round_bound = split_potential(g) + 1;
    for (;;) {
        check_coarsening_interrupt(intr, 50);
        out.resampled = resample_dense(g, fine.grid());
        SampleField& coarse =
            out.field.emplace(out.resampled, fine.isovalue(), fine.inside(), fine.effective_isovalue());
        const auto cells = cells_to_certify(g, fine, coarse);
        std::vector<CertificateFailure> failed(cells.size(), CertificateFailure::None);
        std::vector<double> distance(cells.size(), 0);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.size(), 256),
                          [&](const tbb::blocked_range<std::size_t>& rg) {
                              SampleField::Reader f(fine), a(coarse);
                              for (std::size_t i = rg.begin(); i < rg.end(); ++i) {
                                  const CellCertificate c = certify_cell(f, a, cells[i], edges, budget.distance_world);
                                  failed[i] = c.failure;
                                  distance[i] = c.distance_world;
                              }
                          });
        out.cells_certified = cells.size();
        std::vector<CellId> split;
        AdaptiveGrid::Reader r(g);
        std::size_t reasons[4] = {0, 0, 0, 0};
        std::vector<CellId> near;
        for (std::size_t i = 0; i < cells.size(); ++i) {
            ++reasons[int(failed[i])];
            if (failed[i] != CertificateFailure::None) coarsest_leaves_read(r, cells[i], near, split);
        }
        if (intr) {
            const std::string line = "adaptive grid: round " + std::to_string(out.rounds) + ": " +
                                     std::to_string(cells.size()) + " cells to certify, failed: " +
                                     std::to_string(reasons[int(CertificateFailure::NoMonotoneAxis)]) +
                                     " no monotone axis, " + std::to_string(reasons[int(CertificateFailure::OverBudget)]) +
                                     " over budget, " +
                                     std::to_string(reasons[int(CertificateFailure::CoarseSampleAtLevel)]) +
                                     " coarse sample at v*";
            intr->log(line.c_str());
        }
        const std::size_t failures = cells.size() - reasons[int(CertificateFailure::None)];
        if (split.empty() && failures > 0) // a failing changed cell always has a coarse leaf near it
            throw GuaranteeViolated("adaptive grid: " + std::to_string(failures) +
                                    " cells failed their certificate with no coarse leaf to split");
        if (split.empty()) {
            out.distance_world = cells.empty() ? 0 : *std::max_element(distance.begin(), distance.end());
            break;
        }
        if (double(++out.rounds) > round_bound) // each round splits a leaf: cannot happen
            throw GuaranteeViolated("adaptive grid: the repair rounds exceeded their bound of " +
                                    std::to_string(round_bound) + " (the split potential)");
        std::sort(split.begin(), split.end());
        split.erase(std::unique(split.begin(), split.end()), split.end());
        for (const CellId& c : split) g.split(c);
        out.splits += split.size();
        balance(g, budget.k);
        g.trim_levels();
    }
    return out;
}

} // namespace isodel::octree
