#pragma once
/// \file box_sign.h
/// Whether F' (cell_function.h) keeps one sign on an index-space box, decided from finitely many
/// values: a cheap certificate that no point of the box lies on the other side of Sigma'.
///
/// On each mesh cell's part of the box F' = f o phi, with f trilinear (multilinear) and phi
/// monotone per axis (face_slabs.h), so phi maps the part onto a box of the sample cell and F'
/// takes its extremes at the part's eight corners. The test asks every corner value to have the
/// sign by a margin of 1e-9 of the cell's largest sample, far above the rounding of a trilinear
/// evaluation (below 1e-13 of it), so phi_at anywhere in the box has that sign too.
#include "octree/cell_function.h"

#include <algorithm>
#include <cmath>

namespace isodel::octree {

/// True when phi_at(p) >= 0 (\p inside) or < 0 (not \p inside) for every p in [lo, hi], with
/// the margin above. False says nothing: the box may still keep the sign.
inline bool one_sign_on_box(const SampleField::Reader& reader, const Vec3d& lo, const Vec3d& hi, bool inside)
{
    // The cells phi_at reads for points of the box (it takes the cell floor(p)).
    const Coord a(int(std::floor(lo[0])), int(std::floor(lo[1])), int(std::floor(lo[2])));
    const Coord b(int(std::floor(hi[0])), int(std::floor(hi[1])), int(std::floor(hi[2])));
    for (int z = a[2]; z <= b[2]; ++z)
        for (int y = a[1]; y <= b[1]; ++y)
            for (int x = a[0]; x <= b[0]; ++x) {
                double corner[8];
                reader.cell_corners(Coord(x, y, z), corner);
                double scale = 0;
                for (const double v : corner) scale = std::max(scale, std::abs(v));
                const double margin = 1e-9 * scale;
                const CellFunction f(Trilinear::from_corners(corner), reader.field().face_slabs());
                const double lx[2] = {std::max(lo[0] - x, 0.0), std::min(hi[0] - x, 1.0)};
                const double ly[2] = {std::max(lo[1] - y, 0.0), std::min(hi[1] - y, 1.0)};
                const double lz[2] = {std::max(lo[2] - z, 0.0), std::min(hi[2] - z, 1.0)};
                for (const double u : lx)
                    for (const double v : ly)
                        for (const double w : lz) {
                            const double phi = f(u, v, w);
                            if (inside ? !(phi > margin) : !(phi < -margin)) return false;
                        }
            }
    return true;
}

} // namespace isodel::octree
