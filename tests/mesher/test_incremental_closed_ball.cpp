// The CBP_VF / CBP_VC checks keep each vertex's verdict and re-examine only the vertices whose
// restricted star changed (ViolationFinder, src/mesher/closed_ball.h; FacetCache's stars,
// src/mesher/restricted_facets.h). With ISODEL_CHECK_INCREMENTAL set, every round also examines
// every vertex from scratch and throws if a kept verdict is stale. Random volumes go through
// every violation class, CBP_VE cascades and Hausdorff refinement included; their meshes must
// also verify.
#include <catch2/catch.hpp>

#include "mesher_test_support.h"

#include <cstdlib>

using namespace isodel;

namespace {

struct SelfCheck {
    SelfCheck() { setenv("ISODEL_CHECK_INCREMENTAL", "1", 1); }
    ~SelfCheck() { unsetenv("ISODEL_CHECK_INCREMENTAL"); }
};

} // namespace

TEST_CASE("closed ball checks: kept verdicts equal a fresh examination of every vertex", "[closed-ball]")
{
    const SelfCheck on;
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
