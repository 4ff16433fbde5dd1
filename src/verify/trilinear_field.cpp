#include "verify/trilinear_field.h"

#include <isodel/errors.h>

#include <algorithm>
#include <cmath>

namespace isodel::verify {

TrilinearField::TrilinearField(const openvdb::FloatGrid& grid, double isovalue, Inside inside)
{
    // SampleField wants shared ownership; the caller keeps the grid alive for our lifetime.
    openvdb::FloatGrid::ConstPtr alias(&grid, [](const openvdb::FloatGrid*) {});
    field_ = std::make_unique<octree::SampleField>(alias, isovalue, inside);
    const auto& xf = grid.transform();
    if (!xf.isLinear())
        throw InvalidInput("verify: grid '" + grid.getName() + "' has a non-affine transform");
    b_ = xf.indexToWorld(Vec3d(0.0));
    for (int a = 0; a < 3; ++a) {
        Vec3d e(0.0);
        e[a] = 1.0;
        const Vec3d col = xf.indexToWorld(e) - b_;
        for (int r = 0; r < 3; ++r) A_(r, a) = col[r];
    }
    Ainv_ = A_.inverse();
    metric_inv_ = Ainv_ * Ainv_.transpose();
    phi_scale_ = std::max(1e-300, field_->value_max() - field_->value_min());
}

double TrilinearField::Evaluator::phi(const Vec3d& x, Vec3d* grad)
{
    const Coord c(int(std::floor(x[0])), int(std::floor(x[1])), int(std::floor(x[2])));
    if (c != cached_) {
        reader_.cell_corners(c, c_);
        cached_ = c;
    }
    const double u = x[0] - c[0], v = x[1] - c[1], w = x[2] - c[2];
    // Corner n = i + 2j + 4k.
    const double x00 = c_[0] + u * (c_[1] - c_[0]), x10 = c_[2] + u * (c_[3] - c_[2]);
    const double x01 = c_[4] + u * (c_[5] - c_[4]), x11 = c_[6] + u * (c_[7] - c_[6]);
    const double y0 = x00 + v * (x10 - x00), y1 = x01 + v * (x11 - x01);
    if (grad) {
        const double dx0 = (1 - v) * (c_[1] - c_[0]) + v * (c_[3] - c_[2]);
        const double dx1 = (1 - v) * (c_[5] - c_[4]) + v * (c_[7] - c_[6]);
        (*grad)[0] = (1 - w) * dx0 + w * dx1;
        (*grad)[1] = (1 - w) * (x10 - x00) + w * (x11 - x01);
        (*grad)[2] = y1 - y0;
    }
    return y0 + w * (y1 - y0);
}

bool TrilinearField::Evaluator::project(const Vec3d& x0, Vec3d& out)
{
    // Newton on phi along the world-space gradient: dx_world = -phi g_w / |g_w|^2, which in
    // index space is dx = -phi M g / (g^T M g), M = A^-1 A^-T. Steps are capped at half a voxel so
    // that a flat gradient cannot throw the point across the volume.
    Vec3d x = x0, g;
    const double tol = 1e-12 * f_->phi_scale_;
    for (int it = 0; it < 40; ++it) {
        const double p = phi(x, &g);
        if (std::abs(p) <= tol) {
            out = x;
            return true;
        }
        const Vec3d mg = f_->metric_inv_ * g;
        const double gmg = g.dot(mg);
        if (!(gmg > 0)) break;
        Vec3d dx = mg * (-p / gmg);
        const double len = dx.length();
        if (len > 0.5) dx *= 0.5 / len;
        if (len < 1e-14) { // converged in position even if phi is not below tol (steep data)
            out = x + dx;
            return true;
        }
        x += dx;
    }
    out = x;
    return std::abs(phi(x)) <= 1e-9 * f_->phi_scale_;
}

} // namespace isodel::verify
