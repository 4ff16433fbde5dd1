#pragma once
// Internal: how far a point of a triangle can be from the triangle's nearest corner. The
// mesher's Hausdorff refinement (hausdorff_refinement.cpp) bounds d(x, Sigma) over a triangle
// by d(corner, Sigma) + this reach (distance to Sigma is 1-Lipschitz).
#include <openvdb/math/Vec3.h>

#include <algorithm>
#include <cmath>

namespace isodel::geometry {

/// max over x in triangle abc of min(|x - a|, |x - b|, |x - c|), or an upper bound of it:
/// - acute: the circumradius, reached at the circumcentre (inside the triangle), exactly;
/// - right or obtuse: half the longest edge, an upper bound (the circumcentre is outside, and
///   the corner regions' common boundary inside the triangle stays within half the longest
///   edge of a corner).
/// Both are at most L / sqrt(3) (L: the longest edge), the equilateral case.
inline double triangle_corner_reach(const openvdb::math::Vec3d& a, const openvdb::math::Vec3d& b,
                                    const openvdb::math::Vec3d& c)
{
    double e[3] = {(b - c).lengthSqr(), (c - a).lengthSqr(), (a - b).lengthSqr()};
    std::sort(e, e + 3);
    if (e[2] >= e[0] + e[1]) return 0.5 * std::sqrt(e[2]);
    const double twice_area = (b - a).cross(c - a).length();
    return std::sqrt(e[0] * e[1] * e[2]) / (2.0 * twice_area); // abc / (4 area)
}

} // namespace isodel::geometry
