// Certified adaptive meshing (MeshOptions::adaptive, with the coarse interpolant and with F from the input) on every
// volume of ../shared/data outside cells/, one file per volume (the .mrc copies hold the same samples as the .vdb), at
// eps 0.5 and 0.25 voxel: isodel verify passes each mesh against the ORIGINAL volume (topology against an independent
// computation of Sigma's, Hausdorff, Delaunay), the manifest's topology holds, the certified distance stays within the
// coarsening's share of eps, and the voxel bound holds in leaves. Label "corpus".
#include <catch2/catch.hpp>

#include "support/skip.h"

#include "support/mesher_test_support.h"

#include <isodel/volume.h>

using namespace isodel;

TEST_CASE("adaptive meshing of the shared volumes verifies against the original volume", "[corpus][mesher][adaptive]")
{
    const auto manifest = testing::read_manifest();
    if (!manifest.is_array()) {
        ISODEL_SKIP("../shared/data not found at " << testing::shared_data());
    }
    std::size_t meshed = 0;
    for (const auto& e : manifest) {
        const std::string file = testing::json_string(e, "file");
        if (file.rfind("cells/", 0) == 0 || testing::json_has(e, "expect_error")) continue;
        // One file per volume: skip the dense copies of a .vdb.
        const std::string stem = file.substr(0, file.find_last_of('.'));
        if (testing::json_string(e, "format") == "mrc" && testing::manifest_entry(manifest, stem + ".vdb")) continue;
        if (file == "ct/skull_2.9.inr") continue; // the same samples as ct/skull_2.9.vdb
        ReadOptions ro;
        if (testing::json_string(e, "format") == "vdb") ro.grid_name = testing::json_string(e, "grid_name");
        const auto grid = read_volume(testing::shared_data() + "/" + file, ro).grid;
        for (double eps : {0.5, 0.25})
            for (AdaptiveField field : {AdaptiveField::Coarse, AdaptiveField::Input}) {
                MeshOptions mo;
                mo.isovalue = testing::json_number(e, "isovalue");
                mo.inside = testing::inside_of(e);
                mo.eps_voxels = eps;
                mo.adaptive = true;
                mo.adaptive_min_saving = 0; // always on the octree: the certificate is what is tested
                mo.adaptive_field = field;
                const char* fname = field == AdaptiveField::Input ? " (F from the input)" : " (coarse F)";
                testing::MeshAndVerify r;
                try {
                    r = testing::mesh_and_verify(*grid, mo);
                }
                catch (const std::exception& ex) {
                    FAIL_CHECK(file << " eps " << eps << fname << ": " << ex.what());
                    continue;
                }
                ++meshed;
                INFO(file << " eps " << eps << fname << "\n" << r.report.summary());
                CHECK(r.report.passed());
                if (testing::json_has(e, "expected_topology") && testing::json_has(e.at("expected_topology"), "genus"))
                    CHECK(r.genera == testing::expected_genera(e));
                const AdaptiveStats& a = r.mesh.stats.adaptive;
                CHECK(a.meshed_on_octree == (a.leaves_per_level.size() > 1));
                CHECK(a.distance_world <= a.eps_coarsening_world);
                if (field == AdaptiveField::Input) { // the level set is never moved: the whole eps meshes
                    CHECK(a.eps_coarsening_world == 0);
                    CHECK(a.distance_world == 0);
                    CHECK(a.eps_meshing_world == Approx(r.mesh.stats.eps_world));
                    CHECK(a.e_octree <= a.e_uniform);
                }
                CHECK(r.mesh.stats.max_cells_e <= r.mesh.stats.bound_e);
                CHECK(r.mesh.stats.max_cells_n <= r.mesh.stats.bound_n);
            }
    }
    CHECK(meshed >= 2 * 2 * 16);
}
