#pragma once
// Internal: the exact sign of the in-sphere determinant in fixed-width integer arithmetic, for
// the in-sphere tests of the mesher's Delaunay traits (delaunay/delaunay_traits.h) that CGAL's
// floating-point filter cannot decide and that are not box corners. Nearly all of those are
// exactly 0 (lattice points cospherical across grid cubes), which no floating-point filter can
// decide, and EPICK's multiprecision (Mpzf) evaluation of them is far slower than this.
//
// Why integers suffice: the determinant is a polynomial of the differences p - t. Where those
// are exact doubles (Sterbenz: y/2 <= x <= 2y makes x - y exact, so nearly always for the
// nearby points of a local test) they are integers times one power of two, 2^e. When those
// integers are below 2^60 in magnitude the determinant divided by 2^(5e) is an integer below
// 2^307, computed exactly in 320-bit two's complement (sums and products modulo 2^320 are exact
// while the true values fit). Otherwise the function declines and the caller uses EPICK's.

namespace isodel::geometry {

/// The sign (-1, 0, 1) of CGAL's side_of_oriented_sphere(p, q, r, s, t), computed exactly:
/// the determinant of the rows (x, y, z, x^2 + y^2 + z^2) of p - t, r - t, q - t, s - t, in
/// that order, as CGAL's side_of_oriented_sphereC3 writes it. Returns false, leaving \p sign
/// alone, when a difference to t is not exact or the differences span more than 60 bits.
bool exact_in_sphere_sign(const double p[3], const double q[3], const double r[3], const double s[3],
                          const double t[3], int& sign);

} // namespace isodel::geometry
