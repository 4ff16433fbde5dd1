#pragma once
// Internal: the tetrahedron improver of tet_improvement.h: the tets with their qualities,
// regions and vertex stars, and the local moves on them. Its members are defined in
// tet_improvement.cpp (the sweeps over the bad tets, smoothing, collapses), tet_flips.cpp (2-3
// flips, edge removal) and tet_vertex_insertion.cpp (vertex insertion).
#include "volume/tet_improvement.h"
#include "volume/tet_quality.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <unordered_map>
#include <vector>

namespace isodel::mesher::tet_improver {

using V3 = std::array<double, 3>;
using Tet = std::array<std::int32_t, 4>;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;

inline V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline V3 cross(const V3& a, const V3& b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
inline double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline double norm(const V3& a) { return std::sqrt(dot(a, a)); }
/// p + t d
inline V3 along(const V3& p, const V3& d, double t) { return {p[0] + t * d[0], p[1] + t * d[1], p[2] + t * d[2]}; }
inline constexpr double kPi = 3.14159265358979323846;

/// Exact sign of the orientation of (a, b, c, d) (EPICK's filtered predicate on the doubles).
inline int orient(const V3& a, const V3& b, const V3& c, const V3& d)
{
    auto P = [](const V3& p) { return K::Point_3(p[0], p[1], p[2]); };
    return int(CGAL::orientation(P(a), P(b), P(c), P(d)));
}


/// The dot products of the faces' unit normals, smallest and largest: minus the cosines of the
/// smallest and the largest of the six dihedral angles. The dihedral angle at edge (i, j) is the
/// angle between the faces opposite k and l, the other two vertices: cos = -n_k . n_l / |n_k|
/// |n_l| for the faces' outward (or all inward) normals. Four cross products instead of the
/// twelve of two normals per edge: this is the improvement's innermost function (every trial
/// position of a smoothing evaluates it on the whole star). false for a flat tet.
inline bool normal_dots(const V3& a, const V3& b, const V3& c, const V3& d, double& lowest, double& highest)
{
    const V3 ab = sub(b, a), ac = sub(c, a), ad = sub(d, a), bc = sub(c, b), bd = sub(d, b);
    // All inward when det(ab, ac, ad) > 0, all outward otherwise: the cosines are the same.
    V3 n[4] = {cross(bd, bc), cross(ac, ad), cross(ad, ab), cross(ab, ac)};
    for (V3& v : n) {
        const double len = norm(v);
        if (!(len > 0)) return false;
        v = {v[0] / len, v[1] / len, v[2] / len};
    }
    const double dots[6] = {dot(n[0], n[1]), dot(n[0], n[2]), dot(n[0], n[3]),
                            dot(n[1], n[2]), dot(n[1], n[3]), dot(n[2], n[3])};
    lowest = *std::min_element(dots, dots + 6);
    highest = *std::max_element(dots, dots + 6);
    return true;
}

/// Tet quality inside the improver: -cos of the smaller of the smallest dihedral angle and 180
/// degrees minus the largest, so that a tet is bad when an angle is near 0 or near 180 (a cap's
/// smallest angle can be fair while its largest is near flat, and a solver's conditioning
/// suffers from both); no acos in the inner loops; -1 for a flat tet.
inline double quality(const V3& a, const V3& b, const V3& c, const V3& d)
{
    double lowest = 0, highest = 0;
    if (!normal_dots(a, b, c, d, lowest, highest)) return -1;
    return std::max(std::min(lowest, -highest), -1.0);
}
/// -cos of the smallest dihedral angle alone (what the statistics report).
inline double smallest_angle_quality(const V3& a, const V3& b, const V3& c, const V3& d)
{
    double lowest = 0, highest = 0;
    if (!normal_dots(a, b, c, d, lowest, highest)) return -1;
    return std::max(lowest, -1.0);
}
inline double degrees(double q) { return std::acos(std::clamp(-q, -1.0, 1.0)) * 180.0 / kPi; }
inline constexpr double kBest = 2;     ///< above every quality
inline constexpr double kInvalid = -3; ///< below every quality: an inverted tet
inline constexpr double kMargin = 1e-12; ///< an improvement must beat the old quality by this much
inline constexpr int kMaxAscentSteps = 30; ///< bound on the hill-climbing steps of one smoothing (Improver::ascend_star)
inline constexpr std::size_t kMaxSmoothStar = 256; ///< larger stars are not smoothed or collapsed (Improver::try_smooth)

/// A flip may only replace tets by tets filling the same polytope. The orientation predicates
/// decide that exactly; equal volumes are a second, floating-point, sanity check.
inline bool same_volume(double before, double after) { return std::abs(before - after) <= 1e-9 * std::abs(before); }

class Improver {
public:
    Improver(TetMesh& m, std::size_t surface_vertices, double target_deg)
        : m_(m), fixed_(surface_vertices), target_(-std::cos(target_deg * kPi / 180.0)), star_(m.vertices.size()),
          version_(m.vertices.size(), 0), smooth_failed_(m.vertices.size(), 0), moved_(m.vertices.size(), 0), free_at_(m.vertices.size(), 0),
          free_(m.vertices.size(), 0)
    {
        for (std::size_t t = 0; t < m.tets.size(); ++t) add(m.tets[t], m.tet_region[t]);
    }

    /// Improves the tets, then writes them back into the mesh given to the constructor, its
    /// vertices compacted: \p renumbered (if given) gets each vertex's new index, -1 if removed.
    TetImprovementStats run(const TetImprovementParams& params, std::vector<std::int32_t>* renumbered = nullptr);

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
        adj_.push_back({-2, -2, -2, -2});
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
    bool try_smooth(std::int32_t v);

    /// The worst quality and the number of tets below the target of \p v's star \p s with v
    /// at \p x; false if a tet would not be positively oriented (exact predicate) or its
    /// quality is not above \p beat.
    bool star_quality(std::int32_t v, const std::vector<std::int32_t>& s, const V3& x, double beat, double& worst,
                      int& bad) const;

    /// Hill climbing on the star's worst quality from \p x (whose value is \p worst), along the
    /// steepest ascent direction of the active tets, up to kMaxAscentSteps steps, each kept only if
    /// it raises the worst quality, keeps every tet positive and at most \p max_bad tets bad.
    void ascend_star(std::int32_t v, const std::vector<std::int32_t>& s, V3& x, double& worst, int max_bad) const;

    /// Edge collapse: the free vertex \p v goes, its star becomes the cone from a neighbour x
    /// over the triangles of v's link that miss x. Valid when every new tet is positively
    /// oriented (x then sees the whole link: the cone fills exactly v's star); done for the
    /// neighbour giving the best worst angle, if that beats the star's. Only the other vertices
    /// of the bad tet \p bad are tried: collapsing onto them is what removes it.
    bool collapse(std::int32_t v, const Tet bad);

    /// 2-3 flip of the face of tet t opposite its vertex j: valid iff segment de pierces the
    /// interior of the face (d and e are on opposite sides of it in a valid mesh; the line de
    /// strictly inside its three edges is the three orientations below agreeing).
    bool flip23(std::size_t t, int j);

    /// Edge removal (Shewchuk, "Two discrete optimization algorithms for the topological
    /// improvement of tetrahedral meshes"): the n = 3..7 tets of one region around edge (a, b)
    /// are replaced by 2(n - 2) tets, a triangulation of the ring polygon coned to a and to b,
    /// the one with the best worst angle (dynamic programming over the polygon). n = 3 is the
    /// 3-2 flip. Every new tet must be positively oriented in the orientation the move induces
    /// (exact predicate), which makes the new tets fill exactly the old ones.
    bool remove_edge(std::int32_t a, std::int32_t b);

    /// Vertex insertion (Klingner & Shewchuk's "smoothing-based vertex insertion", simplified):
    /// what is left after the moves above is mostly a sliver between two triangles of M or with
    /// a thin triangle of M as a face, which no move of the other vertices or flip can fix, since
    /// M's vertices and triangles stay. A new vertex x goes into the region next to the bad tet
    /// t: the cavity starts as {t} and takes the tet across each face x does not see strictly
    /// from inside (same region only: M's triangles and the outer boundary stay faces), up to
    /// kMaxCavity tets; then every cavity face coned to x is positively oriented, so the cone
    /// fills the cavity exactly. Candidates: above each face of t, on t's side, at 0.3, 0.6, 1
    /// and 1.5 times the apex height of a regular tet on it, and above the midpoint of each
    /// edge of the face at 0.5 and 0.9 times that edge's length (next to a short edge of M, where
    /// a far vertex makes a thin tet); the best one is kept if it raises the cavity's worst
    /// angle, and the new vertex is then smoothed.
    bool insert_vertex(std::size_t t);

    /// Grows the cavity of point \p x from tet \p t (see insert_vertex). On success \p cone
    /// holds one tet per cavity face, x written as vertex -1 in slot 0, positively oriented.
    /// Either way \p cavity holds the tets it took and \p looked_at gets every tet it found across
    /// a face of theirs it examined (on success, every face).
    bool cavity_for(std::size_t t, std::int32_t region, const V3& x, std::vector<std::int32_t>& cavity,
                    std::vector<Tet>& cone, std::vector<std::int32_t>& looked_at) const;

    /// The alive tet sharing tet c's face opposite its vertex j, or -1. Remembered in adj_: a
    /// tet never changes while alive and an interior face has exactly two tets, so while the
    /// remembered tet is alive it is still the one; a face without one is on the mesh's
    /// boundary, which no move changes (each fills exactly the volume it empties). The vertex
    /// insertion's cavities ask for the same faces many times, and each answer would otherwise
    /// be a scan of a vertex star.
    std::int32_t neighbour(std::int32_t c, int j) const
    {
        std::int32_t& known = adj_[std::size_t(c)][j];
        if (known == -1 || (known >= 0 && alive_[std::size_t(known)])) return known;
        const Tet& C = tets_[c];
        std::int32_t f[3] = {C[(j + 1) & 3], C[(j + 2) & 3], C[(j + 3) & 3]};
        std::sort(f, f + 3, [&](std::int32_t a, std::int32_t b) { return star_[std::size_t(a)].size() < star_[std::size_t(b)].size(); });
        known = -1;
        for (std::int32_t u : star_[std::size_t(f[0])]) {
            if (u == c) continue;
            const Tet& U = tets_[u];
            if (std::find(U.begin(), U.end(), f[1]) != U.end() && std::find(U.begin(), U.end(), f[2]) != U.end()) {
                known = u;
                break;
            }
        }
        return known;
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
    mutable std::vector<std::array<std::int32_t, 4>> adj_; ///< neighbour() per face: -2 not yet known
    std::vector<std::vector<std::int32_t>> star_;
    // Per vertex: version (touch()), the version + 1 at which smooth() last failed and at which
    // free_star() was computed (0: never), and that free_star() value.
    std::vector<std::uint32_t> version_;
    std::vector<std::uint32_t> smooth_failed_;
    /// Per vertex: how many times smoothing moved it.
    std::vector<std::uint32_t> moved_;
    /// What insert_vertex() read where it failed, per tet: the tets it looked at (each cavity
    /// and the tets across the cavities' faces) and the vertices of the cavities with their
    /// moved_ counts. A tet never changes while alive, and a face of two alive tets has no
    /// third, so while those tets are alive and those vertices unmoved, every neighbour() and
    /// orientation the attempt computes is the same (a face without a neighbour is on the
    /// mesh's boundary, which no move changes: each fills exactly the volume it empties) and
    /// it would fail again: it is skipped. The same result, without repeating, pass after pass,
    /// the attempts that cannot succeed.
    struct FailedInsertion {
        std::vector<std::int32_t> tets;
        std::vector<std::pair<std::int32_t, std::uint32_t>> vertices;
    };
    std::unordered_map<std::size_t, FailedInsertion> insert_failed_;
    // insert_vertex()'s "already read" marks: equal to read_stamp_ when read by this attempt.
    std::uint32_t read_stamp_ = 0;
    std::vector<std::uint32_t> tet_read_, vertex_read_;
    // cavity_for()'s membership marks: equal to cavity_stamp_ for the tets of the current cavity.
    mutable std::uint32_t cavity_stamp_ = 0;
    mutable std::vector<std::uint32_t> in_cavity_;
    mutable std::vector<std::pair<std::int32_t, int>> cavity_queue_; ///< cavity_for()'s faces to check

    mutable std::vector<std::uint32_t> free_at_;
    mutable std::vector<char> free_;
};

} // namespace isodel::mesher::tet_improver
