#include "volume/tet_improvement.h"

#include "volume/tet_improver.h"

#include <limits>
#include <tuple>

namespace isodel::mesher {
namespace tet_improver {

TetImprovementStats Improver::run(const TetImprovementParams& params, std::vector<std::int32_t>* renumbered)
{
    TetImprovementStats st;
    double worst = kBest;
    for (const Tet& t : tets_)
        worst = std::min(worst, smallest_angle_quality(P(t[0]), P(t[1]), P(t[2]), P(t[3])));
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
    if (renumbered) *renumbered = std::move(renumber);
    return st;
}

bool Improver::try_smooth(std::int32_t v)
{
    // A hub (a grid point next to a finely sampled patch of M: up to thousands of tets)
    // is not moved: one attempt costs O(star), it is asked again after every change
    // around it, and raising the worst of so many tets by moving one point almost never
    // succeeds.
    if (star_[std::size_t(v)].size() > kMaxSmoothStar) return false;
    if (!free_star(v)) return false;
    // The star, worst tets first: star_quality() then rejects a losing position early.
    std::vector<std::int32_t> s = star_[std::size_t(v)];
    std::sort(s.begin(), s.end(), [&](std::int32_t a, std::int32_t b) {
        return std::make_pair(q(std::size_t(a)), a) < std::make_pair(q(std::size_t(b)), b);
    });
    std::vector<std::pair<std::int32_t, std::int32_t>> link;
    for (std::int32_t t : s)
        for (int i = 0; i < 4; ++i)
            if (tets_[t][i] != v)
                for (int j = i + 1; j < 4; ++j)
                    if (tets_[t][j] != v) link.push_back(std::minmax(tets_[t][i], tets_[t][j]));

    const V3 x0 = P(v);
    double current;
    int current_bad;
    if (!star_quality(v, s, x0, -kBest, current, current_bad)) return false;
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
    V3 best_x = x0;
    for (const V3& x : cand) {
        double w;
        int b;
        if (star_quality(v, s, x, best + kMargin, w, b) && b <= current_bad) {
            best = w;
            best_x = x;
        }
    }
    // Then climb: the star's worst quality is the minimum of smooth functions of v's position
    // (one per tet), so from the best candidate step along the steepest ascent direction of the
    // tets that attain it (Freitag & Ollivier-Gooch's non-smooth optimisation, as Klingner &
    // Shewchuk smooth).
    ascend_star(v, s, best_x, best, current_bad);
    if (!(best > current + kMargin)) return false;
    m_.vertices[std::size_t(v)] = best_x;
    ++moved_[std::size_t(v)];
    for (std::int32_t t : s) {
        qual_[std::size_t(t)] = quality_of(tets_[t]);
        touch(tets_[t]);
    }
    return true;
}

bool Improver::star_quality(std::int32_t v, const std::vector<std::int32_t>& s, const V3& x, double beat, double& worst,
                            int& bad) const
{
    worst = kBest;
    bad = 0;
    // Qualities first: most trial positions lose to \p beat on some tet, and then the exact
    // orientation predicates need not run.
    for (std::int32_t t : s) {
        V3 p[4];
        for (int j = 0; j < 4; ++j) p[j] = tets_[t][j] == v ? x : P(tets_[t][j]);
        const double a = quality(p[0], p[1], p[2], p[3]);
        if (a <= beat) return false;
        worst = std::min(worst, a);
        bad += a < target_;
    }
    for (std::int32_t t : s) {
        V3 p[4];
        for (int j = 0; j < 4; ++j) p[j] = tets_[t][j] == v ? x : P(tets_[t][j]);
        if (orient(p[0], p[1], p[2], p[3]) <= 0) return false;
    }
    return true;
}

void Improver::ascend_star(std::int32_t v, const std::vector<std::int32_t>& s, V3& x, double& worst, int max_bad) const
{
    double shortest = std::numeric_limits<double>::infinity();
    for (std::int32_t t : s)
        for (std::int32_t w : tets_[t])
            if (w != v) shortest = std::min(shortest, norm(sub(P(w), x)));
    if (!(shortest > 0) || !std::isfinite(shortest)) return;
    const double h = 1e-7 * shortest;          // finite-difference step
    double step = 0.1 * shortest;              // first trial step; grows after a success
    constexpr double kActive = 1e-4;           // tets this close to the worst are active
    std::vector<V3> grads;
    for (int it = 0; it < kMaxAscentSteps && step > 1e-4 * shortest; ++it) {
        // Gradients of the active tets' qualities with respect to x (central differences).
        grads.clear();
        for (std::int32_t t : s) {
            V3 p[4];
            int k = 0;
            for (int j = 0; j < 4; ++j) {
                p[j] = P(tets_[t][j]);
                if (tets_[t][j] == v) k = j;
            }
            p[k] = x;
            if (quality(p[0], p[1], p[2], p[3]) > worst + kActive) continue;
            V3 g;
            for (int c = 0; c < 3; ++c) {
                p[k][c] = x[c] + h;
                const double up = quality(p[0], p[1], p[2], p[3]);
                p[k][c] = x[c] - h;
                const double down = quality(p[0], p[1], p[2], p[3]);
                p[k][c] = x[c];
                g[c] = (up - down) / (2 * h);
            }
            grads.push_back(g);
        }
        if (grads.empty()) return;
        // Steepest ascent of the minimum: the point of the active gradients' convex hull
        // nearest the origin (Gilbert's algorithm, a few rounds).
        V3 d = grads.front();
        for (int round = 0; round < 16; ++round) {
            const V3* far = &grads.front();
            for (const V3& g : grads)
                if (dot(g, d) < dot(*far, d)) far = &g;
            const V3 e = sub(*far, d);
            const double ee = dot(e, e);
            if (!(ee > 0) || dot(*far, d) >= dot(d, d) * (1 - 1e-9)) break;
            const double lambda = std::clamp(-dot(d, e) / ee, 0.0, 1.0);
            d = {d[0] + lambda * e[0], d[1] + lambda * e[1], d[2] + lambda * e[2]};
        }
        const double dn = norm(d);
        if (!(dn > 0)) return; // stationary: no direction raises every active tet
        bool moved = false;
        for (double a = step; a > 1e-4 * shortest; a *= 0.5) {
            const V3 y{x[0] + a * d[0] / dn, x[1] + a * d[1] / dn, x[2] + a * d[2] / dn};
            double w;
            int b;
            if (star_quality(v, s, y, worst + kMargin, w, b) && b <= max_bad) {
                x = y;
                worst = w;
                step = 2 * a;
                moved = true;
                break;
            }
        }
        if (!moved) return;
    }
}

bool Improver::collapse(std::int32_t v, const Tet bad)
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

} // namespace tet_improver

double min_dihedral_deg(const tet_improver::V3& a, const tet_improver::V3& b, const tet_improver::V3& c,
                        const tet_improver::V3& d)
{
    return tet_improver::degrees(tet_improver::smallest_angle_quality(a, b, c, d));
}

} // namespace isodel::mesher
