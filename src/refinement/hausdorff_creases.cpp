// Sigma -> M along the creases (hausdorff_refinement.h, third check): where Sigma crosses a cell
// face it is only C0, and a ridge there can stand out of M between M's vertices. The crease
// curves of the crossed cells are sampled every eps/2 (crease_samples.h) and each sample must lie
// within 0.7 eps of M. The stages, in order:
//  1. M's triangles, kept from the last call for the facets still in M;
//  2. the cells to check: those never passed, and those a witness of which has left M;
//  3. each sample settled by a triangle within the threshold (a witness), tried among a few
//     triangles near it: an earlier sample's, then the cell's bucket (crease_cells.h); at a
//     coarse eps, where buckets would hold most of M, an AABB tree of M answers instead;
//  4. the distance to M of the samples nothing settled, from an AABB tree;
//  5. the verdicts: a cell whose farthest sample is beyond the threshold yields that sample.
#include "refinement/hausdorff_refinement.h"

#include "geometry/closest_on_triangle.h"
#include "refinement/crease_samples.h"
#include "self_checks.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

namespace isodel::mesher {
namespace {

using Vec3d = openvdb::Vec3d;
using KD = CGAL::Simple_cartesian<double>;
using Tree = CGAL::AABB_tree<
    CGAL::AABB_traits<KD, CGAL::AABB_triangle_primitive<KD, std::vector<KD::Triangle_3>::const_iterator>>>;

double distance_to(const Vec3d& w, const CreaseTriangle& t)
{
    return (geometry::closest_on_triangle(w, t.a, t.b, t.c) - w).length();
}

KD::Point_3 kd_point(const Vec3d& p) { return {p[0], p[1], p[2]}; }

/// Per crossed cell to check: what settled its crease samples.
struct CellCheck {
    bool any = false;                  ///< the cell has crease samples at all
    std::vector<FacetKey> witness;     ///< triangles within the threshold of its samples
    std::vector<Vec3d> far;            ///< samples no nearby triangle passes, in sampling order
    std::vector<double> far_distance;  ///< their distance to the measured set of triangles (stage 4)
    std::vector<FacetKey> far_nearest; ///< the triangle at that distance
};

/// What the stages after the first read.
struct CreaseInput {
    const octree::SampleField& field;
    const std::vector<const FacetCache::Entry*>& restricted;
    const std::vector<CreaseTriangle>& tris; ///< restricted's triangles, in its order
    const std::vector<openvdb::Coord>& crossed;
    const std::vector<std::size_t>& todo; ///< indices in crossed of the cells to check
    double eps;                           ///< the mesher's eps, world
    double limit;                         ///< the threshold, world
    double to_index_units;                ///< index_units_per_world()
    bool self_check;
};

constexpr std::size_t kRecent = 8; // triangles of a cell's earlier samples, tried first

/// Stage 3 for one cell: each sample is tried against the last kRecent triangles that passed
/// an earlier sample of the cell (eps/2 away along the crease, the lines of one face cross the
/// same few triangles), then against \p nearest, which returns a triangle within the threshold
/// (and records it as seen) or -1, having recorded the sample as far. Which triangle passes a
/// sample does not matter: the cell passes iff every sample is within the threshold of M, and
/// a witness only spares the cell a later recheck.
template <class Nearest>
void settle_samples(const CreaseInput& in, const std::vector<Vec3d>& samples, CellCheck& out, Nearest&& nearest)
{
    std::vector<std::uint32_t> seen; // triangles that passed a sample of this cell, newest last
    std::int64_t last_by = -1;       // the triangle that passed the previous sample
    for (const Vec3d& w : samples) {
        std::int64_t by = -1;
        for (std::size_t k = 0; k < std::min(seen.size(), kRecent) && by < 0; ++k) {
            const std::uint32_t t = seen[seen.size() - 1 - k];
            if (distance_to(w, in.tris[t]) <= in.limit) by = t;
        }
        if (by < 0) by = nearest(w, seen);
        if (by >= 0 && by != last_by) out.witness.push_back(in.restricted[std::size_t(by)]->key);
        last_by = by;
    }
    out.any = !samples.empty();
}

/// Stage 3 for every cell to check, in parallel: its samples (crease_samples.h) settled as
/// settle_samples says, with nearest_for(ti, out) the fallback for cell ti.
template <class NearestFor>
std::vector<CellCheck> settle_cells(const CreaseInput& in, NearestFor&& nearest_for)
{
    const int R = crease_lines_per_voxel(in.field.min_voxel_edge(), in.eps);
    std::vector<CellCheck> checks(in.todo.size());
    tbb::enumerable_thread_specific<octree::SampleField::Reader> readers(
        [&] { return octree::SampleField::Reader(in.field); });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, in.todo.size(), 16), [&](const auto& r) {
        auto& reader = readers.local();
        std::vector<Vec3d> samples;
        for (std::size_t ti = r.begin(); ti != r.end(); ++ti) {
            const openvdb::Coord c = in.crossed[in.todo[ti]];
            double corner[8];
            reader.cell_corners(c, corner);
            samples.clear();
            crease_samples(in.field, c, corner, R, samples);
            settle_samples(in, samples, checks[ti], nearest_for(ti, checks[ti]));
        }
    });
    return checks;
}

