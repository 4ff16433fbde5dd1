// Smooth analytic shapes built in memory (no shared data needed): sphere, torus and two nested
// spheres at eps 0.5, 0.25 and 0.1 voxel. Topology is known analytically; verify certifies the
// Hausdorff bound and Delaunay conformity.
#include <catch2/catch.hpp>

#include "support/mesher_test_support.h"

using namespace isodel;

TEST_CASE("analytic shapes: topology and all guarantees at three eps", "[mesher][analytic]")
{
    const openvdb::Vec3d c(12.37, 12.11, 12.53);
    struct Shape {
        const char* name;
        std::function<double(const openvdb::Vec3d&)> f;
        std::vector<int> genera;
    };
    const std::vector<Shape> shapes = {
        {"sphere", [&](const openvdb::Vec3d& x) { return testing::sphere_f(x, c, 7.2); }, {0}},
        {"torus", [&](const openvdb::Vec3d& x) { return testing::torus_f(x, c, 6.5, 2.4); }, {1}},
        {"shell", [&](const openvdb::Vec3d& x) {
             const double r = (x - c).length();
             return std::min(r - 4.3, 8.9 - r); // inside: the shell between two spheres
         }, {0, 0}},
    };
    for (const auto& s : shapes) {
        auto grid = testing::make_grid(26, 0.5, openvdb::Vec3d(1.0, -2.0, 0.5), s.f);
        for (double eps : {0.5, 0.25, 0.1}) {
            const auto r = testing::mesh_and_verify(*grid, 0.0, Inside::Above, eps);
            INFO(s.name << " eps " << eps << "\n" << r.report.summary());
            CHECK(r.genera == s.genera);
            CHECK(r.report.passed());
        }
    }
}
