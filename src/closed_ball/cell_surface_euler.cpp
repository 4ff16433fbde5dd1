#include "closed_ball/cell_surface_euler.h"

#include "octree/box_sign.h"
#include "octree/cell_function.h"

#include "octree/cell_interpolant.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace isodel::mesher {
namespace {

using openvdb::Coord;
using openvdb::Vec3d;

int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// Freudenthal subdivision: the simplices with lowest vertex x are x + chains of disjoint
// non-empty 0/1 vectors. Bit k of a vector code is its component k.
constexpr int kEdgeVectors[7] = {1, 2, 4, 3, 5, 6, 7};

} // namespace

VoronoiCellPlanes::VoronoiCellPlanes(const octree::SampleField& field, const Vec3d& p, const std::vector<Vec3d>& neighbours)
{
    // (x - m) . (w - p) <= 0 with x = o + A u.
    const Vec3d o = field.index_to_world(Vec3d(0.0));
    const Vec3d A[3] = {field.index_to_world(Vec3d(1, 0, 0)) - o, field.index_to_world(Vec3d(0, 1, 0)) - o,
                        field.index_to_world(Vec3d(0, 0, 1)) - o};
    for (const Vec3d& w : neighbours) {
        const Vec3d g = w - p, m = 0.5 * (p + w);
        n.push_back(Vec3d(A[0].dot(g), A[1].dot(g), A[2].dot(g)));
        c.push_back((m - o).dot(g));
    }
}

int VoronoiCellPlanes::open_segment(const Vec3d& a, const Vec3d& b) const
{
    const Vec3d d = b - a;
    double t0 = 0, t1 = 1;
    bool closed0 = false, closed1 = false;
    for (std::size_t i = 0; i < n.size(); ++i) {
        const double s = n[i].dot(a) - c[i], r = n[i].dot(d); // s + t r <= 0
        if (r == 0) {
            if (s > 0) return 0;
            continue;
        }
        const double t = -s / r;
        if (r > 0 && t < t1) t1 = t, closed1 = true;
        if (r < 0 && t > t0) t0 = t, closed0 = true;
        if (t0 > t1) return 0;
    }
    return int(closed0) + int(closed1) - 1;
}

// Clips the triangle, remembering which edges of the clipped polygon lie on V's boundary
// (included in the piece) and which on the triangle's (not).
int VoronoiCellPlanes::open_triangle(const Vec3d& a, const Vec3d& b, const Vec3d& cc) const
{
    struct Corner {
        Vec3d p;
        bool clip_edge; // the edge from this corner to the next lies on a plane of V
    };
    std::vector<Corner> poly{{a, false}, {b, false}, {cc, false}}, next;
    for (std::size_t i = 0; i < n.size() && !poly.empty(); ++i) {
        next.clear();
        const std::size_t m = poly.size();
        bool any_out = false;
        for (const auto& q : poly)
            if (n[i].dot(q.p) - c[i] > 0) {
                any_out = true;
                break;
            }
        if (!any_out) continue;
        for (std::size_t k = 0; k < m; ++k) {
            const Corner& u = poly[k];
            const Corner& v = poly[(k + 1) % m];
            const double su = n[i].dot(u.p) - c[i], sv = n[i].dot(v.p) - c[i];
            const bool uin = su <= 0, vin = sv <= 0;
            if (uin && vin) next.push_back(u);
            else if (uin && !vin) {
                next.push_back(u);
                next.push_back({u.p + (su / (su - sv)) * (v.p - u.p), true});
            }
            else if (!uin && vin)
                next.push_back({u.p + (su / (su - sv)) * (v.p - u.p), u.clip_edge});
        }
        poly.swap(next);
    }
    if (poly.size() < 3) return 0; // empty, or a touch of measure zero
    int clip = 0, runs = 0;
    for (std::size_t k = 0; k < poly.size(); ++k) {
        clip += poly[k].clip_edge;
        runs += poly[k].clip_edge && !poly[(k + poly.size() - 1) % poly.size()].clip_edge;
    }
    if (clip == int(poly.size())) return 1; // a closed polygon inside the open triangle
    return 1 - runs;
}