/// Stages 3 and 4 while the buckets are small: each sample is settled by its cell's bucket;
/// the samples none passes are measured against the triangles near the cells to check (all of
/// M when those are a quarter of the crossed cells or more), by an AABB tree of those within
/// `reach` of the far samples' cells where that suffices, of all of them otherwise.
std::vector<CellCheck> settle_by_buckets(const CreaseInput& in, std::atomic<std::size_t>& block_filter_checks)
{
    const std::vector<std::size_t>& todo = in.todo;
    std::vector<openvdb::Coord> blocks;
    if (16 * todo.size() < in.crossed.size()) {
        for (const std::size_t ci : todo) blocks.push_back(block_of(in.crossed[ci]));
        std::sort(blocks.begin(), blocks.end());
        blocks.erase(std::unique(blocks.begin(), blocks.end()), blocks.end());
    }
    CellSet cells(todo.size()); // (cell, index in todo)
    for (std::size_t ti = 0; ti < todo.size(); ++ti) cells[ti] = {in.crossed[todo[ti]], std::uint32_t(ti)};
    std::sort(cells.begin(), cells.end());
    const double margin = in.limit * in.to_index_units;
    const CreaseBuckets buckets = bucket_triangles(in.tris, cells, todo.size(), margin, blocks);
    if (in.self_check && !blocks.empty()) {
        for (std::size_t i = 0; i < in.tris.size(); ++i) {
            std::uint32_t n = 0;
            for_each_cell_near(in.tris[i].lo, in.tris[i].hi, cells, margin, {}, [&](std::uint32_t) { ++n; });
            if (n != buckets.n_near[i])
                throw std::logic_error("crease check: the block filter skipped a triangle near a cell to check");
        }
        ++block_filter_checks;
    }
    std::vector<CellCheck> checks = settle_cells(in, [&](std::size_t ti, CellCheck& cell) {
        CellCheck* const out = &cell;
        return [&, ti, out](const Vec3d& w, std::vector<std::uint32_t>& seen) -> std::int64_t {
            for (std::size_t k = buckets.at[ti]; k < buckets.at[ti + 1]; ++k) {
                const std::uint32_t t = buckets.list[k];
                if (distance_to(w, in.tris[t]) > in.limit) continue;
                seen.push_back(t);
                return t;
            }
            out->far.push_back(w);
            return -1;
        };
    });

    // Stage 4.
    const auto near_any = [&](std::size_t i) { return 4 * todo.size() >= in.crossed.size() || buckets.n_near[i] > 0; };
    CellSet far_cells; // (cell, index in todo)
    for (std::size_t ti = 0; ti < todo.size(); ++ti)
        if (!checks[ti].far.empty()) far_cells.push_back({in.crossed[todo[ti]], std::uint32_t(ti)});
    std::sort(far_cells.begin(), far_cells.end());
    const double reach = 4 * in.limit;
    const bool try_local = reach * in.to_index_units <= 1.0; // a few cells per axis around a triangle
    std::vector<std::size_t> near;                           // indices in tris of the tree's triangles
    std::vector<KD::Triangle_3> near_tris;
    Tree tree;
    for (const auto& [c, ti] : far_cells) {
        checks[ti].far_distance.resize(checks[ti].far.size());
        checks[ti].far_nearest.resize(checks[ti].far.size());
    }
    const auto measure = [&](bool local) {
        near.clear();
        std::vector<char> in_tree(in.tris.size(), 0);
        const auto reaches_far_cell = [&](std::size_t i, const std::vector<openvdb::Coord>& filter) {
            char hit = 0;
            for_each_cell_near(in.tris[i].lo, in.tris[i].hi, far_cells, reach * in.to_index_units, filter,
                               [&](std::uint32_t) { hit = 1; });
            return hit;
        };
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, in.tris.size(), 4096), [&](const auto& r) {
            for (std::size_t i = r.begin(); i != r.end(); ++i)
                if (near_any(i)) in_tree[i] = local ? reaches_far_cell(i, blocks) : 1;
        });
        if (in.self_check && local && !blocks.empty())
            for (std::size_t i = 0; i < in.tris.size(); ++i)
                if ((near_any(i) ? reaches_far_cell(i, {}) : 0) != in_tree[i])
                    throw std::logic_error("crease check: the block filter skipped a triangle near a far sample's cell");
        for (std::size_t i = 0; i < in.tris.size(); ++i)
            if (in_tree[i]) near.push_back(i);
        // The local set is empty: every triangle of the set is farther than `reach` from the far
        // samples, so the whole set decides.
        if (local && near.empty()) return false;
        // No triangle near the cells to check: every far sample is farther than the threshold
        // from M; any one triangle keeps the tree non-empty (its distances exceed it too).
        if (near.empty()) near.push_back(0);
        near_tris.clear();
        for (const std::size_t i : near)
            near_tris.emplace_back(kd_point(in.tris[i].a), kd_point(in.tris[i].b), kd_point(in.tris[i].c));
        tree.clear();
        tree.insert(near_tris.cbegin(), near_tris.cend());
        tree.build();
        std::vector<char> beyond(far_cells.size(), 0);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, far_cells.size(), 4), [&](const auto& r) {
            for (std::size_t fi = r.begin(); fi != r.end(); ++fi) {
                CellCheck& k = checks[far_cells[fi].second];
                for (std::size_t j = 0; j < k.far.size(); ++j) {
                    const KD::Point_3 q = kd_point(k.far[j]);
                    const auto cp = tree.closest_point_and_primitive(q);
                    const double d = std::sqrt(CGAL::squared_distance(q, cp.first));
                    // Every triangle of the set within `reach` of the sample is in the local tree.
                    if (local && d > reach) beyond[fi] = 1;
                    k.far_distance[j] = d;
                    k.far_nearest[j] = in.restricted[near[std::size_t(cp.second - near_tris.cbegin())]]->key;
                }
            }
        });
        return std::none_of(beyond.begin(), beyond.end(), [](char b) { return b != 0; });
    };
    if (!far_cells.empty() && !(try_local && measure(true))) measure(false);
    return checks;
}

