#include "octree/protective_layer.h"

#include "octree/voxel_set.h"

#include <algorithm>
#include <cmath>

namespace isodel::octree {

namespace {

/// World-space edge vectors of a cell: the images of the index axes.
std::array<Vec3d, 3> lattice_axes(const SampleField& field)
{
    const auto& xf = field.transform();
    const Vec3d o = xf.indexToWorld(Vec3d(0.0));
    std::array<Vec3d, 3> e;
    for (int a = 0; a < 3; ++a) {
        Vec3d u(0.0);
        u[a] = 1.0;
        e[a] = xf.indexToWorld(u) - o;
    }
    return e;
}

} // namespace

std::array<int, 3> layer_radius(const SampleField& field)
{
    const std::array<Vec3d, 3> e = lattice_axes(field);
    const double vol = std::abs(e[0].dot(e[1].cross(e[2])));
    std::array<int, 3> r{};
    for (int a = 0; a < 3; ++a) {
        const Vec3d& eb = e[(a + 1) % 3];
        const Vec3d& ec = e[(a + 2) % 3];
        const double h = vol / eb.cross(ec).length();                       // plane spacing
        const double R = 0.5 * std::max((eb + ec).length(), (eb - ec).length()); // covering radius bound
        r[a] = std::max(1, int(std::floor(R / h)) + 1);
    }
    return r;
}

bool orthogonal_lattice(const SampleField& field)
{
    const std::array<Vec3d, 3> e = lattice_axes(field);
    // Relative to the edge lengths, and loose enough for the rounding of a rotated transform:
    // a real shear (EMD-3001's non-orthogonal cell) is orders of magnitude above it.
    for (int a = 0; a < 3; ++a) {
        const Vec3d& p = e[a];
        const Vec3d& q = e[(a + 1) % 3];
        if (std::abs(p.dot(q)) > 1e-9 * p.length() * q.length()) return false;
    }
    return true;
}

ProtectiveLayer protective_layer(const SampleField& field, const std::vector<Coord>& crossed_cells)
{
    ProtectiveLayer out;
    out.radius = layer_radius(field);
    const auto& r = out.radius;
    out.bound_e = 1;
    out.bound_n = 1;
    for (int a = 0; a < 3; ++a) out.bound_n *= 2 * r[a] + 1;
    // An E point on an a-edge is trapped in (2 r_b) x (2 r_c) cells around the edge; report the
    // worst axis. That argument (Theorem 2) needs lattice planes orthogonal to the edge: on a
    // sheared lattice (an E point's cell can meet more than 4) only the N-point block argument holds, and an
    // E point lies in a crossed cell like any N point.
    if (orthogonal_lattice(field))
        for (int a = 0; a < 3; ++a)
            out.bound_e = std::max(out.bound_e, 4 * r[(a + 1) % 3] * r[(a + 2) % 3]);
    else
        out.bound_e = out.bound_n;

    // G: every grid point within r of a crossed cell's corners, marked in parallel over the
    // crossed cells and listed in a mask's order (voxel_set.h).
    const std::size_t block = std::size_t(2 * r[0] + 2) * (2 * r[1] + 2) * (2 * r[2] + 2);
    openvdb::CoordBBox bounds = union_of_boxes(crossed_cells.size(), [&](std::size_t i) {
        return openvdb::CoordBBox(crossed_cells[i], crossed_cells[i].offsetBy(1));
    });
    if (!bounds.empty()) {
        bounds.min() -= Coord(r[0], r[1], r[2]);
        bounds.max() += Coord(r[0], r[1], r[2]);
    }
    VoxelSet g = voxel_set(crossed_cells.size(), block, bounds, [&](std::size_t i, auto& acc) {
        const Coord c = crossed_cells[i];
        for (int z = c.z() - r[2]; z <= c.z() + 1 + r[2]; ++z)
            for (int y = c.y() - r[1]; y <= c.y() + 1 + r[1]; ++y)
                for (int x = c.x() - r[0]; x <= c.x() + 1 + r[0]; ++x) acc.setValueOn(Coord(x, y, z));
    });
    out.points = std::move(g.coords);
    out.mask = std::move(g.mask);
    return out;
}

} // namespace isodel::octree
