#include "octree/segment_walk.h"

#include "octree/box_sign.h"
#include "octree/cell_function.h"

#include "octree/cell_interpolant.h"
#include "octree/face_slabs.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace isodel::octree {
namespace {

/// floor(x) as a cell index. Points beyond the int range (a far circumcentre of a flat tet) and
/// NaN map to the lowest index: a cell far outside every domain, where phi is the constant
/// outside value (sample_field.h), which is what the query needs; converting them directly
/// would be undefined behaviour.
int cell_index(double x)
{
    const double f = std::floor(x);
    constexpr double lo = double(std::numeric_limits<int>::min()), hi = double(std::numeric_limits<int>::max());
    return f >= lo && f <= hi ? int(f) : std::numeric_limits<int>::min();
}

Coord cell_of(const Vec3d& p) { return Coord(cell_index(p[0]), cell_index(p[1]), cell_index(p[2])); }

/// Real roots of q(t) = c0 + c1 t + c2 t^2 in (lo, hi), sorted.
int quadratic_roots_in(double c0, double c1, double c2, double lo, double hi, double out[2])
{
    int n = 0;
    double r[2];
    const double scale = std::max({std::abs(c0), std::abs(c1), std::abs(c2)});
    if (scale == 0) return 0;
    if (std::abs(c2) <= 1e-14 * scale) {
        if (c1 != 0) r[n++] = -c0 / c1;
    } else {
        const double disc = c1 * c1 - 4 * c2 * c0;
        if (disc >= 0) {
            // Numerically stable form (no cancellation).
            const double s = std::sqrt(disc);
            const double qq = -0.5 * (c1 + (c1 >= 0 ? s : -s));
            if (qq != 0) {
                r[n++] = qq / c2;
                r[n++] = c0 / qq;
            } else {
                r[n++] = 0;
            }
        }
    }
    int m = 0;
    for (int i = 0; i < n; ++i)
        if (r[i] > lo && r[i] < hi) out[m++] = r[i];
    if (m == 2 && out[0] > out[1]) std::swap(out[0], out[1]);
    return m;
}

inline bool inside(double v) { return v >= 0; }

/// Bisection of a monotone cubic piece with a sign change on [lo, hi].
double bisect(const Cubic& q, double lo, double hi, bool lo_inside)
{
    for (int it = 0; it < 100 && hi - lo > 0; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        if (inside(q(mid)) == lo_inside) lo = mid;
        else hi = mid;
    }
    return 0.5 * (lo + hi);
}

} // namespace

double phi_at(const SampleField::Reader& reader, const Vec3d& p)
{
    const Coord c = cell_of(p);
    return cell_function(reader, c)(p[0] - c[0], p[1] - c[1], p[2] - c[2]);
}

SegmentCrossings segment_crossings(const SampleField::Reader& reader, const Vec3d& a,
                                   const Vec3d& b, int max_cells)
{
    SegmentCrossings out;
    const Vec3d d = b - a;
    // Cell boundary parameters along each axis (3D DDA).
    Coord cell = cell_of(a);
    const Coord last = cell_of(b);
    int step[3];
    double t_next[3], t_delta[3];
    for (int k = 0; k < 3; ++k) {
        if (d[k] > 0) {
            step[k] = 1;
            t_next[k] = (cell[k] + 1 - a[k]) / d[k];
            t_delta[k] = 1.0 / d[k];
        } else if (d[k] < 0) {
            step[k] = -1;
            t_next[k] = (cell[k] - a[k]) / d[k];
            t_delta[k] = -1.0 / d[k];
        } else {
            step[k] = 0;
            t_next[k] = t_delta[k] = INFINITY;
        }
    }
    double t0 = 0.0;
    double v0 = 0.0;
    bool have_v0 = false;
    for (;;) {
        if (++out.cells_visited > max_cells) {
            out.overflow = true;
            out.t.clear();
            return out;
        }
        const bool is_last = (cell == last);
        int axis = 0;
        if (t_next[1] < t_next[axis]) axis = 1;
        if (t_next[2] < t_next[axis]) axis = 2;
        const double t1 = is_last ? 1.0 : std::min(1.0, t_next[axis]);

        double corner[8];
        const CellFunction cf = cell_function(reader, cell, corner);
        const FaceSlabs& slabs = cf.slabs();
        const Vec3d a_local = a - Vec3d(cell[0], cell[1], cell[2]);
        if (!have_v0) {
            v0 = cf(a_local[0], a_local[1], a_local[2]);
            out.inside_at_start = inside(v0);
            have_v0 = true;
        }
        // Where F' has v0's sign on the whole bounding box of the segment's part in this cell,
        // by box_sign.h's margin, Sigma' does not cross the part: skip its pieces (8 evaluations
        // instead of a trilinear re-expanded per slab box, a cubic and its critical points per
        // piece). v0 keeps its sign to the exit, and only its sign is read from here on. The
        // pieces' cubics are expanded about the segment's start: within a few cells of it their
        // rounding is far below the margin and they would find no sign change either (the same
        // roots), but a hundred cells away it can reach
        // the margin, and there the skip is the more accurate of the two.
        const Vec3d p_in = a_local + t0 * d, p_out = a_local + t1 * d;
        const bool keeps_sign = t1 > t0 && sign_on_cell_box(cf, corner, openvdb::math::minComponent(p_in, p_out),
                                                            openvdb::math::maxComponent(p_in, p_out),
                                                            inside(v0) ? 1 : -1) != 0;
        if (t1 > t0 && !keeps_sign) {
            // F' is trilinear on each of the cell's slab/core boxes (face_slabs.h): split
            // [t0, t1] where the segment crosses their planes, then per piece as one cubic.
            double cuts[8];
            int ncut = 0;
            if (slabs.h > 0)
                for (int k = 0; k < 3; ++k) {
                    if (d[k] == 0) continue;
                    for (const double plane : {slabs.h, 1 - slabs.h}) {
                        const double tc = (plane - a_local[k]) / d[k];
                        if (tc > t0 && tc < t1) cuts[ncut++] = tc;
                    }
                }
            std::sort(cuts, cuts + ncut);
            cuts[ncut++] = t1;
            double p0 = t0;
            for (int pc = 0; pc < ncut; ++pc) {
                const double p1 = cuts[pc];
                if (!(p1 > p0)) continue;
                const Vec3d mid = a_local + (0.5 * (p0 + p1)) * d;
                const Cubic q = cf.piece(slabs.piece_of(mid[0]), slabs.piece_of(mid[1]), slabs.piece_of(mid[2]))
                                    .along(a_local, d);
                // Breakpoints: p0, critical points of q in (p0, p1), p1.
                double crit[2];
                const int nc = quadratic_roots_in(q.c[1], 2 * q.c[2], 3 * q.c[3], p0, p1, crit);
                double lo = p0, vlo = v0;
                for (int i = 0; i <= nc; ++i) {
                    const double hi = (i < nc) ? crit[i] : p1;
                    const double vhi = q(hi);
                    if (inside(vlo) != inside(vhi)) out.t.push_back(bisect(q, lo, hi, inside(vlo)));
                    lo = hi;
                    vlo = vhi;
                }
                v0 = vlo;
                p0 = p1;
            }
        }
        t0 = t1;
        if (is_last || t1 >= 1.0) break;
        cell[axis] += step[axis];
        t_next[axis] += t_delta[axis];
    }
    out.inside_at_end = inside(v0);
    return out;
}

} // namespace isodel::octree
