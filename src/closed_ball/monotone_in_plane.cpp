#include "closed_ball/monotone_in_plane.h"

#include "octree/box_cells.h"

#include <cmath>

namespace isodel::mesher {
namespace {

/// The weak sign of dF/dx_k seen so far on each axis: broken once both signs were seen.
struct AxisSigns {
    bool pos[3] = {false, false, false};
    bool neg[3] = {false, false, false};

    bool is_signed(int k) const { return !(pos[k] && neg[k]); }
    /// s_k: +1 unless only negative differences were seen (all zero: either sign holds).
    double sign(int k) const { return neg[k] ? -1.0 : 1.0; }

    /// The direction of the file comment from the signed axes, if there is one.
    std::optional<octree::Vec3d> direction(const octree::Vec3d& N) const
    {
        for (int k = 0; k < 3; ++k)
            if (is_signed(k) && N[k] == 0) {
                octree::Vec3d u(0, 0, 0);
                u[k] = sign(k);
                return u;
            }
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                if (!is_signed(i) || !is_signed(j)) continue;
                const double ci = sign(i) * N[i], cj = sign(j) * N[j];
                if (!(ci > 0 && cj < 0)) continue;
                octree::Vec3d u(0, 0, 0);
                u[i] = -cj * sign(i); // a_i = |c_j|, a_j = c_i: a_i c_i + a_j c_j = 0
                u[j] = ci * sign(j);
                return u;
            }
        return std::nullopt;
    }
};

} // namespace

std::optional<octree::Vec3d> monotone_direction_in_plane(const octree::SampleField::Reader& reader,
                                                         const octree::Vec3d& lo, const octree::Vec3d& hi,
                                                         const octree::Vec3d& N)
{
    AxisSigns s;
    bool possible = true;
    octree::for_each_cell_part(lo, hi, [&](const openvdb::Coord& c, const octree::Vec3d&, const octree::Vec3d&) {
        if (!possible) return;
        double f[8]; // corner (i, j, k) at index i + 2j + 4k
        reader.cell_corners(c, f);
        for (int k = 0; k < 3; ++k) {
            const int bit = 1 << k;
            for (int m = 0; m < 8; ++m) {
                if (m & bit) continue;
                const double d = f[m | bit] - f[m];
                s.pos[k] |= d > 0;
                s.neg[k] |= d < 0;
            }
        }
        // Signs are only ever lost: once no direction is left, none comes back.
        possible = s.direction(N).has_value();
    });
    if (!possible) return std::nullopt;
    return s.direction(N);
}

} // namespace isodel::mesher
