// Tet improvement (tet_improvement.h): the topological moves, 2-3 flips and Shewchuk's edge
// removal, on the Improver's tets (tet_improver.h).
#include "volume/tet_improver.h"

namespace isodel::mesher::tet_improver {

bool Improver::flip23(std::size_t t, int j)
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

bool Improver::remove_edge(std::int32_t a, std::int32_t b)
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

} // namespace isodel::mesher::tet_improver
