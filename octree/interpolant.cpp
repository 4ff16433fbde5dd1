#include "octree/interpolant.h"

#include <cmath>

namespace isodel::octree {

namespace {
inline double lerp(double a, double b, double t) { return a + t * (b - a); }

} // namespace

double TrilinearInterpolant::eval(const double c[8], const Vec3d& u) const
{
    const double x00 = lerp(c[0], c[1], u.x()), x10 = lerp(c[2], c[3], u.x());
    const double x01 = lerp(c[4], c[5], u.x()), x11 = lerp(c[6], c[7], u.x());
    return lerp(lerp(x00, x10, u.y()), lerp(x01, x11, u.y()), u.z());
}

Cubic TrilinearInterpolant::along_segment(const double c[8], const Vec3d& a, const Vec3d& b) const
{
    // F(u) = sum_n c_n X_n(u_x) Y_n(u_y) Z_n(u_z) with X = 1 - u_x or u_x, ...; along the segment
    // each factor is linear in t, so F(t) is a cubic (paper Section 4.3 uses this for roots).
    const Vec3d d = b - a;
    Cubic out;
    for (int n = 0; n < 8; ++n) {
        double f[3][2];
        for (int ax = 0; ax < 3; ++ax) {
            const bool hi = (n >> ax) & 1;
            f[ax][0] = hi ? a[ax] : 1.0 - a[ax];
            f[ax][1] = hi ? d[ax] : -d[ax];
        }
        // (f00 + f01 t)(f10 + f11 t)(f20 + f21 t)
        const double p0 = f[0][0] * f[1][0], p1 = f[0][0] * f[1][1] + f[0][1] * f[1][0],
                     p2 = f[0][1] * f[1][1];
        out.c[0] += c[n] * (p0 * f[2][0]);
        out.c[1] += c[n] * (p0 * f[2][1] + p1 * f[2][0]);
        out.c[2] += c[n] * (p1 * f[2][1] + p2 * f[2][0]);
        out.c[3] += c[n] * (p2 * f[2][1]);
    }
    return out;
}

const LocalInterpolant& trilinear()
{
    static const TrilinearInterpolant t;
    return t;
}

double InterpolantReader::node_value(const Coord& n) const
{
    const int L = cells_.grid().max_level();
    // Coarsest leaf whose closed span contains n: at level l, the candidate origins are
    // align_down(n) and, on axes where n is on the 2^l lattice, one cell lower.
    for (int l = L; l >= 1; --l) {
        const Coord lo = align_down(n, l);
        const int s = 1 << l;
        const bool on[3] = {lo.x() == n.x(), lo.y() == n.y(), lo.z() == n.z()};
        // n on this lattice: no coarser leaf contained it (previous l), and every leaf of level
        // <= l containing it has it as a corner, so n is no hanging node: read the sample.
        if (on[0] && on[1] && on[2]) return cells_.sample(n);
        for (int m = 0; m < 8; ++m) {
            if (((m & 1) && !on[0]) || ((m & 2) && !on[1]) || ((m & 4) && !on[2])) continue;
            const CellId c{lo.offsetBy((m & 1) ? -s : 0, (m & 2) ? -s : 0, (m & 4) ? -s : 0), l};
            if (cells_.is_leaf(c)) {
                double cv[8];
                corners(c, cv);
                const Vec3d p(n.x(), n.y(), n.z());
                return li_->eval(cv, local_coords(c, p));
            }
        }
    }
    return cells_.sample(n);
}

void InterpolantReader::corners(const CellId& c, double out[8]) const
{
    const int s = c.size();
    for (int m = 0; m < 8; ++m)
        out[m] = node_value(c.origin.offsetBy((m & 1) * s, ((m >> 1) & 1) * s, ((m >> 2) & 1) * s));
}

double InterpolantReader::eval_in(const CellId& c, const Vec3d& p) const
{
    double cv[8];
    corners(c, cv);
    return li_->eval(cv, local_coords(c, p));
}

std::optional<CellId> InterpolantReader::leaf_at(const Vec3d& p) const
{
    const CoordBBox cells = cells_.grid().unit_cells();
    Coord u(int(std::floor(p.x())), int(std::floor(p.y())), int(std::floor(p.z())));
    for (int a = 0; a < 3; ++a) // points on the upper domain faces belong to the last cell
        if (u[a] == cells.max()[a] + 1 && p[a] == double(u[a])) u[a] -= 1;
    return cells_.leaf(u);
}

std::optional<double> InterpolantReader::eval(const Vec3d& p) const
{
    const auto c = leaf_at(p);
    if (!c) return std::nullopt;
    return eval_in(*c, p);
}

} // namespace isodel::octree
