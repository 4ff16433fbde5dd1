// Optional triangle quality (MeshOptions::facet_angle_deg, `--facet-angle`): after every guarantee
// holds, restricted facets whose smallest angle is under the bound get their surface point; the
// mesh must still verify (topology, eps, Delaunay conformity) and, when the refinement says
// "met", every triangle of M has its smallest angle at or above the bound.
#include <catch2/catch.hpp>

#include "support/mesher_test_support.h"
#include "support/verify_test_support.h"

#include <isodel/volume.h>

#include <cmath>

using namespace isodel;

namespace {

double smallest_angle_deg(const SurfaceMesh& m)
{
    double lo = 180;
    for (const auto& t : m.triangles)
        for (int i = 0; i < 3; ++i) {
            const auto& a = m.vertices[t[i]];
            const auto& b = m.vertices[t[(i + 1) % 3]];
            const auto& c = m.vertices[t[(i + 2) % 3]];
            double u[3], v[3], uu = 0, vv = 0, uv = 0;
            for (int k = 0; k < 3; ++k) {
                u[k] = b[k] - a[k];
                v[k] = c[k] - a[k];
                uu += u[k] * u[k];
                vv += v[k] * v[k];
                uv += u[k] * v[k];
            }
            lo = std::min(lo, std::acos(std::clamp(uv / std::sqrt(uu * vv), -1.0, 1.0)) * 180.0 / M_PI);
        }
    return lo;
}

testing::MeshAndVerify mesh_with_angle(const openvdb::FloatGrid& grid, Inside inside, double eps_voxels, double angle)
{
    MeshOptions mo;
    mo.inside = inside;
    mo.eps_voxels = eps_voxels;
    mo.facet_angle_deg = angle;
    return testing::mesh_and_verify(grid, mo);
}

} // namespace

TEST_CASE("facet angle: the bundled torus reaches 20 degrees and still verifies", "[mesher][facet_angle]")
{
    const Volume vol = read_volume(std::string(ISODEL_TEST_DATA) + "/torus.vdb");
    const auto plain = mesh_with_angle(*vol.grid, vol.default_inside, 0.5, 0);
    const auto refined = mesh_with_angle(*vol.grid, vol.default_inside, 0.5, 20);
    INFO("without: " << smallest_angle_deg(plain.mesh.surface) << " deg, " << plain.mesh.stats.vertices
                     << " vertices; with 25: " << smallest_angle_deg(refined.mesh.surface) << " deg, "
                     << refined.mesh.stats.vertices << " vertices, stop " << to_string(refined.mesh.stats.facet_angle_stop));
    CHECK(plain.mesh.stats.facet_angle_stop == FacetAngleStop::Off);
    CHECK(plain.mesh.stats.n_facet_angle == 0);
    CHECK(smallest_angle_deg(plain.mesh.surface) < 20); // so the option has work to do
    REQUIRE(refined.report.passed());
    CHECK(refined.genera == std::vector<int>{1});
    CHECK(refined.mesh.stats.facet_angle_stop == FacetAngleStop::Met);
    CHECK(refined.mesh.stats.n_facet_angle > 0);
    CHECK(smallest_angle_deg(refined.mesh.surface) >= 20 - 1e-9);
}

TEST_CASE("facet angle: random volumes keep every guarantee whatever stops the refinement", "[mesher][facet_angle]")
{
    for (unsigned seed = 1; seed <= 6; ++seed) {
        const auto grid = testing::random_volume(5, seed, seed % 2 == 0);
        const auto r = mesh_with_angle(*grid, Inside::Above, 0.25, 25);
        INFO("seed " << seed << ": " << r.mesh.stats.vertices << " vertices, stop " << to_string(r.mesh.stats.facet_angle_stop)
                     << ", smallest angle " << smallest_angle_deg(r.mesh.surface));
        CHECK(r.mesh.stats.facet_angle_stop != FacetAngleStop::Off); // the pass ran and said why it stopped
        if (r.mesh.stats.facet_angle_stop == FacetAngleStop::Met) CHECK(smallest_angle_deg(r.mesh.surface) >= 25 - 1e-9);
        CHECK(r.report.passed());
    }
}
