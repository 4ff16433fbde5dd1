#pragma once
// Internal to verify: the trilinear interpolant phi of octree::SampleField (positive inside) at
// arbitrary index-space points, its gradient, and a Newton projection onto Sigma = {phi = 0}.
// Written here rather than taken from the mesher so that a mesher bug cannot hide in the verifier:
// only the *definition* of the samples (sample_field.h) is shared.
#include "octree/sample_field.h"

#include <openvdb/openvdb.h>

#include <memory>

namespace isodel::verify {

using openvdb::Coord;
using openvdb::Vec3d;

class TrilinearField {
public:
    TrilinearField(const openvdb::FloatGrid& grid, double isovalue, Inside inside);

    const octree::SampleField& samples() const { return *field_; }
    double voxel() const { return field_->min_voxel_edge(); }

    /// Index -> world is x_w = A x_i + b (affine transforms only, checked in the constructor).
    Vec3d to_world(const Vec3d& i) const { return A_ * i + b_; }
    Vec3d to_index(const Vec3d& w) const { return Ainv_ * (w - b_); }
    const openvdb::Mat3d& A() const { return A_; }

    /// phi at index point \p x and its index-space gradient, from the cell containing x.
    /// Not thread-safe: use one Evaluator per thread.
    class Evaluator {
    public:
        explicit Evaluator(const TrilinearField& f) : f_(&f), reader_(*f.field_) {}
        double phi(const Vec3d& x, Vec3d* grad = nullptr);
        /// Newton steps along the world gradient from \p x (index space) until |phi| is below
        /// roundoff; \return false if it did not converge. \p out is in index space.
        bool project(const Vec3d& x, Vec3d& out);
        const octree::SampleField::Reader& reader() const { return reader_; }

    private:
        const TrilinearField* f_;
        octree::SampleField::Reader reader_;
        Coord cached_{Coord::max()};
        double c_[8];
    };

private:
    std::unique_ptr<octree::SampleField> field_;
    openvdb::Mat3d A_, Ainv_, metric_inv_; // metric_inv = A^-1 A^-T (index-space step of a world gradient step)
    Vec3d b_;
    double phi_scale_ = 1.0;               // typical |phi| magnitude, for the Newton tolerance
    friend class Evaluator;
};

} // namespace isodel::verify