/// Stages 3 and 4 at a coarse eps, where a triangle's box grown by the threshold spans more
/// than crease_bucket_margin cells per side and the buckets would hold most of M for every
/// cell (their size grows as eps cubed): an AABB tree of all of M gives each sample not passed
/// by a recent triangle its nearest triangle, which passes it or measures it as far.
std::vector<CellCheck> settle_by_tree(const CreaseInput& in)
{
    std::vector<KD::Triangle_3> all;
    all.reserve(in.tris.size());
    for (const CreaseTriangle& t : in.tris) all.emplace_back(kd_point(t.a), kd_point(t.b), kd_point(t.c));
    Tree tree(all.cbegin(), all.cend());
    tree.build();
    tree.accelerate_distance_queries(); // built here, not lazily by the first of concurrent queries
    return settle_cells(in, [&](std::size_t, CellCheck& cell) {
        CellCheck* const out = &cell;
        return [&, out](const Vec3d& w, std::vector<std::uint32_t>& seen) -> std::int64_t {
            const KD::Point_3 q = kd_point(w);
            const auto cp = tree.closest_point_and_primitive(q);
            const double d = std::sqrt(CGAL::squared_distance(q, cp.first));
            const auto t = std::uint32_t(cp.second - all.cbegin());
            if (d <= in.limit) {
                seen.push_back(t);
                return t;
            }
            out->far.push_back(w);
            out->far_distance.push_back(d);
            out->far_nearest.push_back(in.restricted[t]->key);
            return -1;
        };
    });
}

