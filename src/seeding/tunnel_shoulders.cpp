#include "seeding/tunnel_shoulders.h"

#include "octree/cell_interpolant.h"
#include "octree/segment_walk.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <cmath>

namespace isodel::mesher {
namespace {

using openvdb::Vec3d;

/// Critical points of the trilinear \p f strictly inside the unit cube (at most two).
int interior_critical_points(const octree::Trilinear& f, Vec3d out[2])
{
    const double* a = f.a;
    int n = 0;
    auto keep = [&](const Vec3d& x) {
        for (int k = 0; k < 3; ++k)
            if (!(x[k] > 0 && x[k] < 1)) return;
        out[n++] = x;
    };
    const double scale = std::abs(a[1]) + std::abs(a[2]) + std::abs(a[3]) + std::abs(a[4]) + std::abs(a[5]) + std::abs(a[6]);
    if (std::abs(a[7]) > 1e-12 * scale) {
        // Shifted to X = x + a6/a7, Y = y + a5/a7, Z = z + a4/a7 the bilinear terms vanish:
        // F = a7 XYZ + B1 X + B2 Y + B3 Z + C, and grad F = 0 reads a7 YZ = -B1, a7 XZ = -B2,
        // a7 XY = -B3, so (XYZ)^2 = -B1 B2 B3 / a7^3 and X = -a7 XYZ / B1 (and so on).
        const double B1 = a[1] - a[4] * a[5] / a[7], B2 = a[2] - a[4] * a[6] / a[7], B3 = a[3] - a[5] * a[6] / a[7];
        if (B1 == 0 || B2 == 0 || B3 == 0) return 0; // degenerate: critical lines, no isolated neck
        const double s2 = -B1 * B2 * B3 / (a[7] * a[7] * a[7]);
        if (!(s2 > 0)) return 0;
        for (const double S : {std::sqrt(s2), -std::sqrt(s2)})
            keep({-a[7] * S / B1 - a[6] / a[7], -a[7] * S / B2 - a[5] / a[7], -a[7] * S / B3 - a[4] / a[7]});
    } else {
        // No cubic term: [0 a4 a5; a4 0 a6; a5 a6 0] x = -(a1, a2, a3), determinant 2 a4 a5 a6.
        const double det = 2 * a[4] * a[5] * a[6];
        if (det == 0) return 0;
        const double b1 = -a[1], b2 = -a[2], b3 = -a[3];
        keep({(-a[6] * a[6] * b1 + a[5] * a[6] * b2 + a[4] * a[6] * b3) / det,
              (a[5] * a[6] * b1 - a[5] * a[5] * b2 + a[4] * a[5] * b3) / det,
              (a[4] * a[6] * b1 + a[4] * a[5] * b2 - a[4] * a[4] * b3) / det});
    }
    return n;
}

/// The hyperbola vertices of Sigma on the three grid planes through the critical point \p s.
void shoulders(const octree::Trilinear& f, const Vec3d& s, const Vec3d& cell_origin, std::vector<Vec3d>& out,
               const octree::SampleField::Reader& reader)
{
    const double fs = f(s[0], s[1], s[2]);
    if (fs == 0) return; // Sigma passes through s: a cone point; the tie rule moves v off it
    // Mixed second derivatives at s: on the plane normal to axis a, k[a] = d2F / du dw.
    const double* a = f.a;
    const double k[3] = {a[6] + a[7] * s[0], a[5] + a[7] * s[1], a[4] + a[7] * s[2]};
    // Near s, Sigma is the quadric F(s) + x^T H x / 2 = 0 with H = [0 k2 k1; k2 0 k0; k1 k0 0]:
    // trace 0, so det H = 2 k0 k1 k2 > 0 means one positive and two negative eigenvalues (and
    // < 0 the reverse). Sigma is a one-sheet hyperboloid - a neck, the tunnel - iff F(s) has the
    // sign of det H; otherwise it is two caps facing across a thin gap, which has no loop to cut,
    // and points on both caps only tempt the restricted Delaunay triangulation to bridge the gap
    // (M would gain a handle that Sigma does not have).
    if (!(fs * k[0] * k[1] * k[2] > 0)) return;
    for (int axis = 0; axis < 3; ++axis) {
        if (k[axis] == 0) continue;
        const int u = (axis + 1) % 3, w = (axis + 2) % 3;
        const double t = std::sqrt(std::abs(fs / k[axis]));
        const double diagonal = (-fs / k[axis]) > 0 ? 1.0 : -1.0; // F(s) + k u w = 0 needs sign(u w)
        for (const double side : {-1.0, 1.0}) {
            Vec3d y = s;
            y[u] += side * t;
            y[w] += side * diagonal * t;
            if (y[u] > 0 && y[u] < 1 && y[w] > 0 && y[w] < 1) {
                out.push_back(cell_origin + y);
            } else {
                // The neck reaches through a face of the cell (the saddle lies within t of it):
                // this cell's quadric no longer describes Sigma there, so take the first crossing
                // of the true Sigma on the same ray from s instead (a point of Sigma on the ring
                // around the neck, usually in the neighbouring cell; inside the cell F keeps
                // F(s)'s sign up to the face, as the quadric has no root before t). Dropping it
                // would leave the ring open, and M can then lose the handle at every eps
                // (tests/seeding/test_tunnel_shoulders.cpp).
                // The ray is twice the vertex distance long, and its walk stops after a few cells
                // (a short ray meets at most 4; a wide, shallow neck needs no shoulders): with no
                // crossing there the point is dropped, as the header says.
                const int kMaxRayCells = 8;
                const Vec3d ray_start = cell_origin + s, ray_end = cell_origin + s + 2.0 * (y - s);
                // The walk reads F' (face_slabs.h) in mesh space: walk the ray's image there and
                // return the crossing's sample-space point, like the others.
                const octree::FaceSlabs& slabs = reader.field().face_slabs();
                const Vec3d a = slabs.from_sample(ray_start), b = slabs.from_sample(ray_end);
                const auto crossings = octree::segment_crossings(reader, a, b, kMaxRayCells);
                if (!crossings.t.empty()) out.push_back(slabs.to_sample(a + crossings.t.front() * (b - a)));
            }
        }
    }
}

} // namespace

std::vector<Vec3d> tunnel_shoulder_points(const octree::SampleField& field, const std::vector<openvdb::Coord>& crossed_cells)
{
    std::vector<std::vector<Vec3d>> found(crossed_cells.size());
    tbb::enumerable_thread_specific<octree::SampleField::Reader> readers([&] { return octree::SampleField::Reader(field); });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, crossed_cells.size(), 64), [&](const auto& r) {
        auto& reader = readers.local();
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            double corner[8];
            reader.cell_corners(crossed_cells[i], corner);
            const octree::Trilinear f = octree::Trilinear::from_corners(corner);
            Vec3d crit[2];
            const int nc = interior_critical_points(f, crit);
            for (int m = 0; m < nc; ++m) shoulders(f, crit[m], crossed_cells[i].asVec3d(), found[i], reader);
        }
    });
    std::vector<Vec3d> out; // in crossed-cell order: deterministic whatever the thread count
    for (auto& v : found) out.insert(out.end(), v.begin(), v.end());
    return out;
}

} // namespace isodel::mesher
