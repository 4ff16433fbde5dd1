// The CBP_VF / CBP_VC checks keep each vertex's verdict and re-examine only the vertices whose
// restricted star changed (ViolationFinder, src/closed_ball/closed_ball.h; FacetCache's stars,
// src/closed_ball/restricted_facets.h). With the self-checks on (src/self_checks.h), every round also examines
// every vertex from scratch and throws if a kept verdict is stale. Random volumes go through
// every violation class, CBP_VE cascades and Hausdorff refinement included; their meshes must
// also verify.
#include <catch2/catch.hpp>

#include "refinement/hausdorff_refinement.h"
#include "self_checks.h"
#include "support/mesher_test_support.h"

using namespace isodel;

TEST_CASE("closed ball checks: kept verdicts equal a fresh examination of every vertex", "[closed-ball]")
{
    const mesher::SelfChecksOn on;
    for (unsigned seed = 1; seed <= 8; ++seed)
        for (const double eps : {0.5, 0.1}) {
            const auto grid = testing::random_volume(4, seed, false);
            INFO("random 4^3 volume, seed " << seed << ", eps " << eps << " voxel");
            testing::MeshAndVerify r;
            REQUIRE_NOTHROW(r = testing::mesh_and_verify(*grid, 0.0, Inside::Above, eps));
            INFO(r.report.summary());
            CHECK(r.report.passed());
            CHECK(r.mesh.stats.n_topology > 0);
        }
}

TEST_CASE("crease check: kept triangles and the block filter equal a fresh computation", "[closed-ball][crease]")
{
    // Random volumes at a fine eps take several crease rounds, the later ones rechecking a few
    // cells of hundreds: there the block filter is on, and with the self-checks on
    // each call recomputes the triangles it kept and the triangles near the cells to check.
    const mesher::SelfChecksOn on;
    const std::size_t before = mesher::HausdorffRefinement::crease_block_filter_checks();
    for (unsigned seed = 1; seed <= 3; ++seed) {
        const auto grid = testing::random_volume(10, seed, false);
        INFO("random 10^3 volume, seed " << seed << ", eps 0.1 voxel");
        testing::MeshAndVerify r;
        REQUIRE_NOTHROW(r = testing::mesh_and_verify(*grid, 0.0, Inside::Above, 0.1));
        INFO(r.report.summary());
        CHECK(r.report.passed());
    }
    INFO("block filter checks: " << mesher::HausdorffRefinement::crease_block_filter_checks() - before);
    CHECK(mesher::HausdorffRefinement::crease_block_filter_checks() > before);
}
