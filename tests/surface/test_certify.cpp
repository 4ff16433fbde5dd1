// MeshOptions::certify (isodel mesh --certify): the surface is checked by the verifier before it
// is returned, and a surface that fails the check, or a run stopped by one of its bounds, is
// refused with GuaranteeViolated. These tests pin down that a certified run returns exactly the
// uncertified mesh when it verifies (volumes the crease cut before the face slabs got wrong
// among them) and that a refused run says why.
#include <catch2/catch.hpp>

#include "support/mesher_test_support.h"
#include "support/verify_test_support.h"

#include <isodel/errors.h>

#include <string>

using namespace isodel;

namespace {

MeshOptions options_at(double eps_voxels, bool certify)
{
    MeshOptions mo;
    mo.isovalue = 0.0;
    mo.inside = Inside::Above;
    mo.eps_voxels = eps_voxels;
    mo.certify = certify;
    return mo;
}

} // namespace

TEST_CASE("certify: a mesh that verifies comes back unchanged, counted as verified", "[mesher][certify]")
{
    // Property seeds 347 and 719 (plain, n 5; wrong under the old crease cut), plain 7, and a
    // quantized n 4 volume at eps 0.25.
    const struct {
        int n;
        unsigned seed;
        bool quantized;
        double eps;
    } cases[] = {{5, 347, false, 0.5}, {5, 719, false, 0.5}, {5, 7, false, 0.5}, {4, 10, true, 0.25}};
    for (const auto& c : cases) {
        INFO("n " << c.n << " seed " << c.seed << (c.quantized ? " quantized" : "") << " eps " << c.eps);
        const auto grid = testing::random_volume(c.n, c.seed, c.quantized);
        const auto plain = testing::mesh_and_verify(*grid, options_at(c.eps, false));
        INFO(plain.report.summary());
        CHECK(plain.report.passed());
        const auto certified = testing::mesh_and_verify(*grid, options_at(c.eps, true));
        CHECK(certified.report.passed());
        CHECK(certified.mesh.stats.certify_attempts == 1);
        CHECK(plain.mesh.stats.certify_attempts == 0);
        CHECK(certified.mesh.surface.vertices == plain.mesh.surface.vertices);
        CHECK(certified.mesh.surface.triangles == plain.mesh.surface.triangles);
        CHECK(certified.mesh.stats.seconds.count("certify") == 1);
    }
}

TEST_CASE("certify: a run stopped by a bound is refused and says which", "[mesher][certify]")
{
    MeshOptions mo = options_at(0.5, true);
    mo.max_points = 1;
    try {
        mesh_isosurface(*testing::random_volume(5, 719, false), mo);
        FAIL("a run capped at one inserted point should not certify");
    } catch (const GuaranteeViolated& e) {
        const std::string what = e.what();
        INFO(what);
        CHECK(what.find("point bound") != std::string::npos);
    }
}
