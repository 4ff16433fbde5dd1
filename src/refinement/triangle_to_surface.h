#pragma once
// Internal: the M -> Sigma half of the mesher's Hausdorff check (hausdorff_refinement.h): is a
// triangle of M within the bound of Sigma? Newton projections of a few of its points onto Sigma,
// on a triangle split in four where the covering bound needs it (class comment below).
#include "geometry/triangle_corner_reach.h"
#include "octree/cell_function.h"
#include "octree/sample_field.h"
#include "octree/segment_walk.h"

#include <openvdb/math/Mat3.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

// In detail:: because the names (Vec3d, project) are generic; hausdorff_refinement.cpp takes
// TriangleToSurface alone.
namespace isodel::mesher::detail {

using Vec3d = openvdb::Vec3d;

/// The last cell Newton read, with its F': Newton's steps are short and the samples of one
/// triangle lie in a cell or two, so most projections start in the cell the previous one read.
struct LastCell {
    openvdb::Coord cell{std::numeric_limits<int>::min()};
    octree::CellFunction f;
};

/// Newton projection of a world point onto Sigma along the world gradient of phi. Returns false
/// when it does not converge (flat phi): the caller then has no bound from it. On success
/// \p slack is the last step's length (world units): Sigma is within it of \p out, so
/// d(w0, Sigma) <= |out - w0| + slack is a bound.
inline bool project(const octree::SampleField::Reader& reader, LastCell& last, const openvdb::math::Mat3d& to_index,
                    double step_cap, const Vec3d& w0, Vec3d& out, double& slack)
{
    const auto& field = reader.field();
    Vec3d x = field.world_to_index(w0);
    const octree::CellFunction& f = last.f;
    const openvdb::math::Mat3d to_index_t = to_index.transpose();
    for (int it = 0; it < 30; ++it) {
        const openvdb::Coord c(int(std::floor(x[0])), int(std::floor(x[1])), int(std::floor(x[2])));
        if (c != last.cell) {
            last.f = octree::cell_function(reader, c);
            last.cell = c;
        }
        const Vec3d l = x - c.asVec3d();
        const double phi = f(l[0], l[1], l[2]);
        const Vec3d gw = to_index_t * f.gradient(l[0], l[1], l[2]); // world gradient
        const double g2 = gw.lengthSqr();
        if (!(g2 > 0)) return false;
        Vec3d dw = gw * (-phi / g2);
        const double len = dw.length();
        if (len > step_cap) dw *= step_cap / len;
        x += to_index * dw;
        // Converged once a step is this short. Within one cell Newton's error after it is of
        // the order of the curvature times its square; a step across a cell face (F is only C0
        // there) may leave an error as long as the step, so the step's length is the caller's
        // slack. (A tighter tolerance such as 1e-10 would cost one more iteration on nearly
        // every projection, and there are many per triangle; the slack is at most 5e-6 voxel,
        // negligible against eps.)
        if (len < 1e-5 * step_cap) {
            out = field.index_to_world(x);
            slack = len;
            return true;
        }
    }
    return false;
}

/// The crossing of Sigma nearest to s on the segment s -/+ reach along n (Newton's fallback
/// where phi is flat).
inline bool along_normal(const octree::SampleField::Reader& reader, const Vec3d& s, Vec3d n, double reach, Vec3d& out)
{
    const double len = n.length();
    if (!(len > 0)) return false;
    n *= reach / len;
    const auto& field = reader.field();
    const Vec3d a = field.world_to_index(s - n), b = field.world_to_index(s + n);
    const auto sc = octree::segment_crossings(reader, a, b, 256);
    if (sc.overflow || sc.t.empty()) return false;
    double best = sc.t.front();
    for (double t : sc.t)
        if (std::abs(t - 0.5) < std::abs(best - 0.5)) best = t;
    out = field.index_to_world(a + best * (b - a));
    return true;
}

/// M -> Sigma on one triangle, as a bound: d(x, Sigma) <= d(s, Sigma) + |x - s|, and every point
/// of a triangle is within its corner reach r of a corner (geometry::triangle_corner_reach: the
/// circumradius, or half the longest edge L when not acute; r <= L / sqrt(3)). A sub-triangle
/// passes when the largest bound at its corners plus r is at most `pass`; otherwise it is split
/// in four at its edge midpoints, down to edges of `leaf`, where each corner must be within
/// `limit` of Sigma. That is the rule of a barycentric sample grid of spacing `leaf`
/// (pass = limit + leaf / sqrt(3) bounds the same distance) without projecting every grid
/// sample: a triangle lying on Sigma within a few hundredths of eps passes after a dozen Newton
/// projections instead of ~200. Splitting stops after kMaxDepth halvings: a sub-triangle still
/// longer than `leaf` there must pass the covering bound itself, so every pass is certified by
/// pass <= eps whatever the triangle's size.
/// A sample is projected once per triangle: the midpoint of an edge shared by two sub-triangles
/// is reached from both, so projections are remembered by the sample's position on the
/// triangle's finest sample grid (kMaxDepth halvings).
class TriangleToSurface {
public:
    TriangleToSurface(const octree::SampleField::Reader& reader, const openvdb::math::Mat3d& to_index, double step_cap,
                      double limit, double leaf, double reach)
        : reader_(reader), to_index_(to_index), step_cap_(step_cap), limit_(limit), leaf_(leaf),
          pass_(limit + leaf / std::sqrt(3.0)), reach_(reach), memo_(std::size_t(kGrid + 1) * (kGrid + 1))
    {
    }

