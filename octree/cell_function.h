#pragma once
/// \file cell_function.h
/// F' = F o phi (face_slabs.h) on one mesh cell: the sample cell's trilinear read through the
/// slabs, trilinear on each of the cell's up to 27 slab/core boxes.
#include "octree/cell_interpolant.h"
#include "octree/face_slabs.h"
#include "octree/sample_field.h"

#include <algorithm>

namespace isodel::octree {

/// F' on one mesh cell: the sample cell's trilinear f composed with phi. On each of the cell's
/// boxes it is trilinear in the cell's local coordinates (piece()).
class CellFunction {
public:
    CellFunction() = default;
    CellFunction(const Trilinear& f, const FaceSlabs& slabs) : f_(f), s_(slabs) {}

    double operator()(double x, double y, double z) const { return f_(s_.local(x), s_.local(y), s_.local(z)); }
    /// grad F' (local coordinates): zero across a slab, stretched by 1 / (1 - 2h) in a core.
    openvdb::math::Vec3d gradient(double x, double y, double z) const
    {
        const double l[3] = {x, y, z};
        openvdb::math::Vec3d g = f_.gradient(s_.local(x), s_.local(y), s_.local(z));
        for (int k = 0; k < 3; ++k) g[k] *= slope(l[k]);
        return g;
    }
    /// grad F at phi(x) (sample-space local coordinates): Sigma's normal at x's preimage, also
    /// where grad F' loses components in a slab or vanishes in a corner box (F' constant there).
    openvdb::math::Vec3d sample_gradient(double x, double y, double z) const
    {
        return f_.gradient(s_.local(x), s_.local(y), s_.local(z));
    }
    /// F' on box (ix, iy, iz) (FaceSlabs::piece_of per axis) as a trilinear in the cell's local
    /// coordinates: f(alpha x + beta) with alpha, beta of that box per axis. With h = 0, f.
    Trilinear piece(int ix, int iy, int iz) const;
    const FaceSlabs& slabs() const { return s_; }

private:
    double slope(double t) const { return s_.h == 0 ? 1.0 : s_.piece_of(t) == 1 ? 1.0 / (1 - 2 * s_.h) : 0.0; }
    Trilinear f_{};
    FaceSlabs s_;
};

/// Calls visit(ix, iy, iz, lo, hi) for each of a cell's boxes (FaceSlabs::piece_of indices) that
/// meets the local box [a, b], with their intersection [lo, hi] (closed; may be flat).
template <class Visit>
void for_each_piece(const FaceSlabs& s, const openvdb::math::Vec3d& a, const openvdb::math::Vec3d& b, Visit&& visit)
{
    const int first = s.h == 0 ? 1 : 0, last = s.h == 0 ? 1 : 2; // h = 0: the core is the cell
    for (int iz = first; iz <= last; ++iz)
        for (int iy = first; iy <= last; ++iy)
            for (int ix = first; ix <= last; ++ix) {
                const int idx[3] = {ix, iy, iz};
                openvdb::math::Vec3d lo, hi;
                bool meets = true;
                for (int k = 0; k < 3 && meets; ++k) {
                    double plo, phi;
                    s.piece_bounds(idx[k], plo, phi);
                    lo[k] = std::max(a[k], plo);
                    hi[k] = std::min(b[k], phi);
                    meets = lo[k] <= hi[k];
                }
                if (meets) visit(idx[0], idx[1], idx[2], lo, hi);
            }
}

/// F' on the mesh cell with lowest corner \p c; \p corner receives the cell's samples (the
/// scale of box_sign.h's margin).
inline CellFunction cell_function(const SampleField::Reader& reader, const Coord& c, double corner[8])
{
    reader.cell_corners(c, corner);
    return CellFunction(Trilinear::from_corners(corner), reader.field().face_slabs());
}

/// F' on the mesh cell with lowest corner \p c.
inline CellFunction cell_function(const SampleField::Reader& reader, const Coord& c)
{
    double corner[8];
    return cell_function(reader, c, corner);
}

} // namespace isodel::octree
