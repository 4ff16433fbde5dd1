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
#include "octree/box_cells.h"
#include "octree/cell_function.h"

#include <algorithm>
#include <cmath>

namespace isodel::octree {

/// True when phi_at(p) >= 0 (\p inside) or < 0 (not \p inside) for every p in [lo, hi], with
/// the margin above. False says nothing: the box may still keep the sign.
inline bool one_sign_on_box(const SampleField::Reader& reader, const Vec3d& lo, const Vec3d& hi, bool inside)
{
    bool certified = true;
    for_each_cell_part(lo, hi, [&](const Coord& c, const Vec3d& a, const Vec3d& b) {
        if (!certified) return;
        double corner[8];
        reader.cell_corners(c, corner);
        double scale = 0;
        for (const double v : corner) scale = std::max(scale, std::abs(v));
        const double margin = 1e-9 * scale;
        const CellFunction f(Trilinear::from_corners(corner), reader.field().face_slabs());
        for (int k = 0; k < 8 && certified; ++k) {
            const double phi = f(k & 1 ? b[0] : a[0], k & 2 ? b[1] : a[1], k & 4 ? b[2] : a[2]);
            certified = inside ? phi > margin : phi < -margin;
        }
    });
    return certified;
}

} // namespace isodel::octree
