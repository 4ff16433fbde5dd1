// Sigma -> M along the creases (hausdorff_refinement.h, third check): where Sigma crosses a cell
// face it is only C0, and a ridge there can stand out of M between M's vertices. The crease
// curves of the crossed cells are sampled every eps/2 and each sample must lie within 0.7 eps of
// M. Most samples are settled by a few triangles near them (an earlier sample's, then the
// triangles whose boxes reach the sample's cell); only a sample none of those passes is farther
// than the threshold from all of M, and only there is its distance asked of an AABB tree.
#include "mesher/hausdorff_refinement.h"

#include "geometry/closest_on_triangle.h"
#include "octree/cell_interpolant.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

namespace isodel::mesher {
namespace {

using Vec3d = openvdb::Vec3d;

template <class Tri>
double distance_to(const Vec3d& w, const Tri& t) { return (geometry::closest_on_triangle(w, t.a, t.b, t.c) - w).length(); }

/// Per crossed cell to check: its crease samples in order, and what settled them.
struct CellCheck {
    bool any = false;              ///< the cell has crease samples at all
    std::vector<FacetKey> witness; ///< triangles within the threshold of its samples
    std::vector<Vec3d> far;        ///< samples no nearby triangle passes, in sampling order
};

std::atomic<std::size_t> g_block_filter_checks{0};

} // namespace

std::size_t HausdorffRefinement::crease_block_filter_checks() { return g_block_filter_checks.load(); }

std::vector<Candidate> HausdorffRefinement::crease_violations(const std::vector<const FacetCache::Entry*>& restricted)
{
    if (restricted.empty()) return {};
    // A cell that passed before still passes while its witnesses (a triangle within the
    // threshold of each sample) are in M: d(s, M) <= d(s, T) for every T in M. Only the other
    // cells are sampled again. A cell's witnesses were all in M at the last call (it was checked
    // then, or they were all still there), so one has left M iff it is among the facets that
    // left since: a short list.
    std::vector<FacetKey> now(restricted.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, restricted.size(), 4096), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) now[i] = restricted[i]->key;
    });
    // One merge walk of the last call's M and this one (both sorted) finds the facets that left
    // and the triangles to keep: the last call's for the facets still in M (after the first call
    // nearly all of them: reading every facet's vertices again, scattered in memory, took ~95 ms
    // a call on a 128^3 protein); the new facets' are computed.
    std::vector<FacetKey> left;      // in the last call's M, not in this one, sorted
    std::vector<std::size_t> fresh;  // indices in restricted of the facets new in M
    std::vector<CreaseTriangle> built(restricted.size());
    std::size_t j = 0;
    for (std::size_t i = 0; i < now.size(); ++i) {
        for (; j < crease_m_.size() && crease_m_[j] < now[i]; ++j) left.push_back(crease_m_[j]);
        if (j < crease_m_.size() && crease_m_[j] == now[i]) built[i] = crease_tris_[j++];
        else fresh.push_back(i);
    }
    left.insert(left.end(), crease_m_.begin() + std::ptrdiff_t(j), crease_m_.end());
    const auto triangle_of = [&](const FacetCache::Entry& e) {
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
    };
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, fresh.size(), 4096), [&](const auto& r) {
        for (std::size_t k = r.begin(); k != r.end(); ++k) built[fresh[k]] = triangle_of(*restricted[fresh[k]]);
    });
    const bool self_check = std::getenv("ISODEL_CHECK_INCREMENTAL") != nullptr;
    if (self_check)
        for (std::size_t i = 0; i < restricted.size(); ++i) {
            const CreaseTriangle t = triangle_of(*restricted[i]);
            const CreaseTriangle& k = built[i];
            if (t.a != k.a || t.b != k.b || t.c != k.c || t.lo != k.lo || t.hi != k.hi)
                throw std::logic_error("crease check: a triangle kept from the last call differs from its facet's");
        }
    crease_m_ = std::move(now);
    crease_tris_ = std::move(built);
    const std::vector<CreaseTriangle>& tris = crease_tris_;
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
    if (todo.empty()) return {};
    const double limit = 0.7 * eps_;

    // World distance r is at most r |world_to_index|_F index units along any axis.
    double frob = 0;
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) frob += world_to_index_(r, k) * world_to_index_(r, k);
    const double to_index_units = std::sqrt(frob) * (1 + 1e-9);
    using CellSet = std::vector<std::pair<openvdb::Coord, std::uint32_t>>; // sorted (cell, index)
    // Blocks of 8^3 cells holding a cell to check, when they are few (later calls recheck a few
    // hundred of 77 k cells on a 128^3 protein): most triangles are nowhere near one, and a
    // look-up per block of a triangle's box says so, instead of one per cell (45-65 ms a call).
    const auto block_of = [](const openvdb::Coord& c) {
        const auto down = [](int x) { return x >= 0 ? x / 8 : -((7 - x) / 8); }; // floor(x / 8)
        return openvdb::Coord(down(c[0]), down(c[1]), down(c[2]));
    };
    std::vector<openvdb::Coord> blocks;
    // Runs f with the block filter off (the self-checks' fresh computation).
    const auto without_blocks = [&](auto&& f) {
        std::vector<openvdb::Coord> kept;
        kept.swap(blocks);
        f();
        blocks.swap(kept);
    };
    if (16 * todo.size() < crossed_cells_.size()) {
        for (const std::size_t ci : todo) blocks.push_back(block_of(crossed_cells_[ci]));
        std::sort(blocks.begin(), blocks.end());
        blocks.erase(std::unique(blocks.begin(), blocks.end()), blocks.end());
    }
    // Calls f(index) for each cell of \p cells (cells to check, or some of them) that triangle
    // t's box, grown by \p margin index units, meets.
    const auto for_each_cell_near = [&](const CreaseTriangle& t, const CellSet& cells, double margin, auto&& f) {
        const Vec3d &lo = t.lo, &hi = t.hi;
        // Cells [c, c + 1] meeting the box [lo - margin, hi + margin].
        const openvdb::Coord a(int(std::ceil(lo[0] - margin)) - 1, int(std::ceil(lo[1] - margin)) - 1,
                               int(std::ceil(lo[2] - margin)) - 1);
        const openvdb::Coord b(int(std::floor(hi[0] + margin)), int(std::floor(hi[1] + margin)),
                               int(std::floor(hi[2] + margin)));
        if (!blocks.empty()) {
            const openvdb::Coord ba = block_of(a), bb = block_of(b);
            bool any = false;
            for (int x = ba[0]; x <= bb[0] && !any; ++x)
                for (int y = ba[1]; y <= bb[1] && !any; ++y)
                    for (int z = ba[2]; z <= bb[2] && !any; ++z)
                        any = std::binary_search(blocks.begin(), blocks.end(), openvdb::Coord(x, y, z));
            if (!any) return;
        }
        for (int x = a[0]; x <= b[0]; ++x)
            for (int y = a[1]; y <= b[1]; ++y)
                for (int z = a[2]; z <= b[2]; ++z) {
                    const openvdb::Coord c(x, y, z);
                    const auto it = std::lower_bound(cells.begin(), cells.end(), c,
                                                     [](const auto& e, const openvdb::Coord& k) { return e.first < k; });
                    if (it != cells.end() && it->first == c) f(it->second);
                }
    };

    // Each cell's bucket: the triangles whose box, grown by `limit`, meets the cell. A sample lies
    // in its cell, so a triangle within `limit` of it is in the bucket; a sample no triangle of
    // the bucket passes is farther than `limit` from all of M.
    CellSet cells(todo.size()); // (cell, index in todo)
    for (std::size_t ti = 0; ti < todo.size(); ++ti) cells[ti] = {crossed_cells_[todo[ti]], std::uint32_t(ti)};
    std::sort(cells.begin(), cells.end());
    const double margin = limit * to_index_units;
    std::vector<std::uint32_t> n_near(tris.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tris.size(), 4096), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i)
            for_each_cell_near(tris[i], cells, margin, [&](std::uint32_t) { ++n_near[i]; });
    });
    if (self_check && !blocks.empty()) {
        without_blocks([&] {
            for (std::size_t i = 0; i < tris.size(); ++i) {
                std::uint32_t n = 0;
                for_each_cell_near(tris[i], cells, margin, [&](std::uint32_t) { ++n; });
                if (n != n_near[i])
                    throw std::logic_error("crease check: the block filter skipped a triangle near a cell to check");
            }
        });
        ++g_block_filter_checks;
    }
    std::vector<std::size_t> pair_at(tris.size() + 1, 0);
    for (std::size_t i = 0; i < tris.size(); ++i) pair_at[i + 1] = pair_at[i] + n_near[i];
    std::vector<std::uint32_t> pair_cell(pair_at.back());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tris.size(), 4096), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            if (n_near[i] == 0) continue;
            std::size_t at = pair_at[i];
            for_each_cell_near(tris[i], cells, margin, [&](std::uint32_t ti) { pair_cell[at++] = ti; });
        }
    });
    // Counting sort by cell: bucket[bucket_at[ti] .. bucket_at[ti + 1]) in triangle order.
    std::vector<std::size_t> bucket_at(todo.size() + 1, 0);
    for (const std::uint32_t ti : pair_cell) ++bucket_at[ti + 1];
    for (std::size_t ti = 0; ti < todo.size(); ++ti) bucket_at[ti + 1] += bucket_at[ti];
    std::vector<std::uint32_t> bucket(pair_cell.size());
    {
        std::vector<std::size_t> fill(bucket_at.begin(), bucket_at.end() - 1);
        for (std::size_t i = 0; i < tris.size(); ++i)
            for (std::size_t k = pair_at[i]; k < pair_at[i + 1]; ++k) bucket[fill[pair_cell[k]]++] = std::uint32_t(i);
    }

    // Lines every eps/2 (world) on each face; R lines per unit of index.
    const int R = std::clamp(int(std::ceil(2.0 * field_.min_voxel_edge() / eps_)), 2, 64);
    const octree::FaceSlabs& slabs = field_.face_slabs();
    constexpr std::size_t kRecent = 8; // triangles of earlier samples of a cell tried first
    std::vector<CellCheck> checks(todo.size());
    tbb::enumerable_thread_specific<octree::SampleField::Reader> readers([&] { return octree::SampleField::Reader(field_); });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, todo.size(), 16), [&](const auto& r) {
        auto& reader = readers.local();
        for (std::size_t ti = r.begin(); ti != r.end(); ++ti) {
            const openvdb::Coord c = crossed_cells_[todo[ti]];
            CellCheck& out = checks[ti];
            double corner[8];
            reader.cell_corners(c, corner);
            const auto f = octree::Trilinear::from_corners(corner);
            std::vector<std::uint32_t> seen; // triangles that passed a sample of this cell, newest last
            std::int64_t last_by = -1;       // the triangle that passed the previous sample
            // Faces x = 0, 1; y = 0, 1; z = 0, 1 of the cell; on each, lines along the two other axes.
            for (int axis = 0; axis < 3; ++axis)
                for (int side = 0; side < 2; ++side) {
                    // F is bilinear on the face, so it has the corners' sign all over the face
                    // when they agree: no line on it crosses Sigma.
                    int n_inside = 0;
                    for (int k = 0; k < 8; ++k)
                        if (((k >> axis) & 1) == side && corner[k] >= 0) ++n_inside;
                    if (n_inside == 0 || n_inside == 4) continue;
                    for (int dir = 0; dir < 3; ++dir) {
                        if (dir == axis) continue;
                        const int other = 3 - axis - dir;
                        for (int i = 1; i < R; ++i) {
                            Vec3d p0(0.0);
                            p0[axis] = side;
                            p0[other] = double(i) / R;
                            Vec3d p1 = p0;
                            p1[dir] = 1;
                            const double v0 = f(p0[0], p0[1], p0[2]), v1 = f(p1[0], p1[1], p1[2]);
                            if ((v0 >= 0) == (v1 >= 0)) continue;
                            out.any = true;
                            const Vec3d l = p0 + (p1 - p0) * (v0 / (v0 - v1)); // F is linear here
                            // Sigma' (face_slabs.h) has this crease at the slab's boundary on
                            // the cell's side: the same curve, mapped, h inside the cell.
                            Vec3d m = slabs.from_sample(c.asVec3d() + l);
                            m[axis] += side == 0 ? slabs.h : -slabs.h;
                            const Vec3d w = field_.index_to_world(m);
                            // d(w, M) <= d(w, T) for T in M. The triangles that passed the
                            // previous samples (eps/2 away along the crease; the lines of one
                            // face cross the same few triangles) usually pass w too; then the
                            // cell's bucket. Which triangle passes w does not matter: the cell
                            // passes iff every sample is within `limit` of M, and a witness
                            // only spares the cell a later recheck.
                            std::int64_t by = -1;
                            for (std::size_t k = 0; k < std::min(seen.size(), kRecent) && by < 0; ++k) {
                                const std::uint32_t t = seen[seen.size() - 1 - k];
                                if (distance_to(w, tris[t]) <= limit) by = t;
                            }
                            for (std::size_t k = bucket_at[ti]; k < bucket_at[ti + 1] && by < 0; ++k) {
                                const std::uint32_t t = bucket[k];
                                if (distance_to(w, tris[t]) > limit) continue;
                                by = t;
                                seen.push_back(t);
                            }
                            if (by < 0) out.far.push_back(w);
                            else if (by != last_by) out.witness.push_back(restricted[std::size_t(by)]->key);
                            last_by = by;
                        }
                    }
                }
        }
    });

    // The samples no nearby triangle passed are farther than `limit` from M; the candidate is
    // the farthest, at that distance, so each needs its distance to the nearest of the triangles
    // near the cells to check (all of M when they are a quarter of the crossed cells or more),
    // the set earlier versions held in their one tree. An AABB tree of those of them within
    // `reach` of the far samples' cells gives it where it is at most `reach`; otherwise (rare, or
    // at a coarse eps, where `reach` would span many cells) a tree of the whole set.
    using KD = CGAL::Simple_cartesian<double>;
    using Tree = CGAL::AABB_tree<CGAL::AABB_traits<KD, CGAL::AABB_triangle_primitive<KD, std::vector<KD::Triangle_3>::const_iterator>>>;
    const auto near_any = [&](std::size_t i) { return 4 * todo.size() >= crossed_cells_.size() || n_near[i] > 0; };
    CellSet far_cells; // (cell, index in todo)
    for (std::size_t ti = 0; ti < todo.size(); ++ti)
        if (!checks[ti].far.empty()) far_cells.push_back({crossed_cells_[todo[ti]], std::uint32_t(ti)});
    std::sort(far_cells.begin(), far_cells.end());
    const double reach = 4 * limit;
    const bool try_local = reach * to_index_units <= 1.0; // a few cells per axis around a triangle
    std::vector<std::size_t> near; // indices in tris of the tree's triangles
    std::vector<KD::Triangle_3> near_tris;
    Tree tree;
    std::vector<double> far_distance; // per far sample, in far_cells' order
    std::vector<FacetKey> far_nearest; // the triangle at that distance
    std::vector<std::size_t> far_at(todo.size(), 0); // each cell's first far sample in far_distance
    std::size_t n_far = 0;
    for (const auto& [c, ti] : far_cells) {
        far_at[ti] = n_far;
        n_far += checks[ti].far.size();
    }
    far_distance.resize(n_far);
    far_nearest.resize(n_far);
    const auto measure = [&](bool local) {
        near.clear();
        std::vector<char> in_tree(tris.size(), 0);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tris.size(), 4096), [&](const auto& r) {
            for (std::size_t i = r.begin(); i != r.end(); ++i)
                if (near_any(i)) {
                    if (!local) in_tree[i] = 1;
                    else for_each_cell_near(tris[i], far_cells, reach * to_index_units, [&](std::uint32_t) { in_tree[i] = 1; });
                }
        });
        if (self_check && local && !blocks.empty())
            without_blocks([&] {
                for (std::size_t i = 0; i < tris.size(); ++i) {
                    char in = 0;
                    if (near_any(i))
                        for_each_cell_near(tris[i], far_cells, reach * to_index_units, [&](std::uint32_t) { in = 1; });
                    if (in != in_tree[i])
                        throw std::logic_error(
                            "crease check: the block filter skipped a triangle near a far sample's cell");
                }
            });
        for (std::size_t i = 0; i < tris.size(); ++i)
            if (in_tree[i]) near.push_back(i);
        // The local set is empty: every triangle of the set is farther than `reach` from the far
        // samples, so the whole set decides.
        if (local && near.empty()) return false;
        // No triangle near the cells to check: every far sample is farther than `limit` from M;
        // any one triangle keeps the tree non-empty (its distances exceed `limit` too).
        if (near.empty()) near.push_back(0);
        const auto kp = [](const Vec3d& p) { return KD::Point_3(p[0], p[1], p[2]); };
        near_tris.clear();
        for (const std::size_t i : near) near_tris.emplace_back(kp(tris[i].a), kp(tris[i].b), kp(tris[i].c));
        tree.clear();
        tree.insert(near_tris.cbegin(), near_tris.cend());
        tree.build();
        std::vector<char> beyond(far_cells.size(), 0);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, far_cells.size(), 4), [&](const auto& r) {
            for (std::size_t fi = r.begin(); fi != r.end(); ++fi) {
                const std::uint32_t ti = far_cells[fi].second;
                for (std::size_t j = 0; j < checks[ti].far.size(); ++j) {
                    const Vec3d& w = checks[ti].far[j];
                    const KD::Point_3 q(w[0], w[1], w[2]);
                    const auto cp = tree.closest_point_and_primitive(q);
                    const double d = std::sqrt(CGAL::squared_distance(q, cp.first));
                    // Every triangle of the set within `reach` of w is in the local tree.
                    if (local && d > reach) beyond[fi] = 1;
                    far_distance[far_at[ti] + j] = d;
                    far_nearest[far_at[ti] + j] = restricted[near[std::size_t(cp.second - near_tris.cbegin())]]->key;
                }
            }
        });
        return std::none_of(beyond.begin(), beyond.end(), [](char b) { return b != 0; });
    };
    if (!far_cells.empty() && !(try_local && measure(true))) measure(false);
    std::vector<std::vector<Candidate>> found(todo.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, todo.size(), 16), [&](const auto& r) {
        for (std::size_t ti = r.begin(); ti != r.end(); ++ti) {
            const std::size_t ci = todo[ti];
            CellCheck& k = checks[ti];
            double worst = limit;
            Vec3d worst_at;
            for (std::size_t j = 0; j < k.far.size(); ++j) {
                const double d = far_distance[far_at[ti] + j];
                k.witness.push_back(far_nearest[far_at[ti] + j]);
                if (d > worst) {
                    worst = d;
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