std::atomic<std::size_t> g_block_filter_checks{0};

} // namespace

std::size_t HausdorffRefinement::crease_block_filter_checks() { return g_block_filter_checks.load(); }

double HausdorffRefinement::index_units_per_world() const
{
    double frob = 0;
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) frob += world_to_index_(r, k) * world_to_index_(r, k);
    return std::sqrt(frob) * (1 + 1e-9);
}

CreaseTriangle HausdorffRefinement::crease_triangle(const FacetCache::Entry& e) const
{
    const auto vs = facet_vertices(e.facet); // in id order: a function of the key
    CreaseTriangle t;
    t.a = to_vdb(vs[0]->point());
    t.b = to_vdb(vs[1]->point());
    t.c = to_vdb(vs[2]->point());
    t.lo = Vec3d(std::numeric_limits<double>::max());
    t.hi = Vec3d(-std::numeric_limits<double>::max());
    for (const Vec3d& v : {t.a, t.b, t.c}) {
        const Vec3d x = field_.world_to_index(v);
        t.lo = openvdb::math::minComponent(t.lo, x);
        t.hi = openvdb::math::maxComponent(t.hi, x);
    }
    return t;
}

std::vector<FacetKey> HausdorffRefinement::update_crease_triangles(
    const std::vector<const FacetCache::Entry*>& restricted, bool self_check)
{
    std::vector<FacetKey> now(restricted.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, restricted.size(), 4096), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) now[i] = restricted[i]->key;
    });
    // One merge walk of the last call's M and this one (both sorted) finds the facets that left
    // and the triangles to keep: the last call's for the facets still in M (after the first call
    // nearly all of them, whose vertices would otherwise be read again, scattered in memory);
    // the new facets' are computed.
    std::vector<FacetKey> left;     // in the last call's M, not in this one, sorted
    std::vector<std::size_t> fresh; // indices in restricted of the facets new in M
    std::vector<CreaseTriangle> built(restricted.size());
    std::size_t j = 0;
    for (std::size_t i = 0; i < now.size(); ++i) {
        for (; j < crease_m_.size() && crease_m_[j] < now[i]; ++j) left.push_back(crease_m_[j]);
        if (j < crease_m_.size() && crease_m_[j] == now[i]) built[i] = crease_tris_[j++];
        else fresh.push_back(i);
    }
    left.insert(left.end(), crease_m_.begin() + std::ptrdiff_t(j), crease_m_.end());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, fresh.size(), 4096), [&](const auto& r) {
        for (std::size_t k = r.begin(); k != r.end(); ++k) built[fresh[k]] = crease_triangle(*restricted[fresh[k]]);
    });
    if (self_check)
        for (std::size_t i = 0; i < restricted.size(); ++i) {
            const CreaseTriangle t = crease_triangle(*restricted[i]);
            const CreaseTriangle& k = built[i];
            if (t.a != k.a || t.b != k.b || t.c != k.c || t.lo != k.lo || t.hi != k.hi)
                throw std::logic_error("crease check: a triangle kept from the last call differs from its facet's");
        }
    crease_m_ = std::move(now);
    crease_tris_ = std::move(built);
    return left;
}