int sampled_euler_characteristic(const octree::SampleField::Reader& reader, const VoronoiCellPlanes& cell,
                                 const Vec3d& lo, const Vec3d& hi, int per_voxel)
{
    const int r = per_voxel;
    // The sub-lattice, one point of margin around [lo, hi].
    int i0[3], n[3];
    for (int k = 0; k < 3; ++k) {
        i0[k] = int(std::floor(lo[k] * r)) - 1;
        n[k] = int(std::ceil(hi[k] * r)) + 1 - i0[k] + 1;
    }
    const auto at = [&](int x, int y, int z) { return (std::size_t(z) * n[1] + y) * n[0] + x; };
    std::vector<double> F(std::size_t(n[0]) * n[1] * n[2]);
    // Only the voxels T can meet in V are sampled: a voxel beyond one of V's planes (surely, so
    // every sub-cube of it is missed however it is rounded) or on which F' keeps one sign (every
    // sub-cube of it has corners of one sign) adds nothing to chi, and its sub-cubes are skipped
    // below. The sum is the same; the work follows Sigma in V, not V's box.
    const Coord v0(floor_div(i0[0], r), floor_div(i0[1], r), floor_div(i0[2], r));
    const Coord v1(floor_div(i0[0] + n[0] - 1, r), floor_div(i0[1] + n[1] - 1, r), floor_div(i0[2] + n[2] - 1, r));
    const Coord vn = v1 - v0 + Coord(1);
    const auto voxel = [&](int x, int y, int z) { return (std::size_t(z) * vn.y() + y) * vn.x() + x; };
    std::vector<char> meets(std::size_t(vn.x()) * vn.y() * vn.z(), 0);
    {
        std::vector<octree::CellFunction> tri(meets.size());
        for (int z = 0; z < vn.z(); ++z)
            for (int y = 0; y < vn.y(); ++y)
                for (int x = 0; x < vn.x(); ++x) {
                    const Coord c = v0 + Coord(x, y, z);
                    double corner[8];
                    tri[voxel(x, y, z)] = octree::cell_function(reader, c, corner);
                    meets[voxel(x, y, z)] =
                        !cell.misses_box_surely(c.asVec3d(), c.asVec3d() + Vec3d(1)) &&
                        octree::sign_on_cell_box(tri[voxel(x, y, z)], corner, Vec3d(0), Vec3d(1)) == 0;
                }
        // F at the sub-lattice points of every voxel that meets (its closed box), each read from
        // the voxel floor(point) as before, so a point shared by two voxels has one value.
        for (int vz = 0; vz < vn.z(); ++vz)
            for (int vy = 0; vy < vn.y(); ++vy)
                for (int vx = 0; vx < vn.x(); ++vx) {
                    if (!meets[voxel(vx, vy, vz)]) continue;
                    const int vv[3] = {v0.x() + vx, v0.y() + vy, v0.z() + vz};
                    int a[3], b[3]; // the voxel's sub-lattice points, clipped to the array
                    for (int k = 0; k < 3; ++k) {
                        a[k] = std::max(vv[k] * r - i0[k], 0);
                        b[k] = std::min(vv[k] * r + r - i0[k], n[k] - 1);
                    }
                    for (int z = a[2]; z <= b[2]; ++z)
                        for (int y = a[1]; y <= b[1]; ++y)
                            for (int x = a[0]; x <= b[0]; ++x) {
                                const int g[3] = {i0[0] + x, i0[1] + y, i0[2] + z};
                                int v[3];
                                double l[3];
                                for (int k = 0; k < 3; ++k) {
                                    v[k] = floor_div(g[k], r);
                                    l[k] = double(g[k] - v[k] * r) / r;
                                }
                                const auto& t = tri[voxel(v[0] - v0.x(), v[1] - v0.y(), v[2] - v0.z())];
                                F[at(x, y, z)] = t(l[0], l[1], l[2]);
                            }
                }
    }
    const auto inside = [&](std::size_t i) { return F[i] >= 0; }; // phi >= 0 is inside
    const auto index_of = [&](int x, int y, int z, int code) {
        return at(x + (code & 1), y + ((code >> 1) & 1), z + ((code >> 2) & 1));
    };
    const auto point_of = [&](int x, int y, int z, int code) {
        return Vec3d(double(i0[0] + x + (code & 1)) / r, double(i0[1] + y + ((code >> 1) & 1)) / r,
                     double(i0[2] + z + ((code >> 2) & 1)) / r);
    };
    // T's vertex on the lattice edge from corner code a to corner code b of the cube at (x,y,z).
    // Always from the lower end (the corner whose code is a subset of the other's): every
    // simplex sharing the edge then rounds the vertex the same way and agrees whether it is in V.
    const auto crossing = [&](int x, int y, int z, int a, int b) {
        if ((a & b) == b) std::swap(a, b);
        const double fa = F[index_of(x, y, z, a)], fb = F[index_of(x, y, z, b)];
        const Vec3d pa = point_of(x, y, z, a), pb = point_of(x, y, z, b);
        return pa + (fa / (fa - fb)) * (pb - pa);
    };

    long chi = 0;
    for (int z = 0; z + 1 < n[2]; ++z)
        for (int y = 0; y + 1 < n[1]; ++y)
            for (int x = 0; x + 1 < n[0]; ++x) {
                if (!meets[voxel(floor_div(i0[0] + x, r) - v0.x(), floor_div(i0[1] + y, r) - v0.y(),
                                 floor_div(i0[2] + z, r) - v0.z())])
                    continue; // adds nothing (above); its corners may be unsampled
                const bool in0 = inside(at(x, y, z));
                bool mixed = false; // T meets only sub-cubes whose corners change sign
                for (int c = 1; c < 8 && !mixed; ++c) mixed = inside(index_of(x, y, z, c)) != in0;
                if (!mixed || cell.misses_box(point_of(x, y, z, 0), point_of(x, y, z, 7))) continue;
                // Vertices of T: lattice edges {x, x + e} that change sign.
                for (const int e : kEdgeVectors)
                    if (inside(index_of(x, y, z, e)) != in0) chi += cell.contains(crossing(x, y, z, 0, e));
                // Edges of T: lattice triangles {x, x + a, x + a + b} that change sign (one segment).
                for (int a = 1; a < 8; ++a)
                    for (int b = 1; b < 8; ++b) {
                        if (a & b) continue;
                        const int s[3] = {0, a, a | b};
                        Vec3d q[2];
                        int m = 0;
                        for (int i = 0; i < 3; ++i)
                            for (int j = i + 1; j < 3; ++j)
                                if (inside(index_of(x, y, z, s[i])) != inside(index_of(x, y, z, s[j])))
                                    q[m++] = crossing(x, y, z, s[i], s[j]);
                        if (m == 2) chi += cell.open_segment(q[0], q[1]);
                    }
                // Faces of T: the six tetrahedra of the cube.
                static const int kPerm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
                for (const auto& pi : kPerm) {
                    const int v[4] = {0, 1 << pi[0], (1 << pi[0]) | (1 << pi[1]), 7};
                    int pos[4], neg[4], np = 0, nn = 0;
                    for (const int c : v) (inside(index_of(x, y, z, c)) ? pos[np++] : neg[nn++]) = c;
                    if (np == 0 || nn == 0) continue;
                    if (np == 1 || nn == 1) {
                        const int lone = np == 1 ? pos[0] : neg[0];
                        const int* other = np == 1 ? neg : pos;
                        chi += cell.open_triangle(crossing(x, y, z, lone, other[0]), crossing(x, y, z, lone, other[1]),
                                                  crossing(x, y, z, lone, other[2]));
                    }
                    else {
                        // A quad a-c, b-c, b-d, a-d: two triangles and their shared open diagonal.
                        const Vec3d ac = crossing(x, y, z, pos[0], neg[0]), bc = crossing(x, y, z, pos[1], neg[0]),
                                    bd = crossing(x, y, z, pos[1], neg[1]), ad = crossing(x, y, z, pos[0], neg[1]);
                        chi += cell.open_triangle(ac, bc, bd) + cell.open_triangle(ac, bd, ad) + cell.open_segment(ac, bd);
                    }
                }
            }
    return int(chi);
}

} // namespace isodel::mesher
