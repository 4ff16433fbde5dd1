// MeshOptions::adaptive_min_saving: the octree's share of eps must buy fewer grid-edge crossings.
// Where it keeps Sigma's cells fine, the surface is meshed on the input's own grid with the
// whole eps, and the mesh is exactly the one without adaptive; where Sigma coarsens (a smooth
// sphere), it is meshed on the octree. The decision follows the E counts it reports: a bound
// before building (then the octree is not built at all) and the octree's own count after.
#include <catch2/catch.hpp>

#include "support/mesher_test_support.h"

#include <isodel/adaptive.h>
#include <isodel/mesh.h>

#include <cmath>

using namespace isodel;

namespace {

using Vec3d = openvdb::Vec3d;

MeshOptions adaptive_options(double min_saving)
{
    MeshOptions mo;
    mo.isovalue = 0;
    mo.inside = Inside::Above;
    mo.eps_voxels = 0.5;
    mo.adaptive = true;
    mo.adaptive_min_saving = min_saving;
    return mo;
}

/// The same volume meshed without adaptive: what a run on the input's grid must reproduce.
MeshResult uniform_mesh(const openvdb::FloatGrid& grid)
{
    MeshOptions plain = adaptive_options(0);
    plain.adaptive = false;
    return mesh_isosurface(grid, plain);
}

/// A sphere of radius \p r voxels, a distance field (|grad F| = 1), plus \p bumps of amplitude
/// 0.3 voxel at a 2.5-voxel wavelength: the bumps keep Sigma's cells fine.
openvdb::FloatGrid::Ptr sphere(double r, bool bumps)
{
    const double c = r + 4.3;
    return testing::make_grid(int(2 * r + 9), 1.0, Vec3d(0.0), [&](const Vec3d& x) {
        const Vec3d p = x - Vec3d(c, c + 0.17, c - 0.11);
        const double b = bumps ? 0.3 * std::sin(2.5 * p.x()) * std::sin(2.5 * p.y()) * std::sin(2.5 * p.z()) : 0.0;
        return r - p.length() + b;
    });
}

} // namespace

TEST_CASE("adaptive min saving: an octree that saves too few crossings gives way to the input's grid",
          "[mesher][adaptive]")
{
    const auto grid = sphere(14, true);
    const MeshResult uniform = uniform_mesh(*grid);

    const MeshResult r = mesh_isosurface(*grid, adaptive_options(0.1));
    const AdaptiveStats& a = r.stats.adaptive;
    INFO("E uniform " << a.e_uniform << ", E octree " << a.e_octree << ", removable " << a.e_removable);
    REQUIRE(a.used);
    CHECK(a.e_uniform == uniform.stats.e_points);
    // Decided before building: the bound falls short, and nothing was built.
    CHECK(double(a.e_removable) < 0.1 * double(a.e_uniform));
    CHECK(a.e_octree == a.e_uniform);
    CHECK(a.cells_certified == 0);
    CHECK(a.leaves_per_level.size() == 1); // the grid meshed: the input's
    CHECK_FALSE(a.meshed_on_octree);
    CHECK(a.distance_world == 0);
    CHECK(a.eps_meshing_world == Approx(0.5));
    // Exactly the mesh without adaptive.
    CHECK(r.surface.vertices == uniform.surface.vertices);
    CHECK(r.surface.triangles == uniform.surface.triangles);
    // The octree saved is the input's grid: no coarse levels.
    REQUIRE(r.adaptive_grid);
    CHECK(r.adaptive_grid->levels.size() <= 1);

    // Forced onto the octree, the same volume meshes there (and the E count is the mesher's).
    const MeshResult forced = mesh_isosurface(*grid, adaptive_options(0));
    CHECK(forced.stats.adaptive.meshed_on_octree);
    CHECK(forced.stats.adaptive.e_octree == forced.stats.e_points);
    CHECK(forced.stats.adaptive.e_uniform == a.e_uniform);
    CHECK(double(forced.stats.adaptive.e_octree) > 0.9 * double(a.e_uniform)); // it saves little indeed
}

TEST_CASE("adaptive min saving: the bound before building, and the count after it", "[mesher][adaptive]")
{
    const auto grid = sphere(20, false);
    const MeshResult uniform = uniform_mesh(*grid);
    const MeshResult forced = mesh_isosurface(*grid, adaptive_options(0));
    const AdaptiveStats& f = forced.stats.adaptive;
    const double saved = double(f.e_uniform) - double(f.e_octree);
    const MeshResult bounded = mesh_isosurface(*grid, adaptive_options(0.1));
    const std::size_t removable = bounded.stats.adaptive.e_removable;
    INFO("E uniform " << f.e_uniform << ", E octree " << f.e_octree << ", removable " << removable);
    REQUIRE(f.meshed_on_octree);
    CHECK(double(removable) >= saved); // a bound on what the octree saved
    REQUIRE(double(removable) > saved + 2);

    // A share between the two: the bound lets the octree be built, its count then refuses it.
    const double share = (saved + double(removable)) / 2 / double(f.e_uniform);
    const MeshResult r = mesh_isosurface(*grid, adaptive_options(share));
    const AdaptiveStats& a = r.stats.adaptive;
    CHECK(a.cells_certified == f.cells_certified); // built
    CHECK(a.e_octree == f.e_octree);
    CHECK(a.leaves_per_level.size() == 1); // but the grid meshed is the input's
    CHECK(r.adaptive_grid->levels.size() <= 1);
    CHECK_FALSE(a.meshed_on_octree);
    CHECK(r.surface.vertices == uniform.surface.vertices);
    CHECK(r.surface.triangles == uniform.surface.triangles);
}

TEST_CASE("adaptive min saving: a smooth sphere coarsens at Sigma and meshes on the octree", "[mesher][adaptive]")
{
    const auto grid = sphere(20, false);
    const auto r = testing::mesh_and_verify(*grid, adaptive_options(0.1));
    const AdaptiveStats& a = r.mesh.stats.adaptive;
    INFO("E uniform " << a.e_uniform << ", E octree " << a.e_octree << "\n" << r.report.summary());
    CHECK(r.report.passed());
    CHECK(a.meshed_on_octree);
    CHECK(double(a.e_octree) <= 0.9 * double(a.e_uniform));
    CHECK(a.e_octree == r.mesh.stats.e_points);
    CHECK(a.eps_meshing_world == Approx(0.5 - a.distance_world));
}
