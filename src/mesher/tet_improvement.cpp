#include "mesher/tet_improvement.h"

#include "mesher/tet_quality.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <vector>

namespace isodel::mesher {
namespace {

using V3 = std::array<double, 3>;
using Tet = std::array<std::int32_t, 4>;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;

V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 cross(const V3& a, const V3& b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const V3& a) { return std::sqrt(dot(a, a)); }
constexpr double kPi = 3.14159265358979323846;

/// Exact sign of the orientation of (a, b, c, d) (EPICK's filtered predicate on the doubles).
int orient(const V3& a, const V3& b, const V3& c, const V3& d)
{
    auto P = [](const V3& p) { return K::Point_3(p[0], p[1], p[2]); };
    return int(CGAL::orientation(P(a), P(b), P(c), P(d)));
}


/// Tet quality inside the improver: minus the largest cosine of the six dihedral angles, which
/// grows with the smallest angle (no acos in the inner loops); -1 for a flat tet.
double quality(const V3& a, const V3& b, const V3& c, const V3& d)
{
    const V3* p[4] = {&a, &b, &c, &d};
    static constexpr int kEdges[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}, {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
    double cmax = -1;
    for (const auto& e : kEdges) {
        const V3 ev = sub(*p[e[1]], *p[e[0]]);
        const V3 n1 = cross(ev, sub(*p[e[2]], *p[e[0]]));
        const V3 n2 = cross(ev, sub(*p[e[3]], *p[e[0]]));
        const double den = std::sqrt(dot(n1, n1) * dot(n2, n2));
        if (!(den > 0)) return -1;
        cmax = std::max(cmax, dot(n1, n2) / den);
    }
    return -std::min(cmax, 1.0);
}
double degrees(double q) { return std::acos(std::clamp(-q, -1.0, 1.0)) * 180.0 / kPi; }
constexpr double kBest = 2;     ///< above every quality
constexpr double kInvalid = -3; ///< below every quality: an inverted tet
constexpr double kMargin = 1e-12; ///< an improvement must beat the old quality by this much
constexpr std::size_t kMaxSmoothStar = 256; ///< larger stars are not smoothed or collapsed (Improver::try_smooth)

/// A flip may only replace tets by tets filling the same polytope. The orientation predicates
/// decide that exactly; equal volumes are a second, floating-point, sanity check.
bool same_volume(double before, double after) { return std::abs(before - after) <= 1e-9 * std::abs(before); }

class Improver {
public:
    Improver(TetMesh& m, std::size_t surface_vertices, double target_deg)
        : m_(m), fixed_(surface_vertices), target_(-std::cos(target_deg * kPi / 180.0)), star_(m.vertices.size()),
          version_(m.vertices.size(), 0), smooth_failed_(m.vertices.size(), 0), free_at_(m.vertices.size(), 0),
          free_(m.vertices.size(), 0)
    {
        for (std::size_t t = 0; t < m.tets.size(); ++t) add(m.tets[t], m.tet_region[t]);
    }

    TetImprovementStats run(const TetImprovementParams& params)
    {
        TetImprovementStats st;
        double worst = kBest;
        for (std::size_t t = 0; t < tets_.size(); ++t) worst = std::min(worst, q(t));
        st.min_dihedral_before_deg = tets_.empty() ? 0 : degrees(worst);
        for (; st.passes < params.max_passes; ++st.passes) {
            std::vector<std::tuple<double, Tet, std::size_t>> bad;
            for (std::size_t t = 0; t < tets_.size(); ++t)
                if (alive_[t] && q(t) < target_) bad.emplace_back(q(t), tets_[t], t);
            std::sort(bad.begin(), bad.end());
            std::size_t changed = 0;
            for (const auto& item : bad) {
                const std::size_t t = std::get<2>(item);
                if (!alive_[t] || q(t) >= target_) continue;
                for (int j = 0; j < 4; ++j)
                    if (smooth(tets_[t][j])) ++st.vertices_moved, ++changed;
                if (q(t) >= target_) continue;
                for (int j = 0; j < 4 && alive_[t]; ++j)
                    if (collapse(tets_[t][j], tets_[t])) ++st.vertices_removed, ++changed;
                for (int i = 0; i < 4 && alive_[t]; ++i)
                    for (int j = i + 1; j < 4 && alive_[t]; ++j)
                        if (remove_edge(tets_[t][i], tets_[t][j])) ++st.edges_removed, ++changed;
                for (int j = 0; j < 4 && alive_[t]; ++j)
                    if (flip23(t, j)) ++st.flips_23, ++changed;
                if (alive_[t] && q(t) < target_ && insert_vertex(t)) ++st.vertices_inserted, ++changed;
            }
            if (changed == 0) break;
        }
        // Write back; vertices removed by collapses leave the numbering (M's keep theirs).
        std::vector<std::int32_t> renumber(m_.vertices.size(), -1);
        std::vector<V3> kept(m_.vertices.begin(), m_.vertices.begin() + std::ptrdiff_t(fixed_));
        for (std::size_t v = 0; v < fixed_; ++v) renumber[v] = std::int32_t(v);
        for (std::size_t v = fixed_; v < m_.vertices.size(); ++v)
            if (!star_[v].empty()) {
                renumber[v] = std::int32_t(kept.size());
                kept.push_back(m_.vertices[v]);
            }
        m_.vertices = std::move(kept);
        m_.tets.clear();
        m_.tet_region.clear();
        for (std::size_t t = 0; t < tets_.size(); ++t)
            if (alive_[t]) {
                Tet x = tets_[t];
                for (auto& w : x) w = renumber[std::size_t(w)];
                m_.tets.push_back(x);
                m_.tet_region.push_back(region_[t]);
            }
        return st;
    }

private:
    const V3& P(std::int32_t v) const { return m_.vertices[std::size_t(v)]; }
    double q(std::size_t t) const { return qual_[t]; }
    double quality_of(const Tet& t) const { return quality(P(t[0]), P(t[1]), P(t[2]), P(t[3])); }

    void add(const Tet& t, std::int32_t region)
    {
        const auto id = std::int32_t(tets_.size());
        tets_.push_back(t);
        qual_.push_back(quality_of(t));
        region_.push_back(region);
        alive_.push_back(1);
        for (std::int32_t v : t) star_[std::size_t(v)].push_back(id);
        touch(t);
    }
    /// A vertex's version changes whenever its star or the position of a vertex of its star
    /// does: smooth() and free_star() depend on nothing else, so an answer computed at the
    /// current version is still the answer (memoised below; a hub vertex next to a finely
    /// sampled patch of M has thousands of tets and is asked for every bad tet around it).
    void touch(const Tet& t)
    {
        for (std::int32_t v : t) ++version_[std::size_t(v)];
    }

    void kill(std::size_t t)
    {
        alive_[t] = 0;
        touch(tets_[t]);
        for (std::int32_t v : tets_[t]) {
            auto& s = star_[std::size_t(v)];
            s.erase(std::find(s.begin(), s.end(), std::int32_t(t)));
        }
    }
    /// Alive tets holding all of \p vs.
    std::vector<std::int32_t> tets_with(std::initializer_list<std::int32_t> vs) const
    {
        std::vector<std::int32_t> out;
        const auto& s = star_[std::size_t(*vs.begin())];
        for (std::int32_t t : s) {
            bool all = true;
            for (std::int32_t v : vs) all &= std::find(tets_[t].begin(), tets_[t].end(), v) != tets_[t].end();
            if (all) out.push_back(t);
        }
        return out;
    }

    /// A vertex is free when it is not M's, its star is closed (every triangle (v, x, y) in two
    /// of its tets: not on the mesh's outer boundary) and all of one region (not on M).
    bool free_star(std::int32_t v) const
    {
        if (std::size_t(v) < fixed_) return false;
        const std::size_t i = std::size_t(v);
        if (free_at_[i] != version_[i] + 1) {
            free_[i] = compute_free_star(v);
            free_at_[i] = version_[i] + 1;
        }
        return free_[i];
    }
    bool compute_free_star(std::int32_t v) const
    {
        const auto& s = star_[std::size_t(v)];
        if (s.size() < 4) return false;
        std::vector<std::pair<std::int32_t, std::int32_t>> link;
        for (std::int32_t t : s) {
            if (region_[t] != region_[s.front()]) return false;
            std::int32_t o[3], n = 0;
            for (std::int32_t w : tets_[t])
                if (w != v) o[n++] = w;
            for (int i = 0; i < 3; ++i) link.push_back(std::minmax(o[i], o[(i + 1) % 3]));
        }
        std::sort(link.begin(), link.end());
        for (std::size_t i = 0; i < link.size(); i += 2)
            if (i + 1 >= link.size() || link[i] != link[i + 1] || (i + 2 < link.size() && link[i + 2] == link[i])) return false;
        return true;
    }

    /// Vertex smoothing: \p v moves when it is free (not M's, star closed, one region) and a
    /// candidate position raises its star's worst angle.
    bool smooth(std::int32_t v)
    {
        if (smooth_failed_[std::size_t(v)] == version_[std::size_t(v)] + 1) return false; // nothing changed since
        if (!try_smooth(v)) {
            smooth_failed_[std::size_t(v)] = version_[std::size_t(v)] + 1;
            return false;
        }
        return true;
    }
    bool try_smooth(std::int32_t v)
    {
        // A hub (a grid point next to a finely sampled patch of M: up to thousands of tets)
        // is not moved: one attempt costs O(star), it is asked again after every change
        // around it, and raising the worst of so many tets by moving one point almost never
        // succeeds.
        if (star_[std::size_t(v)].size() > kMaxSmoothStar) return false;
        if (!free_star(v)) return false;
        const auto& s = star_[std::size_t(v)];
        std::vector<std::pair<std::int32_t, std::int32_t>> link;
        for (std::int32_t t : s)
            for (int i = 0; i < 4; ++i)
                if (tets_[t][i] != v)
                    for (int j = i + 1; j < 4; ++j)
                        if (tets_[t][j] != v) link.push_back(std::minmax(tets_[t][i], tets_[t][j]));

        // A move must raise the star's worst angle without adding tets below the target.
        auto star_quality = [&](const V3& x, double& worst, int& bad) {
            worst = kBest;
            bad = 0;
            for (std::int32_t t : s) {
                V3 p[4];
                for (int j = 0; j < 4; ++j) p[j] = tets_[t][j] == v ? x : P(tets_[t][j]);
                if (orient(p[0], p[1], p[2], p[3]) <= 0) return false;
                const double a = quality(p[0], p[1], p[2], p[3]);
                worst = std::min(worst, a);
                bad += a < target_;
            }
            return true;
        };
        const V3 x0 = P(v);
        double current;
        int current_bad;
        if (!star_quality(x0, current, current_bad)) return false;
        // Candidates: toward the centroid of the link, and off the face opposite v in the worst
        // tet, to the apex height of a regular tet on that face.
        std::vector<V3> cand;
        V3 c{0, 0, 0};
        std::size_t nl = 0;
        for (const auto& [a, b] : link) {
            for (int k = 0; k < 3; ++k) c[k] += P(a)[k] + P(b)[k];
            nl += 2;
        }
        for (int k = 0; k < 3; ++k) c[k] /= double(nl);
        for (double f : {1.0, 0.5, 0.25})
            cand.push_back({x0[0] + f * (c[0] - x0[0]), x0[1] + f * (c[1] - x0[1]), x0[2] + f * (c[2] - x0[2])});
        std::int32_t worst_t = s.front();
        for (std::int32_t t : s)
            if (q(std::size_t(t)) < q(std::size_t(worst_t))) worst_t = t;
        {
            std::int32_t o[3], n = 0;
            for (std::int32_t w : tets_[worst_t])
                if (w != v) o[n++] = w;
            const V3 fc{(P(o[0])[0] + P(o[1])[0] + P(o[2])[0]) / 3, (P(o[0])[1] + P(o[1])[1] + P(o[2])[1]) / 3,
                        (P(o[0])[2] + P(o[1])[2] + P(o[2])[2]) / 3};
            V3 nrm = cross(sub(P(o[1]), P(o[0])), sub(P(o[2]), P(o[0])));
            const double nn = norm(nrm);
            if (nn > 0) {
                if (dot(nrm, sub(x0, fc)) < 0) nrm = {-nrm[0], -nrm[1], -nrm[2]};
                const double edge = (norm(sub(P(o[1]), P(o[0]))) + norm(sub(P(o[2]), P(o[1]))) + norm(sub(P(o[0]), P(o[2])))) / 3;
                const double h = std::sqrt(2.0 / 3.0) * edge;
                for (double f : {1.0, 0.5}) {
                    const V3 apex{fc[0] + f * h * nrm[0] / nn, fc[1] + f * h * nrm[1] / nn, fc[2] + f * h * nrm[2] / nn};
                    cand.push_back(apex);
                    cand.push_back({0.5 * (apex[0] + x0[0]), 0.5 * (apex[1] + x0[1]), 0.5 * (apex[2] + x0[2])});
                }
            }
        }
        double best = current;
        const V3* best_x = nullptr;
        for (const V3& x : cand) {
            double w;
            int b;
            if (star_quality(x, w, b) && b <= current_bad && w > best + kMargin) {
                best = w;
                best_x = &x;
            }
        }
        if (!best_x) return false;
        m_.vertices[std::size_t(v)] = *best_x;
        for (std::int32_t t : s) {
            qual_[std::size_t(t)] = quality_of(tets_[t]);
            touch(tets_[t]);
        }
        return true;
    }

    /// Edge collapse: the free vertex \p v goes, its star becomes the cone from a neighbour x
    /// over the triangles of v's link that miss x. Valid when every new tet is positively
    /// oriented (x then sees the whole link: the cone fills exactly v's star); done for the
    /// neighbour giving the best worst angle, if that beats the star's. Only the other vertices
    /// of the bad tet \p bad are tried: collapsing onto them is what removes it.
    bool collapse(std::int32_t v, const Tet bad)
    {
        // Hubs stay (see try_smooth): the cone over thousands of link triangles from one
        // neighbour is never better, and each attempt is O(star).
        if (std::size_t(v) < fixed_ || star_[std::size_t(v)].size() > kMaxSmoothStar || !free_star(v)) return false;
        const std::vector<std::int32_t> s = star_[std::size_t(v)];
        double current = kBest;
        for (std::int32_t t : s) current = std::min(current, q(std::size_t(t)));
        std::vector<std::int32_t> nbrs;
        for (std::int32_t w : bad)
            if (w != v) nbrs.push_back(w);
        double best = current + kMargin;
        std::int32_t best_x = -1;
        for (std::int32_t x : nbrs) {
            double worst = kBest;
            bool ok = true;
            for (std::int32_t t : s) {
                Tet n = tets_[t];
                if (std::find(n.begin(), n.end(), x) != n.end()) continue;
                for (auto& w : n)
                    if (w == v) w = x;
                if (orient(P(n[0]), P(n[1]), P(n[2]), P(n[3])) <= 0) {
                    ok = false;
                    break;
                }
                worst = std::min(worst, quality_of(n));
                if (worst <= best) {
                    ok = false;
                    break;
                }
            }
            if (ok && worst > best) {
                best = worst;
                best_x = x;
            }
        }
        if (best_x < 0) return false;
        const std::int32_t region = region_[s.front()];
        std::vector<Tet> fresh;
        for (std::int32_t t : s) {
            Tet n = tets_[t];
            if (std::find(n.begin(), n.end(), best_x) != n.end()) continue;
            for (auto& w : n)
                if (w == v) w = best_x;
            fresh.push_back(n);
        }
        for (std::int32_t t : s) kill(std::size_t(t));
        for (const Tet& n : fresh) add(n, region);
        return true;
    }

    /// 2-3 flip of the face of tet t opposite its vertex j: valid iff segment de pierces the
    /// interior of the face (d and e are on opposite sides of it in a valid mesh; the line de
    /// strictly inside its three edges is the three orientations below agreeing).
    bool flip23(std::size_t t, int j)
    {
        const Tet& T = tets_[t];
        const std::int32_t d = T[j];
        std::int32_t f[3], n = 0;
        for (int i = 0; i < 4; ++i)
            if (i != j) f[n++] = T[i];
        std::int32_t u = -1;
        for (std::int32_t x : tets_with({f[0], f[1], f[2]}))
            if (std::size_t(x) != t) u = x;
        if (u < 0 || region_[u] != region_[t]) return false;
        std::int32_t e = -1;
        for (std::int32_t w : tets_[u])
            if (w != f[0] && w != f[1] && w != f[2]) e = w;
        Tet nt[3] = {{f[0], f[1], d, e}, {f[1], f[2], d, e}, {f[2], f[0], d, e}};
        const int s0 = orient(P(f[0]), P(f[1]), P(d), P(e));
        if (s0 == 0) return false;
        for (auto& x : nt) {
            if (orient(P(x[0]), P(x[1]), P(x[2]), P(x[3])) != s0) return false;
            if (s0 < 0) std::swap(x[2], x[3]);
        }
        return replace({std::int32_t(t), u}, {nt[0], nt[1], nt[2]});
    }

    /// Edge removal (Shewchuk, "Two discrete optimization algorithms for the topological
    /// improvement of tetrahedral meshes"): the n = 3..7 tets of one region around edge (a, b)
    /// are replaced by 2(n - 2) tets, a triangulation of the ring polygon coned to a and to b,
    /// the one with the best worst angle (dynamic programming over the polygon). n = 3 is the
    /// 3-2 flip. Every new tet must be positively oriented in the orientation the move induces
    /// (exact predicate), which makes the new tets fill exactly the old ones.
    bool remove_edge(std::int32_t a, std::int32_t b)
    {
        const auto ring_tets = tets_with({a, b});
        const std::size_t n = ring_tets.size();
        if (n < 3 || n > 7) return false;
        // Ring order: for each tet (a, b, x, y) positively oriented, y follows x.
        std::vector<std::pair<std::int32_t, std::int32_t>> next;
        for (std::int32_t t : ring_tets) {
            if (region_[t] != region_[ring_tets[0]]) return false;
            std::int32_t o[2], m = 0;
            for (std::int32_t w : tets_[t])
                if (w != a && w != b) o[m++] = w;
            if (orient(P(a), P(b), P(o[0]), P(o[1])) < 0) std::swap(o[0], o[1]);
            next.emplace_back(o[0], o[1]);
        }
        std::sort(next.begin(), next.end());
        std::vector<std::int32_t> r{next[0].first};
        while (r.size() <= n) {
            const auto it = std::lower_bound(next.begin(), next.end(), std::make_pair(r.back(), std::int32_t(-1)));
            if (it == next.end() || it->first != r.back()) return false; // open ring (boundary)
            if (it->second == r.front()) break;
            r.push_back(it->second);
        }
        if (r.size() != n) return false;
        double old_q = kBest;
        for (std::int32_t t : ring_tets) old_q = std::min(old_q, q(std::size_t(t)));
        // Triangle (i, j, k), i < j < k in ring order: tets (ri, rj, rk, b) and (ri, rk, rj, a).
        auto tri_q = [&](std::size_t i, std::size_t j, std::size_t k) {
            const V3 &pi = P(r[i]), &pj = P(r[j]), &pk = P(r[k]);
            if (orient(pi, pj, pk, P(b)) <= 0 || orient(pi, pk, pj, P(a)) <= 0) return kInvalid;
            return std::min(quality(pi, pj, pk, P(b)), quality(pi, pk, pj, P(a)));
        };
        double best[7][7];
        int split[7][7];
        for (std::size_t len = 1; len < n; ++len)
            for (std::size_t i = 0; i + len < n; ++i) {
                const std::size_t j = i + len;
                if (len == 1) {
                    best[i][j] = kBest;
                    continue;
                }
                best[i][j] = kInvalid;
                split[i][j] = -1;
                for (std::size_t k = i + 1; k < j; ++k) {
                    const double v = std::min({best[i][k], best[k][j], tri_q(i, k, j)});
                    if (v > best[i][j]) {
                        best[i][j] = v;
                        split[i][j] = int(k);
                    }
                }
            }
        if (!(best[0][n - 1] > old_q + kMargin)) return false;
        std::vector<Tet> fresh;
        std::vector<std::pair<std::size_t, std::size_t>> todo{{0, n - 1}};
        while (!todo.empty()) {
            const auto [i, j] = todo.back();
            todo.pop_back();
            if (j - i < 2) continue;
            const auto k = std::size_t(split[i][j]);
            fresh.push_back({r[i], r[k], r[j], b});
            fresh.push_back({r[i], r[j], r[k], a});
            todo.push_back({i, k});
            todo.push_back({k, j});
        }
        return replace(ring_tets, fresh);
    }

    /// Vertex insertion (Klingner & Shewchuk's "smoothing-based vertex insertion", simplified):
    /// what is left after the moves above is mostly a sliver between two triangles of M or with
    /// a thin triangle of M as a face, which no move of the other vertices or flip can fix, since
    /// M's vertices and triangles stay. A new vertex x goes into the region next to the bad tet
    /// t: the cavity starts as {t} and takes the tet across each face x does not see strictly
    /// from inside (same region only: M's triangles and the outer boundary stay faces), up to
    /// kMaxCavity tets; then every cavity face coned to x is positively oriented, so the cone
    /// fills the cavity exactly. Candidates: above each face of t, on t's side, at 0.3, 0.6 and
    /// 1 times the apex height of a regular tet on it; the best one is kept if it raises the
    /// cavity's worst angle.
    bool insert_vertex(std::size_t t)
    {
        const Tet T = tets_[t];
        const std::int32_t region = region_[t];
        std::vector<V3> cand;
        for (int j = 0; j < 4; ++j) {
            const V3 &a = P(T[(j + 1) & 3]), &b = P(T[(j + 2) & 3]), &c = P(T[(j + 3) & 3]);
            const V3 fc{(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3, (a[2] + b[2] + c[2]) / 3};
            V3 nrm = cross(sub(b, a), sub(c, a));
            const double nn = norm(nrm);
            if (!(nn > 0)) continue;
            if (dot(nrm, sub(P(T[j]), fc)) < 0) nrm = {-nrm[0], -nrm[1], -nrm[2]};
            const double edge = (norm(sub(b, a)) + norm(sub(c, b)) + norm(sub(a, c))) / 3;
            const double h = std::sqrt(2.0 / 3.0) * edge / nn;
            for (double f : {0.3, 0.6, 1.0}) cand.push_back({fc[0] + f * h * nrm[0], fc[1] + f * h * nrm[1], fc[2] + f * h * nrm[2]});
        }
        std::vector<std::int32_t> best_cavity;
        std::vector<Tet> best_cone;
        double best = q(t);
        std::size_t best_i = cand.size();
        for (std::size_t i = 0; i < cand.size(); ++i) {
            std::vector<std::int32_t> cavity;
            std::vector<Tet> cone;
            if (!cavity_for(t, region, cand[i], cavity, cone)) continue;
            double old_q = kBest, new_q = kBest;
            for (std::int32_t c : cavity) old_q = std::min(old_q, q(std::size_t(c)));
            for (const Tet& x : cone) new_q = std::min(new_q, quality(x[0] < 0 ? cand[i] : P(x[0]), P(x[1]), P(x[2]), P(x[3])));
            if (new_q > old_q + kMargin && new_q > best + kMargin) {
                best = new_q;
                best_i = i;
                best_cavity = std::move(cavity);
                best_cone = std::move(cone);
            }
        }
        if (best_i == cand.size()) return false;
        const auto v = std::int32_t(m_.vertices.size());
        m_.vertices.push_back(cand[best_i]);
        star_.emplace_back();
        for (auto* memo : {&version_, &smooth_failed_, &free_at_}) memo->push_back(0);
        free_.push_back(0);
        for (Tet& x : best_cone) x[0] = v;
        if (replace(best_cavity, best_cone)) return true;
        m_.vertices.pop_back(); // the volume check refused the cone: no vertex without tets
        star_.pop_back();
        for (auto* memo : {&version_, &smooth_failed_, &free_at_}) memo->pop_back();
        free_.pop_back();
        return false;
    }

    /// Grows the cavity of point \p x from tet \p t (see insert_vertex). On success \p cone
    /// holds one tet per cavity face, x written as vertex -1 in slot 0, positively oriented.
    bool cavity_for(std::size_t t, std::int32_t region, const V3& x, std::vector<std::int32_t>& cavity,
                    std::vector<Tet>& cone) const
    {
        constexpr std::size_t kMaxCavity = 24;
        const auto in_cavity = [&](std::int32_t u) { return std::find(cavity.begin(), cavity.end(), u) != cavity.end(); };
        // Tet C with x in place of C[j], rotated by an even permutation so x is in slot 0: it is
        // positively oriented iff x is strictly on C[j]'s side of the face.
        const auto coned = [&](const Tet& C, int j) {
            static constexpr int kEven[4][4] = {{0, 1, 2, 3}, {1, 0, 3, 2}, {2, 3, 0, 1}, {3, 2, 1, 0}};
            Tet n = C;
            n[j] = -1;
            return Tet{n[kEven[j][0]], n[kEven[j][1]], n[kEven[j][2]], n[kEven[j][3]]};
        };
        const auto sees = [&](const Tet& n) { return orient(x, P(n[1]), P(n[2]), P(n[3])) > 0; };
        cavity.assign(1, std::int32_t(t));
        // Faces are checked once: a face x sees stays seen, one it does not see makes the cavity
        // take the tet across. Which faces end on the cavity's boundary is settled at the end.
        std::vector<std::pair<std::int32_t, int>> queue;
        for (int j = 0; j < 4; ++j) queue.emplace_back(std::int32_t(t), j);
        while (!queue.empty()) {
            const auto [c, j] = queue.back();
            queue.pop_back();
            const std::int32_t across = neighbour(c, j);
            if (across >= 0 && in_cavity(across)) continue;
            if (sees(coned(tets_[c], j))) continue;
            if (across < 0 || region_[across] != region || cavity.size() >= kMaxCavity) return false;
            cavity.push_back(across);
            for (int k = 0; k < 4; ++k) queue.emplace_back(across, k);
        }
        cone.clear();
        for (std::int32_t c : cavity)
            for (int j = 0; j < 4; ++j) {
                const std::int32_t across = neighbour(c, j);
                if (across >= 0 && in_cavity(across)) continue;
                cone.push_back(coned(tets_[c], j));
                if (!sees(cone.back())) return false;
            }
        return true;
    }

    /// The alive tet sharing tet c's face opposite its vertex j, or -1.
    std::int32_t neighbour(std::int32_t c, int j) const
    {
        const Tet& C = tets_[c];
        std::int32_t f[3] = {C[(j + 1) & 3], C[(j + 2) & 3], C[(j + 3) & 3]};
        std::sort(f, f + 3, [&](std::int32_t a, std::int32_t b) { return star_[std::size_t(a)].size() < star_[std::size_t(b)].size(); });
        for (std::int32_t u : star_[std::size_t(f[0])]) {
            if (u == c) continue;
            const Tet& U = tets_[u];
            if (std::find(U.begin(), U.end(), f[1]) != U.end() && std::find(U.begin(), U.end(), f[2]) != U.end()) return u;
        }
        return -1;
    }

    /// Replaces \p old by \p fresh when they fill the same volume and the worst angle grows.
    bool replace(const std::vector<std::int32_t>& old, const std::vector<Tet>& fresh)
    {
        double vo = 0, vn = 0, qo = kBest, qn = kBest;
        for (std::int32_t t : old) {
            const Tet& x = tets_[t];
            vo += signed_tet_volume(P(x[0]), P(x[1]), P(x[2]), P(x[3]));
            qo = std::min(qo, q(std::size_t(t)));
        }
        for (const Tet& x : fresh) {
            vn += signed_tet_volume(P(x[0]), P(x[1]), P(x[2]), P(x[3]));
            qn = std::min(qn, quality_of(x));
        }
        if (!same_volume(vo, vn) || qn <= qo + kMargin) return false;
        const std::int32_t region = region_[old.front()];
        for (std::int32_t t : old) kill(std::size_t(t));
        for (const Tet& x : fresh) add(x, region);
        return true;
    }

    TetMesh& m_;
    std::size_t fixed_;
    double target_;
    std::vector<Tet> tets_;
    std::vector<double> qual_; ///< quality() of each tet, kept current
    std::vector<std::int32_t> region_;
    std::vector<char> alive_;
    std::vector<std::vector<std::int32_t>> star_;
    // Per vertex: version (touch()), the version + 1 at which smooth() last failed and at which
    // free_star() was computed (0: never), and that free_star() value.
    std::vector<std::uint32_t> version_;
    std::vector<std::uint32_t> smooth_failed_;
    mutable std::vector<std::uint32_t> free_at_;
    mutable std::vector<char> free_;
};

} // namespace

double min_dihedral_deg(const V3& a, const V3& b, const V3& c, const V3& d) { return degrees(quality(a, b, c, d)); }

TetImprovementStats improve_tets(TetMesh& mesh, std::size_t surface_vertices, const TetImprovementParams& params)
{
    return Improver(mesh, surface_vertices, params.target_deg).run(params);
}

} // namespace isodel::mesher
