// The exact in-sphere sign in 320-bit integers (exact_in_sphere.h).
#include "geometry/exact_in_sphere.h"

#include <cstdint>
#include <cstring>

namespace isodel::geometry {
namespace {

using i128 = __int128;
using u128 = unsigned __int128;

/// A 320-bit two's complement integer: sums modulo 2^320, exact for values below 2^319.
struct Int320 {
    std::uint64_t w[5]; // little-endian limbs

    friend Int320 operator+(const Int320& a, const Int320& b)
    {
        Int320 r;
        u128 carry = 0;
        for (int i = 0; i < 5; ++i) {
            const u128 s = u128(a.w[i]) + b.w[i] + carry;
            r.w[i] = std::uint64_t(s);
            carry = s >> 64;
        }
        return r;
    }

    Int320 operator-() const
    {
        Int320 r;
        u128 carry = 1; // ~x + 1
        for (int i = 0; i < 5; ++i) {
            const u128 s = u128(~w[i]) + carry;
            r.w[i] = std::uint64_t(s);
            carry = s >> 64;
        }
        return r;
    }

    int sign() const
    {
        if (std::int64_t(w[4]) < 0) return -1;
        return (w[0] | w[1] | w[2] | w[3] | w[4]) ? 1 : 0;
    }
};

/// (-1)^negative |a| |b| for magnitudes given as limbs (little-endian), the product below 2^319.
Int320 product(const std::uint64_t* a, int na, const std::uint64_t* b, int nb, bool negative)
{
    std::uint64_t r[5] = {0, 0, 0, 0, 0};
    for (int i = 0; i < na; ++i) {
        std::uint64_t carry = 0;
        for (int j = 0; j < nb; ++j) {
            const u128 t = u128(a[i]) * b[j] + r[i + j] + carry;
            r[i + j] = std::uint64_t(t);
            carry = std::uint64_t(t >> 64);
        }
        r[i + nb] = carry; // row i reaches no further; na + nb <= 5
    }
    const Int320 v{{r[0], r[1], r[2], r[3], r[4]}};
    return negative ? -v : v;
}

/// a b, |a| < 2^63, |b| < 2^127.
Int320 product(std::int64_t a, i128 b)
{
    const std::uint64_t ua = std::uint64_t(a < 0 ? -a : a);
    const u128 ub = u128(b < 0 ? -b : b);
    const std::uint64_t limbs[2] = {std::uint64_t(ub), std::uint64_t(ub >> 64)};
    return product(&ua, 1, limbs, 2, (a < 0) != (b < 0));
}

/// (-1)^negative l m, 0 <= l < 2^128, |m| < 2^192.
Int320 product(u128 l, const Int320& m, bool negative)
{
    const bool m_negative = m.sign() < 0;
    const Int320 mag = m_negative ? -m : m;
    const std::uint64_t limbs[2] = {std::uint64_t(l), std::uint64_t(l >> 64)};
    return product(limbs, 2, mag.w, 3, negative != m_negative);
}

/// a - b, and whether it is exact (Knuth's two-difference: its rounding error is 0).
bool exact_difference(double a, double b, double& d)
{
    d = a - b;
    const double bv = a - d;
    const double av = d + bv;
    return (a - av) + (bv - b) == 0;
}

/// Each nonzero difference as an odd integer times a power of two: mantissa and exponent.
struct Scaled {
    std::int64_t m = 0;
    int e = 0;
};

Scaled scaled(double d)
{
    if (d == 0) return {};
    std::uint64_t bits;
    std::memcpy(&bits, &d, sizeof bits);
    const int biased = int((bits >> 52) & 0x7ff);
    std::uint64_t m = bits & ((std::uint64_t(1) << 52) - 1);
    int e = -1074; // a subnormal: m 2^-1074
    if (biased != 0) {
        m |= std::uint64_t(1) << 52; // the hidden bit
        e = biased - 1075;
    }
    const int tz = __builtin_ctzll(m); // trailing zero bits
    const std::int64_t odd = std::int64_t(m >> tz);
    return {(bits >> 63) ? -odd : odd, e + tz};
}

/// Bits of |m| (m != 0).
int bit_length(std::int64_t m) { return 64 - __builtin_clzll(std::uint64_t(m < 0 ? -m : m)); }

} // namespace

bool exact_in_sphere_sign(const double p[3], const double q[3], const double r[3], const double s[3],
                          const double t[3], int& sign)
{
    // Rows in CGAL's order: p, r, q, s (side_of_oriented_sphereC3).
    const double* rows[4] = {p, r, q, s};
    Scaled d[4][3];
    bool any = false;
    int lowest = 0, highest = 0; // of the bits of the nonzero differences
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) {
            double x;
            if (!exact_difference(rows[i][k], t[k], x)) return false;
            d[i][k] = scaled(x);
            if (x == 0) continue;
            const int lo = d[i][k].e, hi = d[i][k].e + bit_length(d[i][k].m);
            lowest = any ? (lo < lowest ? lo : lowest) : lo;
            highest = any ? (hi > highest ? hi : highest) : hi;
            any = true;
        }
    if (!any) { // five equal points
        sign = 0;
        return true;
    }
    if (highest - lowest > 60) return false;
    // The differences in units of 2^lowest: |X| < 2^60.
    std::int64_t X[4][3];
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) X[i][k] = d[i][k].m == 0 ? 0 : d[i][k].m * (std::int64_t(1) << (d[i][k].e - lowest));
    // The xy minors of the row pairs (< 2^121) and the lifts (< 2^122).
    const auto minor2 = [&](int a, int b) { return i128(X[a][0]) * X[b][1] - i128(X[a][1]) * X[b][0]; };
    const i128 m01 = minor2(0, 1), m02 = minor2(0, 2), m03 = minor2(0, 3), m12 = minor2(1, 2), m13 = minor2(1, 3),
               m23 = minor2(2, 3);
    // det(P; Q; R) on (x, y, z) = P.z m(Q, R) - Q.z m(P, R) + R.z m(P, Q): < 2^183.
    const auto minor3 = [&](int P, int Q, int R, i128 mQR, i128 mPR, i128 mPQ) {
        return product(X[P][2], mQR) + product(-X[Q][2], mPR) + product(X[R][2], mPQ);
    };
    const Int320 M0 = minor3(1, 2, 3, m23, m13, m12), M1 = minor3(0, 2, 3, m23, m03, m02),
                 M2 = minor3(0, 1, 3, m13, m03, m01), M3 = minor3(0, 1, 2, m12, m02, m01);
    const auto lift = [&](int a) {
        return u128(i128(X[a][0]) * X[a][0] + i128(X[a][1]) * X[a][1] + i128(X[a][2]) * X[a][2]);
    };
    // Along the lift column: det = -|A|^2 M_A + |B|^2 M_B - |C|^2 M_C + |D|^2 M_D (< 2^307).
    const Int320 det = product(lift(0), M0, true) + product(lift(1), M1, false) + product(lift(2), M2, true) +
                       product(lift(3), M3, false);
    sign = det.sign();
    return true;
}

} // namespace isodel::geometry