    /// True when triangle abc is within the bound of Sigma. \p p is a point of Sigma (the
    /// facet's surface point), \p off how far each vertex may be from Sigma. On failure \p at is
    /// a point of Sigma near the offending sample when one was found.
    bool check(const Vec3d& a, const Vec3d& b, const Vec3d& c, const double off[3], const Vec3d& p,
               std::optional<Vec3d>& at)
    {
        p_ = p;
        normal_ = (b - a).cross(c - a);
        at_ = &at;
        if (++stamp_ == 0) { // wrapped: forget every stamp
            for (auto& m : memo_) m.stamp = 0;
            stamp_ = 1;
        }
        Corner A{a, off[0], true, {}, kGrid, 0, a}, B{b, off[1], true, {}, 0, kGrid, b},
            C{c, off[2], true, {}, 0, 0, c};
        const double L = std::max({(b - a).length(), (c - b).length(), (a - c).length()});
        return passes(A, B, C, 0, L, geometry::triangle_corner_reach(a, b, c));
    }

private:
    struct Corner {
        Vec3d s;
        double d;             ///< d(s, Sigma) <= d
        bool exact = false;   ///< d already includes the Newton projection
        std::optional<Vec3d> q; ///< that projection
        int u = 0, v = 0;       ///< barycentric weights of a and b on the finest grid (kGrid)
        Vec3d start;            ///< where Newton starts (a midpoint: between its ends' projections)
    };

    /// A corner's own point of Sigma when it has one: a midpoint's Newton start between the
    /// projections of its ends lies within the chord's sagitta of Sigma, closer than the
    /// midpoint itself, so Newton needs fewer steps; any point of Sigma bounds the distance.
    static const Vec3d& on_sigma(const Corner& x) { return x.q ? *x.q : x.s; }

    /// The projection of one sample of the current triangle (check()'s stamp).
    struct Projected {
        std::uint32_t stamp = 0;
        Vec3d s;                ///< the sample
        std::optional<Vec3d> q; ///< its Newton projection, when it converged
        double slack = 0;       ///< Sigma is within this of q (project())
    };

    void tighten(Corner& x)
    {
        if (x.exact) return;
        x.exact = true;
        Projected& m = memo_[std::size_t(x.u) * (kGrid + 1) + std::size_t(x.v)];
        // The same grid position gives the same sample (midpoints are symmetric in their ends);
        // comparing s keeps that an optimisation, not an assumption.
        if (m.stamp != stamp_ || m.s != x.s) {
            m.stamp = stamp_;
            m.s = x.s;
            Vec3d q;
            m.q.reset();
            if (project(reader_, last_cell_, to_index_, step_cap_, x.start, q, m.slack)) m.q = q;
        }
        if (m.q) {
            x.q = m.q;
            x.d = std::min(x.d, (*m.q - x.s).length() + m.slack);
        }
    }

    /// A point of Sigma near the failing corner x, for the caller to insert instead of p.
    void report(const Corner& x) const
    {
        Vec3d q;
        if (x.q) *at_ = x.q;
        else if (along_normal(reader_, x.s, normal_, reach_, q)) *at_ = q;
    }

    Corner midpoint(const Corner& x, const Corner& y) const
    {
        Corner m{0.5 * (x.s + y.s), 0.0, false, {}, (x.u + y.u) / 2, (x.v + y.v) / 2,
                 0.5 * (on_sigma(x) + on_sigma(y))};
        const double h = 0.5 * (x.s - y.s).length();
        m.d = std::min({x.d + h, y.d + h, (m.s - p_).length()});
        return m;
    }

    /// \p L, \p reach: the longest edge and the corner reach of ABC. The four halves of a
    /// triangle are similar to it with ratio 1/2, so a sub-triangle's are its parent's halved
    /// (halving is exact in floating point) instead of measured again from its rounded
    /// midpoints, which may differ from that in the last bit.
    bool passes(Corner& A, Corner& B, Corner& C, int depth, double L, double reach)
    {
        const auto covered = [&] { return std::max({A.d, B.d, C.d}) + reach <= pass_; };
        if (covered()) return true;
        if (L <= leaf_) {
            for (Corner* x : {&A, &B, &C}) {
                if (x->d <= limit_) continue;
                tighten(*x);
                if (x->d <= limit_) continue;
                report(*x);
                return false;
            }
            return true;
        }
        tighten(A);
        tighten(B);
        tighten(C);
        if (covered()) return true;
        if (depth >= kMaxDepth) {
            // Edges still longer than `leaf` (a triangle over 32 leaves long): corners within
            // `limit` would not bound the points between them, so only the covering bound
            // passes; otherwise the triangle fails and its surface point p is inserted (or a
            // point of Sigma near a corner that is itself too far).
            for (const Corner* x : {&A, &B, &C})
                if (x->d > limit_) {
                    report(*x);
                    break;
                }
            return false;
        }
        Corner ab = midpoint(A, B), bc = midpoint(B, C), ca = midpoint(C, A);
        const double half_L = 0.5 * L, half_reach = 0.5 * reach;
        return passes(A, ab, ca, depth + 1, half_L, half_reach) && passes(ab, B, bc, depth + 1, half_L, half_reach) &&
               passes(ca, bc, C, depth + 1, half_L, half_reach) && passes(ab, bc, ca, depth + 1, half_L, half_reach);
    }

    static constexpr int kMaxDepth = 5; // 32 sub-edges per edge
    static constexpr int kGrid = 1 << kMaxDepth;
    const octree::SampleField::Reader& reader_;
    const openvdb::math::Mat3d& to_index_;
    double step_cap_, limit_, leaf_, pass_, reach_;
    Vec3d p_, normal_;
    std::optional<Vec3d>* at_ = nullptr;
    std::vector<Projected> memo_; ///< by (u, v) of the finest grid
    std::uint32_t stamp_ = 0;
    LastCell last_cell_;
};

} // namespace isodel::mesher::detail
