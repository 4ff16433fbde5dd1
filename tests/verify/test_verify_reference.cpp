// Reference topology of Sigma (check 1) on analytic volumes built in memory and on the single-cell
// ambiguity cases and random volumes of ../shared/data (manifest expected_topology). The analytic
// and larger volumes of ../shared/data are in tests/corpus/test_verify_manifest_topology.cpp.
#include <catch2/catch.hpp>

#include "support/skip.h"

#include "support/verify_test_support.h"

#include "octree/critical_values.h"

#include <isodel/verify.h>

#include <algorithm>
#include <array>

using namespace isodel;
using openvdb::Vec3d;

namespace {

std::vector<int> genera(const ReferenceTopologyReport& r)
{
    std::vector<int> g;
    for (const auto& c : r.components) g.push_back(c.genus);
    return g;
}

} // namespace

TEST_CASE("reference topology: analytic volumes in memory", "[verify][reference]")
{
    const Vec3d c(12.3, 12.6, 12.1);
    SECTION("sphere")
    {
        auto g = testing::make_grid(26, 1.0, Vec3d(0.0), [&](const Vec3d& x) { return testing::sphere_f(x, c, 7.0); });
        const auto r = reference_topology(*g, 0.0, Inside::Above);
        CHECK(r.determined);
        CHECK(genera(r) == std::vector<int>{0});
        CHECK(r.components[0].euler == 2);
    }
    SECTION("torus, inside below (sign flipped)")
    {
        auto g = testing::make_grid(26, 0.1, Vec3d(0.0), [&](const Vec3d& x) { return -testing::torus_f(x, c, 7.0, 2.5); }, 1.0f);
        const auto r = reference_topology(*g, 0.0, Inside::Below);
        CHECK(r.determined);
        CHECK(genera(r) == std::vector<int>{1});
    }
    SECTION("two spheres and a hollow shell")
    {
        auto g = testing::make_grid(40, 1.0, Vec3d(0.0), [&](const Vec3d& x) {
            const double a = testing::sphere_f(x, Vec3d(10.2, 10.1, 10.3), 6.0);
            const double shell = std::min(testing::sphere_f(x, Vec3d(27.3, 26.8, 27.1), 9.0),
                                          -testing::sphere_f(x, Vec3d(27.3, 26.8, 27.1), 5.0));
            return std::max(a, shell);
        });
        const auto r = reference_topology(*g, 0.0, Inside::Above);
        CHECK(r.determined);
        CHECK(genera(r) == std::vector<int>{0, 0, 0});
    }
    SECTION("a blob smaller than a voxel around one sample")
    {
        auto g = testing::make_grid(6, 1.0, Vec3d(0.0), [&](const Vec3d& x) { return x == Vec3d(3, 3, 3) ? 0.2 : -1.0; });
        const auto r = reference_topology(*g, 0.0, Inside::Above);
        CHECK(r.determined);
        CHECK(genera(r) == std::vector<int>{0});
    }
}

TEST_CASE("reference topology: single-cell cases and random volumes of ../shared/data", "[verify][reference]")
{
    const auto manifest = testing::read_manifest();
    if (!manifest.is_array()) {
        ISODEL_SKIP("../shared/data not found at " << testing::shared_data() << ": test skipped");
    }
    int checked = 0, undetermined = 0;
    for (const auto& e : manifest) {
        const std::string file = testing::json_string(e, "file");
        const std::string cat = testing::json_string(e, "category");
        if (testing::json_string(e, "format") != "vdb" || (cat != "mc-ambiguity-cell" && cat != "random")) continue;
        if (!testing::json_has(e, "expected_topology")) continue;
        auto grid = testing::read_vdb(testing::shared_data() + "/" + file, testing::json_string(e, "grid_name"));
        const Inside inside = testing::json_string(e, "inside") == "below" ? Inside::Below : Inside::Above;
        const auto r = reference_topology(*grid, testing::json_number(e, "isovalue"), inside, 4, 32);
        std::vector<int> expected;
        for (const auto& v : e.at("expected_topology").at("genus")) expected.push_back(v.get<int>());
        std::sort(expected.begin(), expected.end());
        INFO(file << " refinements " << r.refinements.size() << " last R " << r.refinements.back());
        if (!r.determined) ++undetermined;
        CHECK(r.determined);
        CHECK(genera(r) == expected);
        ++checked;
    }
    INFO("checked " << checked << ", undetermined " << undetermined);
    CHECK(checked >= 40);
}

TEST_CASE("reference topology: a saddle 1e-5 from v inside one cell is decided exactly", "[verify][reference]")
{
    // Marching cubes case 4: two opposite corners of one cell above v. The cell's interior saddle
    // s decides whether their blobs join through a tube (s above v: one component) or not (two).
    // With v = s -/+ 1e-5 the tube is ~3e-3 voxel wide: a uniform R x lattice cannot tell the two
    // apart before R ~ 300 (its samples near s differ by 2e-5 between the cases); the plane
    // through the saddle makes it a lattice vertex whose sign is exact (refined_lattice.h).
    const float a = 2.0f, b = 3.3f;
    auto grid = openvdb::FloatGrid::create(-1.f);
    grid->getAccessor().setValueOn(openvdb::Coord(1, 1, 1), a);
    grid->getAccessor().setValueOn(openvdb::Coord(2, 2, 2), b);
    const std::array<double, 8> corners = {a, -1, -1, -1, -1, -1, -1, b};
    octree::CellCritical pts[2];
    REQUIRE(octree::cell_critical_points(corners, pts) == 1);
    const double s = pts[0].value;
    INFO("saddle at (" << pts[0].x << ", " << pts[0].y << ", " << pts[0].z << "), value " << s);
    REQUIRE(std::abs(pts[0].x - 0.5) > 0.01); // off the centre, where even R would sample it
    for (double delta : {1e-5, -1e-5}) {
        const auto r = reference_topology(*grid, s - delta, Inside::Above);
        INFO("v = s - " << delta);
        CHECK(r.determined);
        CHECK(r.critical_planes >= 3);
        CHECK(r.components.size() == (delta > 0 ? 1u : 2u));
        CHECK(genera(r) == std::vector<int>(r.components.size(), 0));
    }
}
