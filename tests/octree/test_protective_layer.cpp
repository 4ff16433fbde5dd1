// The voxel bound the protective layer G is held to (octree/protective_layer.h): Theorem 2's
// 4-cell trap for E points needs lattice planes orthogonal to the edge, so a sheared map
// (EMD-3001's cell) must report the N-point block bound for E points too; the mesher's measured
// maximum must stay within whatever bound is reported.
#include "octree/protective_layer.h"
#include "octree/sample_field.h"

#include <isodel/mesh.h>

#include <catch2/catch.hpp>

#include <cmath>

using namespace isodel;

namespace {

/// A ball of radius 3.3 voxels in index space, sampled as a density (inside above 0).
openvdb::FloatGrid::Ptr ball(const openvdb::math::Transform::Ptr& xf)
{
    auto grid = openvdb::FloatGrid::create(-1.f);
    grid->setTransform(xf);
    auto acc = grid->getAccessor();
    for (int z = -5; z <= 5; ++z)
        for (int y = -5; y <= 5; ++y)
            for (int x = -5; x <= 5; ++x)
                acc.setValueOn({x, y, z}, float(3.3 - std::sqrt(double(x * x + y * y + z * z))));
    return grid;
}

openvdb::math::Transform::Ptr sheared()
{
    // EMD-3001-like: the c axis leans 20 degrees towards a, and the voxels are not cubes.
    openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
    m.setRow(0, openvdb::math::Vec4d(0.45, 0, 0, 0));
    m.setRow(1, openvdb::math::Vec4d(0, 0.39, 0, 0));
    m.setRow(2, openvdb::math::Vec4d(0.46 * std::sin(0.35), 0, 0.46 * std::cos(0.35), 0));
    return openvdb::math::Transform::createLinearTransform(m);
}

} // namespace

TEST_CASE("protective layer: the E-point bound is Theorem 2's 4 cells only on orthogonal lattices",
          "[octree][voxel-bound]")
{
    const auto cubic = ball(openvdb::math::Transform::createLinearTransform(0.5));
    const auto aniso = ball(openvdb::math::Transform::createLinearTransform(
        openvdb::math::Mat4d(0.5, 0., 0., 0., 0., 0.6, 0., 0., 0., 0., 0.55, 0., 0., 0., 0., 1.)));
    const auto shear = ball(sheared());
    // Rotated but orthogonal: must not count as sheared (orthogonality, not axis alignment).
    auto rotated_xf = openvdb::math::Transform::createLinearTransform(0.5);
    rotated_xf->postRotate(0.3, openvdb::math::Z_AXIS);
    rotated_xf->postRotate(0.2, openvdb::math::X_AXIS);
    const auto rotated = ball(rotated_xf);
    const octree::SampleField fc(cubic, 0.0, Inside::Above), fa(aniso, 0.0, Inside::Above);
    const octree::SampleField fs(shear, 0.0, Inside::Above), fr(rotated, 0.0, Inside::Above);
    CHECK(octree::orthogonal_lattice(fc));
    CHECK(octree::orthogonal_lattice(fa));
    CHECK(octree::orthogonal_lattice(fr));
    CHECK_FALSE(octree::orthogonal_lattice(fs));
    const auto lc = octree::protective_layer(fc, std::vector<openvdb::Coord>{});
    const auto ls = octree::protective_layer(fs, std::vector<openvdb::Coord>{});
    CHECK(lc.bound_e == 4);
    CHECK(lc.bound_n == 27);
    CHECK(ls.bound_e == ls.bound_n);
    CHECK(ls.bound_n == 27); // a one-voxel layer still covers this shear (layer_radius)
    CHECK(octree::protective_layer(fr, std::vector<openvdb::Coord>{}).bound_e == 4);
}

TEST_CASE("protective layer: on a sheared lattice the measured E-point maximum stays within the reported bound",
          "[octree][voxel-bound]")
{
    MeshOptions mo;
    mo.isovalue = 0.0;
    mo.inside = Inside::Above;
    mo.eps_voxels = 0.5;
    const auto r = mesh_isosurface(*ball(sheared()), mo);
    INFO("E: " << r.stats.max_cells_e << " of " << r.stats.bound_e << ", N: " << r.stats.max_cells_n << " of "
               << r.stats.bound_n);
    CHECK(r.stats.max_cells_e > 4); // the sheared cell does break the cubic 4-cell trap
    CHECK(r.stats.max_cells_e <= r.stats.bound_e);
    CHECK(r.stats.max_cells_n <= r.stats.bound_n);
    CHECK(r.stats.bound_repairs == 0);
}
