// MeshStats says where the refinement's time goes ("the stats JSON's phase times make clear
// where time goes"): refinement_seconds splits closed_ball + refine into its steps, each
// counted once (their sum stays within the two phases), most of the two phases accounted for,
// and every step that ran on a random volume (which exercises every refinement phase) shows time.
#include <catch2/catch.hpp>

#include "support/mesher_test_support.h"

#include <isodel/mesh.h>

using namespace isodel;

TEST_CASE("refinement_seconds splits the closed-ball and refine phases by step", "[mesher][stats]")
{
    for (const double angle : {0.0, 20.0}) {
        INFO("facet angle " << angle);
        MeshOptions mo;
        mo.isovalue = 0.0;
        mo.inside = Inside::Above;
        mo.eps_voxels = 0.25;
        mo.facet_angle_deg = angle;
        const MeshResult r = mesh_isosurface(*testing::random_volume(7, 3u, false), mo);
        const auto& steps = r.stats.refinement_seconds;
        const double phases = r.stats.seconds.at("closed_ball") + r.stats.seconds.at("refine");
        double sum = 0;
        for (const char* k : {"grid_cells", "facet_records", "violation_scan", "facet_loops", "cell_disks", "hausdorff",
                              "creases", "insertion", "voxel_bound_n"}) {
            INFO(k);
            REQUIRE(steps.count(k) == 1);
            CHECK(steps.at(k) >= 0);
        }
        for (const char* k : {"grid_cells", "facet_records", "violation_scan", "facet_loops", "cell_disks", "hausdorff",
                              "creases", "insertion", "voxel_bound_n"}) {
            INFO(k << " did work on this volume");
            CHECK(steps.at(k) > 0);
        }
        CHECK(steps.count("facet_angle") == (angle > 0 ? 1u : 0u));
        if (angle > 0) CHECK(steps.at("facet_angle") > 0);
        for (const auto& [k, v] : steps) sum += v;
        INFO("steps " << sum << " s, closed_ball + refine " << phases << " s");
        CHECK(sum <= phases + 1e-9);
        CHECK(sum >= 0.3 * phases); // the rest is bookkeeping (97 % are steps on a 128^3 protein)
        const testing::Json json = testing::Json::parse(to_json(r.stats));
        CHECK(json.at("refinement_seconds").size() == steps.size());
        CHECK(json.at("refinement_seconds").at("cell_disks").get<double>() == steps.at("cell_disks"));
        CHECK(json.at("counts").at("facet_angle_stop").get<std::string>() == to_string(r.stats.facet_angle_stop));
    }
}
