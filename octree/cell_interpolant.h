#pragma once
/// \file cell_interpolant.h
/// The trilinear interpolant of one cell and its restriction to a line, a cubic polynomial
/// (paper Section 5: the Voronoi-edge / Sigma intersection is solved per cell on this cubic).
#include <openvdb/math/Vec3.h>

namespace isodel::octree {

/// c0 + c1 t + c2 t^2 + c3 t^3.
struct Cubic {
    double c[4] = {0, 0, 0, 0};
    double operator()(double t) const { return ((c[3] * t + c[2]) * t + c[1]) * t + c[0]; }
    double derivative(double t) const { return (3 * c[3] * t + 2 * c[2]) * t + c[1]; }
};

/// F(x,y,z) = a0 + a1 x + a2 y + a3 z + a4 xy + a5 xz + a6 yz + a7 xyz on the unit cube, in
/// coordinates local to the cell scaled so the cell is [0,1]^3.
struct Trilinear {
    double a[8];

    /// \p corner[i + 2j + 4k] is the value at local corner (i,j,k).
    static Trilinear from_corners(const double corner[8])
    {
        const double* c = corner;
        Trilinear t;
        t.a[0] = c[0];
        t.a[1] = c[1] - c[0];
        t.a[2] = c[2] - c[0];
        t.a[3] = c[4] - c[0];
        t.a[4] = c[3] - c[1] - c[2] + c[0];
        t.a[5] = c[5] - c[1] - c[4] + c[0];
        t.a[6] = c[6] - c[2] - c[4] + c[0];
        t.a[7] = c[7] - c[3] - c[5] - c[6] + c[1] + c[2] + c[4] - c[0];
        return t;
    }

    double operator()(double x, double y, double z) const
    {
        return a[0] + a[1] * x + a[2] * y + a[3] * z + a[4] * x * y + a[5] * x * z + a[6] * y * z +
               a[7] * x * y * z;
    }

    openvdb::math::Vec3d gradient(double x, double y, double z) const
    {
        return {a[1] + a[4] * y + a[5] * z + a[7] * y * z, a[2] + a[4] * x + a[6] * z + a[7] * x * z,
                a[3] + a[5] * x + a[6] * y + a[7] * x * y};
    }

    /// F(p + t d) as a cubic in t (p, d in local cell coordinates).
    Cubic along(const openvdb::math::Vec3d& p, const openvdb::math::Vec3d& d) const
    {
        const double px = p[0], py = p[1], pz = p[2], dx = d[0], dy = d[1], dz = d[2];
        Cubic q;
        q.c[0] = (*this)(px, py, pz);
        q.c[1] = a[1] * dx + a[2] * dy + a[3] * dz + a[4] * (px * dy + dx * py) +
                 a[5] * (px * dz + dx * pz) + a[6] * (py * dz + dy * pz) +
                 a[7] * (dx * py * pz + px * dy * pz + px * py * dz);
        q.c[2] = a[4] * dx * dy + a[5] * dx * dz + a[6] * dy * dz +
                 a[7] * (dx * dy * pz + dx * py * dz + px * dy * dz);
        q.c[3] = a[7] * dx * dy * dz;
        return q;
    }
};

} // namespace isodel::octree
