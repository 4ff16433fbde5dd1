// Tet improvement (tet_improvement.h): vertex insertion next to the slivers no other move
// fixes, on the Improver's tets (tet_improver.h).
#include "volume/tet_improver.h"

namespace isodel::mesher::tet_improver {

bool Improver::insert_vertex(std::size_t t)
{
    if (const auto memo = insert_failed_.find(t); memo != insert_failed_.end()) {
        bool same = true;
        for (std::int32_t u : memo->second.tets) same &= alive_[std::size_t(u)] != 0;
        for (const auto& [w, moves] : memo->second.vertices) same &= moved_[std::size_t(w)] == moves;
        if (same) return false; // nothing it reads has changed since it failed (insert_failed_)
    }
    const Tet T = tets_[t];
    const std::int32_t region = region_[t];
    // What this attempt reads, each tet and vertex once (stamped: sorting the lists cost more
    // than the memo saved). The candidates come from T's vertices, which cavity {t} holds.
    FailedInsertion read;
    ++read_stamp_;
    tet_read_.resize(tets_.size(), 0);
    vertex_read_.resize(m_.vertices.size(), 0);
    const auto read_tet = [&](std::int32_t u) {
        if (tet_read_[std::size_t(u)] != read_stamp_) tet_read_[std::size_t(u)] = read_stamp_, read.tets.push_back(u);
    };
    const auto read_cavity = [&](const std::vector<std::int32_t>& cavity) {
        for (std::int32_t c : cavity) {
            read_tet(c);
            for (std::int32_t w : tets_[c])
                if (vertex_read_[std::size_t(w)] != read_stamp_)
                    vertex_read_[std::size_t(w)] = read_stamp_, read.vertices.emplace_back(w, moved_[std::size_t(w)]);
        }
    };
    read_cavity({std::int32_t(t)});
    std::vector<std::int32_t> looked_at;
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
        for (double f : {0.3, 0.6, 1.0, 1.5}) cand.push_back(along(fc, nrm, f * h));
        // Next to each edge of the face, at a distance of the edge's own length: a needle face
        // (one short edge) makes every tet with a far apex thin, one near the short edge is not.
        for (int e = 0; e < 3; ++e) {
            const V3& u = e == 0 ? a : e == 1 ? b : c;
            const V3& w = e == 0 ? b : e == 1 ? c : a;
            const double len = norm(sub(w, u)) / nn;
            const V3 mid{(u[0] + w[0]) / 2, (u[1] + w[1]) / 2, (u[2] + w[2]) / 2};
            for (double f : {0.5, 0.9}) cand.push_back(along(mid, nrm, f * len));
        }
    }
    std::vector<std::int32_t> best_cavity, cavity;
    std::vector<Tet> best_cone, cone;
    double best = q(t);
    std::size_t best_i = cand.size();
    for (std::size_t i = 0; i < cand.size(); ++i) {
        looked_at.clear();
        const bool ok = cavity_for(t, region, cand[i], cavity, cone, looked_at);
        read_cavity(cavity);
        for (std::int32_t u : looked_at) read_tet(u);
        if (!ok) continue;
        double old_q = kBest;
        for (std::int32_t c : cavity) old_q = std::min(old_q, q(std::size_t(c)));
        // The candidate wins iff its cone's worst quality beats both bars: the cone's tets stop
        // being evaluated at the first one after which it does not (the worst only goes down;
        // std::min passes over a NaN quality either way).
        const auto wins = [&](double worst) { return worst > old_q + kMargin && worst > best + kMargin; };
        double new_q = kBest;
        for (const Tet& x : cone) {
            new_q = std::min(new_q, quality(x[0] < 0 ? cand[i] : P(x[0]), P(x[1]), P(x[2]), P(x[3])));
            if (!wins(new_q)) break;
        }
        if (wins(new_q)) {
            best = new_q;
            best_i = i;
            best_cavity.swap(cavity);
            best_cone.swap(cone);
        }
    }
    const auto failed = [&] {
        insert_failed_[t] = std::move(read);
        return false;
    };
    if (best_i == cand.size()) return failed();
    const auto v = std::int32_t(m_.vertices.size());
    m_.vertices.push_back(cand[best_i]);
    star_.emplace_back();
    for (auto* memo : {&version_, &smooth_failed_, &moved_, &free_at_}) memo->push_back(0);
    free_.push_back(0);
    for (Tet& x : best_cone) x[0] = v;
    if (replace(best_cavity, best_cone)) {
        smooth(v); // the cone's vertex is free: settle it where its star is best
        return true;
    }
    m_.vertices.pop_back(); // the volume check refused the cone: no vertex without tets
    star_.pop_back();
    for (auto* memo : {&version_, &smooth_failed_, &moved_, &free_at_}) memo->pop_back();
    free_.pop_back();
    return failed();
}

