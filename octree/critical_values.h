#pragma once
/// \file critical_values.h
/// Critical points of the piecewise trilinear interpolant F, stratum by stratum.
///
/// Why: the topology of {F >= t} changes only when t passes a critical value of some stratum of
/// the grid (Morse theory on the stratified domain): a sample (vertex), the saddle of F restricted
/// to a cell face (bilinear: at most one), or the critical point inside a cell (trilinear: at most
/// two, saddles). F is linear along grid edges, so edges have none. The tie rule of
/// sample_field.h shifts v to v* = v - d with d below the gap to the nearest such value, so that
/// {F = v*} has the topology of the limit {F = v - delta}, delta -> 0+.
///
/// Cell coordinates: corner n of a cell has offset (n & 1, (n >> 1) & 1, (n >> 2) & 1).
#include <array>
#include <cmath>

namespace isodel::octree {

/// Saddle of the bilinear function with corner values f00 = a, f10 = b, f01 = c, f11 = d on the
/// unit square. Returns false when it does not lie strictly inside the square (or the function
/// has no isolated critical point); otherwise the saddle is at (\p u, \p w) and F = \p value there.
inline bool face_saddle(double a, double b, double c, double d, double& u, double& w, double& value)
{
    const double den = a - b - c + d;
    if (den == 0) return false;
    u = (a - c) / den;
    w = (a - b) / den;
    if (!(u > 0 && u < 1 && w > 0 && w < 1)) return false;
    value = (a * d - b * c) / den;
    return true;
}

/// face_saddle() without the position.
inline bool face_saddle_value(double a, double b, double c, double d, double& value)
{
    double u, w;
    return face_saddle(a, b, c, d, u, w, value);
}

/// A critical point of a cell's trilinear function, in cell coordinates, and F there.
struct CellCritical {
    double x, y, z, value;
};

/// Critical points of the trilinear function with corner values \p f (see above) strictly inside
/// the unit cube. Writes up to two into \p out, returns their number.
/// Degenerate cells (a line or plane of critical points) report none.
inline int cell_critical_points(const std::array<double, 8>& f, CellCritical out[2])
{
    // F = a0 + a1 x + a2 y + a3 z + a4 xy + a5 xz + a6 yz + a7 xyz.
    const double a0 = f[0];
    const double a1 = f[1] - f[0], a2 = f[2] - f[0], a3 = f[4] - f[0];
    const double a4 = f[3] - f[2] - f[1] + f[0];
    const double a5 = f[5] - f[4] - f[1] + f[0];
    const double a6 = f[6] - f[4] - f[2] + f[0];
    const double a7 = f[7] - f[6] - f[5] - f[3] + f[4] + f[2] + f[1] - f[0];
    auto eval = [&](double x, double y, double z) {
        return a0 + a1 * x + a2 * y + a3 * z + a4 * x * y + a5 * x * z + a6 * y * z + a7 * x * y * z;
    };
    auto inside = [](double x, double y, double z) { return x > 0 && x < 1 && y > 0 && y < 1 && z > 0 && z < 1; };
    // grad F = 0:  a1 + a4 y + a5 z + a7 yz = 0,  a2 + a4 x + a6 z + a7 xz = 0,
    //              a3 + a5 x + a6 y + a7 xy = 0.
    // The first two give y and x as functions of z (denominator a4 + a7 z); the third then is the
    // quadratic A z^2 + B z + C = 0 below, smooth in a7 (a closed form that translates by 1/a7
    // loses every digit when a7 is a rounding error away from 0).
    const double m = a3 * a7 - a5 * a6;
    const double A = a7 * m, B = 2 * a4 * m;
    const double C = a3 * a4 * a4 - a2 * a4 * a5 - a1 * a4 * a6 + a1 * a2 * a7;
    double roots[2];
    int nr = 0;
    if (A == 0) {
        if (B != 0) roots[nr++] = -C / B;
    } else {
        const double disc = B * B - 4 * A * C;
        if (disc >= 0) {
            const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B)); // no cancellation
            if (q != 0) roots[nr++] = C / q;
            roots[nr++] = q / A;
            if (nr == 2 && roots[0] == roots[1]) nr = 1;
        }
    }
    const double scale = std::abs(a4) + std::abs(a5) + std::abs(a6) + std::abs(a7);
    int n = 0;
    for (int k = 0; k < nr; ++k) {
        double z = roots[k];
        const double den = a4 + a7 * z;
        if (!(std::abs(den) > 1e-12 * scale)) continue; // degenerate: a line of critical points
        double y = -(a1 + a5 * z) / den, x = -(a2 + a6 * z) / den;
        // Two Newton steps on grad F polish the root (Hessian: zero diagonal, linear entries).
        for (int it = 0; it < 2; ++it) {
            const double g0 = a1 + a4 * y + a5 * z + a7 * y * z, g1 = a2 + a4 * x + a6 * z + a7 * x * z,
                         g2 = a3 + a5 * x + a6 * y + a7 * x * y;
            const double h01 = a4 + a7 * z, h02 = a5 + a7 * y, h12 = a6 + a7 * x;
            const double det = 2 * h01 * h02 * h12;
            if (det == 0) break;
            // Inverse of [0 h01 h02; h01 0 h12; h02 h12 0] by cofactors.
            const double dx = -(-h12 * h12 * g0 + h02 * h12 * g1 + h01 * h12 * g2) / det;
            const double dy = -(h02 * h12 * g0 - h02 * h02 * g1 + h01 * h02 * g2) / det;
            const double dz = -(h01 * h12 * g0 + h01 * h02 * g1 - h01 * h01 * g2) / det;
            x += dx, y += dy, z += dz;
        }
        if (inside(x, y, z)) out[n++] = {x, y, z, eval(x, y, z)};
    }
    return n;
}

} // namespace isodel::octree
