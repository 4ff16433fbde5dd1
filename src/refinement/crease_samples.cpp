#include "refinement/crease_samples.h"

#include "octree/cell_interpolant.h"

#include <algorithm>
#include <cmath>

namespace isodel::mesher {

int crease_lines_per_voxel(double min_voxel_edge, double eps)
{
    // Lines every eps / 2 (world). Bounded both ways: at least one interior line per face
    // direction, and at most 64 (a coarser sampling than eps / 2 at eps < 1/32 voxel, where
    // M's vertices are denser than the samples anyway).
    const double r = std::ceil(2.0 * min_voxel_edge / eps);
    return r >= 64 ? 64 : std::max(2, int(r));
}

void crease_samples(const octree::SampleField& field, const openvdb::Coord& c, const double corner[8],
                    int lines_per_voxel, std::vector<openvdb::Vec3d>& out)
{
    using Vec3d = openvdb::Vec3d;
    const int R = lines_per_voxel;
    const octree::FaceSlabs& slabs = field.face_slabs();
    const auto f = octree::Trilinear::from_corners(corner);
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            // F is bilinear on the face, so it has the corners' sign all over the face when
            // they agree: no line on it crosses Sigma.
            int n_inside = 0;
            for (int k = 0; k < 8; ++k)
                if (((k >> axis) & 1) == side && corner[k] >= 0) ++n_inside;
            if (n_inside == 0 || n_inside == 4) continue;
            for (int dir = 0; dir < 3; ++dir) {
                if (dir == axis) continue;
                const int other = 3 - axis - dir;
                for (int i = 1; i < R; ++i) {
                    Vec3d p0(0.0);
                    p0[axis] = side;
                    p0[other] = double(i) / R;
                    Vec3d p1 = p0;
                    p1[dir] = 1;
                    const double v0 = f(p0[0], p0[1], p0[2]), v1 = f(p1[0], p1[1], p1[2]);
                    if ((v0 >= 0) == (v1 >= 0)) continue;
                    const Vec3d l = p0 + (p1 - p0) * (v0 / (v0 - v1)); // F is linear here
                    // Sigma' has this crease at the slab's boundary on the cell's side: the
                    // same curve, mapped, h inside the cell.
                    Vec3d m = slabs.from_sample(c.asVec3d() + l);
                    m[axis] += side == 0 ? slabs.h : -slabs.h;
                    out.push_back(field.index_to_world(m));
                }
            }
        }
}

} // namespace isodel::mesher
