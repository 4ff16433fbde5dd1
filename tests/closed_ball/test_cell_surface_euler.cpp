// The sampled Euler characteristic of Sigma n Vor(p) (src/closed_ball/cell_surface_euler.h), the
// fallback that finds a handle inside one Voronoi cell: counted on shapes whose pieces are
// known, with box-shaped Voronoi cells (six neighbours at +-2h along the axes make the cube of
// half-size h around p). The grid has a 0.5 world-unit voxel, so the counts are also checked
// through a transform that is not the identity.
#include <catch2/catch.hpp>

#include "closed_ball/cell_surface_euler.h"
#include "support/verify_test_support.h"

using namespace isodel;
using openvdb::Vec3d;

namespace {

int chi_in_box(const openvdb::FloatGrid::Ptr& grid, const Vec3d& centre_index, double half_index)
{
    const octree::SampleField field(grid, 0.0, Inside::Above);
    const octree::SampleField::Reader reader(field);
    const Vec3d p = field.index_to_world(centre_index);
    std::vector<Vec3d> nb;
    for (int a = 0; a < 3; ++a)
        for (const double s : {-1.0, 1.0}) {
            Vec3d q = centre_index;
            q[a] += 2 * s * half_index;
            nb.push_back(field.index_to_world(q));
        }
    const mesher::VoronoiCellPlanes cell(field, p, nb);
    return mesher::sampled_euler_characteristic(reader, cell, centre_index - Vec3d(half_index),
                                                centre_index + Vec3d(half_index), 16);
}

} // namespace

TEST_CASE("cell Euler characteristic: sphere, hemisphere, torus, torus minus a disk", "[mesher][closed_ball]")
{
    const Vec3d c(12.3, 11.7, 12.1); // off the lattice: no sample at the isovalue
    const auto sphere = testing::make_grid(26, 0.5, Vec3d(0.0), [&](const Vec3d& x) { return testing::sphere_f(x, c, 5.0); });
    CHECK(chi_in_box(sphere, c, 8.0) == 2);                       // whole sphere
    CHECK(chi_in_box(sphere, c - Vec3d(0, 0, 8.0), 8.0) == 1);    // lower half: a disk
    CHECK(chi_in_box(sphere, c + Vec3d(20.0, 0, 0), 8.0) == 0);   // misses it

    const auto torus = testing::make_grid(26, 0.5, Vec3d(0.0), [&](const Vec3d& x) { return testing::torus_f(x, c, 6.0, 2.2); });
    CHECK(chi_in_box(torus, c, 10.0) == 0); // whole torus
    // The cube's +x face at c.x + 7.5 cuts a cap off the tube's outer side (which reaches
    // c.x + 8.2): a torus minus a disk, the shape CBP_VC's one-cycle test cannot see.
    CHECK(chi_in_box(torus, c - Vec3d(2.5, 0, 0), 10.0) == -1);
    // The cube's +x face through the axis keeps half the torus: a tube bent in a U, an annulus.
    CHECK(chi_in_box(torus, c - Vec3d(10.0, 0, 0), 10.0) == 0);
}
