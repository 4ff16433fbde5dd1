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

/// The sign F' keeps on the local box [\p lo, \p hi] of one cell, by the margin above: +1 when
/// every corner value exceeds it, -1 when every one is below its negative, 0 when neither (the
/// box may still keep a sign). \p f is the cell's F', \p corner its samples (for the margin).
/// With \p want +1 or -1 only that sign is asked for: 0 as soon as a corner lacks it.
inline int sign_on_cell_box(const CellFunction& f, const double corner[8], const Vec3d& lo, const Vec3d& hi,
                            int want = 0)
{
    double scale = 0;
    for (int k = 0; k < 8; ++k) scale = std::max(scale, std::abs(corner[k]));
    const double margin = 1e-9 * scale;
    int sign = want;
    for (int k = 0; k < 8; ++k) {
        const double phi = f(k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]);
        const int s = phi > margin ? 1 : phi < -margin ? -1 : 0;
        if (s == 0 || (sign != 0 && s != sign)) return 0;
        sign = s;
    }
    return sign;
}

/// True when phi_at(p) >= 0 (\p inside) or < 0 (not \p inside) for every p in [lo, hi], with
/// the margin above. False says nothing: the box may still keep the sign.
inline bool one_sign_on_box(const SampleField::Reader& reader, const Vec3d& lo, const Vec3d& hi, bool inside)
{
    bool certified = true;
    for_each_cell_part(lo, hi, [&](const Coord& c, const Vec3d& a, const Vec3d& b) {
        if (!certified) return;
        double corner[8];
        const CellFunction f = cell_function(reader, c, corner);
        certified = sign_on_cell_box(f, corner, a, b, inside ? 1 : -1) != 0;
    });
    return certified;
}

} // namespace isodel::octree
