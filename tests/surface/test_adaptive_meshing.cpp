// Certified adaptive meshing (MeshOptions::adaptive, docs/adaptive.md) against the original
// volume: features smaller than a coarse cell (a handle, a blob, a neck) in a flat field
// (|grad F| = 0.1) next to a smooth sphere. A value tolerance (isodel::decimate with T equal to
// the distance budget, as if |grad F| were 1) loses each feature; the certificate keeps it, the
// grid still coarsens elsewhere, and isodel verify passes the mesh against the original volume.
#include <catch2/catch.hpp>

#include "support/mesher_test_support.h"

#include <isodel/adaptive.h>
#include <isodel/errors.h>

#include <cmath>
#include <functional>

using namespace isodel;

namespace {

using Vec3d = openvdb::Vec3d;

struct Feature {
    const char* name;
    std::function<double(const Vec3d&)> sdf; ///< signed distance, positive inside, about (0,0,0)
    std::vector<int> genera;                 ///< of the whole level set, with the sphere
};

double torus_sdf(const Vec3d& p, double R, double r)
{
    const double q = std::sqrt(p.x() * p.x() + p.y() * p.y()) - R;
    return r - std::sqrt(q * q + p.z() * p.z());
}

std::vector<Feature> features()
{
    return {
        {"blob", [](const Vec3d& p) { return 1.3 - p.length(); }, {0, 0}},
        {"handle", [](const Vec3d& p) { return torus_sdf(p, 1.7, 0.65); }, {0, 1}},
        // The rod's axis runs through samples (y = 21, z = 19: not corners of coarse cells): the fine grid keeps
        // it, 0.03 above v on the axis.
        {"neck", [](const Vec3d& q) {
             const Vec3d p = q + Vec3d(0, -0.7, 0.6), a(4.0, 0, 0);
             const double balls = std::max(1.4 - (p - a).length(), 1.4 - (p + a).length());
             const double rod = std::min(0.3 - std::sqrt(p.y() * p.y() + p.z() * p.z()), 4.0 - std::abs(p.x()));
             return std::max(balls, rod);
         }, {0, 0}},
    };
}

// A sphere of radius 8 (|grad F| = 1) and the feature scaled to |grad F| = 0.1, in a 40^3 grid.
openvdb::FloatGrid::Ptr scene(const Feature& f)
{
    const Vec3d sphere(12.3, 20.2, 19.7), at(29.4, 20.3, 19.6);
    return testing::make_grid(40, 1.0, Vec3d(0.0), [&](const Vec3d& x) {
        return std::max(8.0 - (x - sphere).length(), 0.1 * f.sdf(x - at));
    });
}

MeshOptions options(double eps_voxels)
{
    MeshOptions mo;
    mo.isovalue = 0;
    mo.inside = Inside::Above;
    mo.eps_voxels = eps_voxels;
    return mo;
}

std::vector<int> genera_of(const MeshResult& r)
{
    std::vector<int> g;
    for (const auto& c : r.stats.components) g.push_back(c.genus);
    std::sort(g.begin(), g.end());
    return g;
}

} // namespace

TEST_CASE("adaptive meshing: a handle, a blob and a neck smaller than a coarse cell keep their topology",
          "[mesher][adaptive]")
{
    for (const Feature& f : features()) {
        INFO(f.name);
        const auto grid = scene(f);
        // The fine grid resolves the feature: the uniform mesh has the expected topology.
        const auto uniform = testing::mesh_and_verify(*grid, options(0.5));
        REQUIRE(uniform.report.passed());
        REQUIRE(uniform.genera == f.genera);

        // Without the certificate: a value tolerance equal to the distance budget loses it.
        DecimateOptions d;
        d.tolerance = 0.25;
        const DecimateResult dec = decimate(*grid, d);
        REQUIRE(dec.histogram.size() >= 3); // it did coarsen
        std::vector<int> lost;
        try {
            lost = genera_of(mesh_isosurface(dec.volume, options(0.25)));
        } catch (const Error&) {
            lost = {-1}; // no mesh at all is a loss too
        }
        CHECK(lost != f.genera);

        // With it: the same budget (adaptive_share 0.5 of eps 0.5), verified against the original.
        for (int threads : {1, 2}) {
            MeshOptions mo = options(0.5);
            mo.adaptive = true;
            mo.adaptive_min_saving = 0; // on the octree: the certificate is what is tested
            mo.threads = threads;
            const auto r = testing::mesh_and_verify(*grid, mo);
            INFO("threads " << threads << "\n" << r.report.summary());
            CHECK(r.report.passed());
            CHECK(r.genera == f.genera);
            const AdaptiveStats& a = r.mesh.stats.adaptive;
            CHECK(a.used);
            CHECK(a.meshed_on_octree);
            CHECK(a.leaves_per_level.size() >= 3); // coarse cells elsewhere
            CHECK(a.distance_world <= a.eps_coarsening_world);
            CHECK(a.eps_meshing_world == Approx(0.5 - a.distance_world));
        }
    }
}

TEST_CASE("adaptive meshing: the same mesh at 1 and 2 threads, refused combinations", "[mesher][adaptive]")
{
    const auto grid = scene(features()[1]);
    MeshOptions mo = options(0.5);
    mo.adaptive = true;
    mo.adaptive_min_saving = 0;
    mo.threads = 1;
    const MeshResult one = mesh_isosurface(*grid, mo);
    mo.threads = 2;
    const MeshResult two = mesh_isosurface(*grid, mo);
    CHECK(one.surface.vertices == two.surface.vertices);
    CHECK(one.surface.triangles == two.surface.triangles);

    MeshOptions blocks = mo;
    blocks.block_voxels = 16;
    CHECK_THROWS_AS(mesh_isosurface(*grid, blocks), InvalidInput);
    CHECK_THROWS_AS(check_mesh_options(blocks), InvalidInput);
    MeshOptions share = mo;
    share.adaptive_share = 1.0;
    CHECK_THROWS_AS(check_mesh_options(share), InvalidInput);
    for (double saving : {-0.1, 1.0}) {
        MeshOptions bad = mo;
        bad.adaptive_min_saving = saving;
        CHECK_THROWS_AS(check_mesh_options(bad), InvalidInput);
    }
    DecimateOptions d;
    d.tolerance = 0.01;
    CHECK_THROWS_AS(mesh_isosurface(decimate(*grid, d).volume, mo), InvalidInput);
}

TEST_CASE("adaptive meshing, seeds from the octree and F from the input: the features keep their topology",
          "[mesher][adaptive]")
{
    // AdaptiveField::Input (docs/adaptive.md "Seeds from the octree"): the whole eps goes to the
    // mesher, the octree gives E and G only, and its certificate keeps an E point on every
    // component (the blob, the handle's ring, the neck's rod sit inside would-be coarse cells).
    for (const Feature& f : features()) {
        INFO(f.name);
        const auto grid = scene(f);
        MeshOptions mo = options(0.5);
        mo.adaptive = true;
        mo.adaptive_field = AdaptiveField::Input;
        mo.adaptive_min_saving = 0;
        const auto r = testing::mesh_and_verify(*grid, mo);
        INFO(r.report.summary());
        CHECK(r.report.passed());
        CHECK(r.genera == f.genera);
        const AdaptiveStats& a = r.mesh.stats.adaptive;
        CHECK(a.meshed_on_octree);
        CHECK(a.leaves_per_level.size() >= 3); // coarse cells elsewhere
        CHECK(a.eps_coarsening_world == 0.0);
        CHECK(a.eps_meshing_world == Approx(0.5));
        CHECK(a.e_octree < a.e_uniform);
    }
}