bool Improver::cavity_for(std::size_t t, std::int32_t region, const V3& x, std::vector<std::int32_t>& cavity,
                          std::vector<Tet>& cone, std::vector<std::int32_t>& looked_at) const
{
    constexpr std::size_t kMaxCavity = 64;
    // Cavity membership by stamp: a linear search of the cavity per face would make the growth
    // quadratic in the cavity, on the improvement's innermost path.
    if (++cavity_stamp_ == 0) { // wrapped: forget every old mark
        std::fill(in_cavity_.begin(), in_cavity_.end(), 0);
        cavity_stamp_ = 1;
    }
    in_cavity_.resize(tets_.size(), 0);
    const auto take = [&](std::int32_t u) {
        cavity.push_back(u);
        in_cavity_[std::size_t(u)] = cavity_stamp_;
    };
    const auto in_cavity = [&](std::int32_t u) { return in_cavity_[std::size_t(u)] == cavity_stamp_; };
    // Tet C with x in place of C[j], rotated by an even permutation so x is in slot 0: it is
    // positively oriented iff x is strictly on C[j]'s side of the face.
    const auto coned = [&](const Tet& C, int j) {
        static constexpr int kEven[4][4] = {{0, 1, 2, 3}, {1, 0, 3, 2}, {2, 3, 0, 1}, {3, 2, 1, 0}};
        Tet n = C;
        n[j] = -1;
        return Tet{n[kEven[j][0]], n[kEven[j][1]], n[kEven[j][2]], n[kEven[j][3]]};
    };
    const auto sees = [&](const Tet& n) { return orient(x, P(n[1]), P(n[2]), P(n[3])) > 0; };
    cavity.clear();
    take(std::int32_t(t));
    // Faces are checked once: a face x sees stays seen, one it does not see makes the cavity
    // take the tet across. Every face of every cavity tet is checked here, and the cavity only
    // grows, so each face left on the cavity's boundary at the end is one x sees: the cone
    // over it is positively oriented, and the tet across it is already in looked_at.
    auto& queue = cavity_queue_;
    queue.clear();
    for (int j = 0; j < 4; ++j) queue.emplace_back(std::int32_t(t), j);
    while (!queue.empty()) {
        const auto [c, j] = queue.back();
        queue.pop_back();
        const std::int32_t across = neighbour(c, j);
        if (across >= 0) looked_at.push_back(across);
        if (across >= 0 && in_cavity(across)) continue;
        if (sees(coned(tets_[c], j))) continue;
        if (across < 0 || region_[across] != region || cavity.size() >= kMaxCavity) return false;
        take(across);
        for (int k = 0; k < 4; ++k) queue.emplace_back(across, k);
    }
    cone.clear();
    for (std::int32_t c : cavity)
        for (int j = 0; j < 4; ++j) {
            const std::int32_t across = neighbour(c, j);
            if (across >= 0 && in_cavity(across)) continue;
            cone.push_back(coned(tets_[c], j));
            CGAL_assertion(sees(cone.back()));
        }
    return true;
}

} // namespace isodel::mesher::tet_improver
