#pragma once
// Internal: the strict sign shared by every edge difference along one axis, the test behind the
// octree certificates (certified_coarsening.h, seed_octree.h): on a unit cell the d-derivative of
// a trilinear function is bilinear in the other two coordinates, so its extremes are the four
// d-edge differences, and strict signs there give a strictly monotone function on the cell.
#include <algorithm>
#include <cmath>
#include <limits>

namespace isodel::octree {

/// Tracks the sign of the differences added and the smallest magnitude; broken by the first zero
/// or sign change.
struct Monotone {
    int sign = 0;
    bool ok = true;
    double min_abs = std::numeric_limits<double>::infinity();
    void add(double diff)
    {
        if (!ok) return;
        const int s = diff > 0 ? 1 : diff < 0 ? -1 : 0;
        if (s == 0 || (sign != 0 && s != sign)) {
            ok = false;
            return;
        }
        sign = s;
        min_abs = std::min(min_abs, std::abs(diff));
    }
};

} // namespace isodel::octree
