#pragma once
/// \file box_cells.h
/// The grid cells an index-space box meets and the box's part in each, in cell-local coordinates
/// ([0, 1]^3). Bounds of F' over a box are taken cell by cell, because F' is one trilinear
/// function (per slab piece, face_slabs.h) only inside a cell: box_sign.h's certificate and the
/// Voronoi cell disk certificate (src/closed_ball/voronoi_cell_disks.cpp) both walk a box this way.
#include <openvdb/math/Coord.h>
#include <openvdb/math/Vec3.h>

#include <algorithm>
#include <cmath>

namespace isodel::octree {

/// Calls fn(cell, a, b) for the cells floor(lo) ... floor(hi), the ones phi_at reads for points
/// of the box (it takes the cell floor(p)). [a, b] is the box clipped to the cell, relative to
/// its lowest corner; it may be flat (a[k] == b[k]) where the box only touches the cell.
template <class Fn>
inline void for_each_cell_part(const openvdb::Vec3d& lo, const openvdb::Vec3d& hi, Fn&& fn)
{
    const openvdb::Coord c0(int(std::floor(lo[0])), int(std::floor(lo[1])), int(std::floor(lo[2])));
    const openvdb::Coord c1(int(std::floor(hi[0])), int(std::floor(hi[1])), int(std::floor(hi[2])));
    for (int z = c0.z(); z <= c1.z(); ++z)
        for (int y = c0.y(); y <= c1.y(); ++y)
            for (int x = c0.x(); x <= c1.x(); ++x) {
                const openvdb::Coord c(x, y, z);
                const openvdb::Vec3d o = c.asVec3d();
                openvdb::Vec3d a, b;
                for (int k = 0; k < 3; ++k) {
                    a[k] = std::max(lo[k] - o[k], 0.0);
                    b[k] = std::min(hi[k] - o[k], 1.0);
                }
                fn(c, a, b);
            }
}

} // namespace isodel::octree