std::vector<std::size_t> HausdorffRefinement::crease_cells_to_check(const std::vector<FacetKey>& left)
{
    // A cell that passed before still passes while its witnesses (a triangle within the
    // threshold of each sample) are in M: d(s, M) <= d(s, T) for every T in M. Its witnesses
    // were all in M at the last call, so one has left M iff it is among the facets that left.
    crease_state_.resize(crossed_cells_.size(), CreaseState::Unknown);
    crease_witness_.resize(crossed_cells_.size());
    std::vector<char> recheck(crossed_cells_.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, crossed_cells_.size(), 1024), [&](const auto& r) {
        for (std::size_t ci = r.begin(); ci != r.end(); ++ci)
            recheck[ci] = crease_state_[ci] == CreaseState::Unknown ||
                          (crease_state_[ci] == CreaseState::Passed &&
                           std::any_of(crease_witness_[ci].begin(), crease_witness_[ci].end(), [&](const FacetKey& k) {
                               return std::binary_search(left.begin(), left.end(), k);
                           }));
    });
    std::vector<std::size_t> todo;
    for (std::size_t ci = 0; ci < crossed_cells_.size(); ++ci)
        if (recheck[ci]) todo.push_back(ci);
    return todo;
}

std::vector<Candidate> HausdorffRefinement::crease_violations(const std::vector<const FacetCache::Entry*>& restricted)
{
    if (restricted.empty()) return {};
    const bool self_check = incremental_self_checks();
    const std::vector<FacetKey> left = update_crease_triangles(restricted, self_check);
    const std::vector<std::size_t> todo = crease_cells_to_check(left);
    if (todo.empty()) return {};
    const double limit = 0.7 * eps_;
    const CreaseInput in{field_, restricted, crease_tris_, crossed_cells_, todo, eps_, limit, index_units_per_world(),
                         self_check};
    std::vector<CellCheck> checks = limit * in.to_index_units <= crease_bucket_margin
                                        ? settle_by_buckets(in, g_block_filter_checks)
                                        : settle_by_tree(in);

    // Stage 5: a cell passes when every sample is within the threshold; otherwise its farthest
    // sample is the candidate, and the cell is checked again at the next call.
    std::vector<std::vector<Candidate>> found(todo.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, todo.size(), 16), [&](const auto& r) {
        for (std::size_t ti = r.begin(); ti != r.end(); ++ti) {
            const std::size_t ci = todo[ti];
            CellCheck& k = checks[ti];
            double worst = limit;
            Vec3d worst_at;
            for (std::size_t j = 0; j < k.far.size(); ++j) {
                k.witness.push_back(k.far_nearest[j]);
                if (k.far_distance[j] > worst) {
                    worst = k.far_distance[j];
                    worst_at = k.far[j];
                }
            }
            if (!k.any) {
                crease_state_[ci] = CreaseState::NoCrease;
            } else if (worst > limit) {
                crease_state_[ci] = CreaseState::Unknown;
                found[ti].push_back({Point(worst_at[0], worst_at[1], worst_at[2]), PointKind::Geometry, worst,
                                     FacetKey{{std::uint32_t(ci), 0xffffffffu, 0}}});
            } else {
                std::sort(k.witness.begin(), k.witness.end());
                k.witness.erase(std::unique(k.witness.begin(), k.witness.end()), k.witness.end());
                crease_state_[ci] = CreaseState::Passed;
                crease_witness_[ci] = std::move(k.witness);
            }
        }
    });
    std::vector<Candidate> out;
    for (auto& v : found)
        for (const Candidate& c : v) {
            if (keep_ && !keep_(c.p)) crease_state_[c.origin.v[0]] = CreaseState::NoCrease; // not ours (set_filter)
            else out.push_back(c);
        }
    return out;
}

} // namespace isodel::mesher
