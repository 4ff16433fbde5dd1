#pragma once
// Internal: the closest point of a triangle to a point, shared by the mesher's Hausdorff
// refinement and isodel verify (a pure distance computation: no combinatorial decision).
#include <openvdb/math/Vec3.h>

namespace isodel::geometry {

/// Closest point to p on triangle abc (Ericson, Real-Time Collision Detection, 5.1.5).
inline openvdb::Vec3d closest_on_triangle(const openvdb::Vec3d& p, const openvdb::Vec3d& a,
                                          const openvdb::Vec3d& b, const openvdb::Vec3d& c)
{
    using Vec3d = openvdb::Vec3d;
    const Vec3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const Vec3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
    const Vec3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const double den = 1.0 / (va + vb + vc);
    return a + ab * (vb * den) + ac * (vc * den);
}

} // namespace isodel::geometry
