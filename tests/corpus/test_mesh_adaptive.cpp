// Property IV: after decimation (k = 1 and 2) the mesh of the decimated F still has properties
// I-III, certified by isodel verify against the adaptive interpolant resampled on the finest
// grid. The skull and a blurred-atom protein of ../shared/data are decimated with a tolerance of
// 5% of their value range, large enough that Sigma runs through coarse cells (at 1% the skull's
// bone surface keeps every crossed cell fine and the test would not exercise coarse cells).
// A .vdb adaptive file read by read_volume gives the same resampled grid (src/io/read_vdb.cpp);
// the round trip through a file is checked too. Label "corpus".
#include <catch2/catch.hpp>

#include "../mesher/mesher_test_support.h"

#include <isodel/adaptive.h>
#include <isodel/volume.h>

#include <cstdio>

using namespace isodel;

TEST_CASE("decimated volumes mesh with guarantees I-III against their resampled grid", "[corpus][mesher][adaptive]")
{
    const auto manifest = testing::read_manifest();
    if (manifest.type != minijson::Value::Array) {
        WARN("../shared/data not found at " << testing::shared_data() << ": test skipped");
        SUCCEED();
        return;
    }
    for (const std::string file : {"ct/skull_2.9.vdb", "protein/1hpv_molmap_6A_2A.vdb"}) {
        const minijson::Value* entry = testing::manifest_entry(manifest, file);
        REQUIRE(entry != nullptr);
        const auto& e = *entry;
        auto grid = testing::read_vdb(testing::shared_data() + "/" + file, e["grid_name"].as_string());
        const double range = e["value_range"].arr[1].num - e["value_range"].arr[0].num;
        for (int k : {1, 2}) {
            DecimateOptions d;
            d.k = k;
            d.tolerance = 0.05 * range;
            const DecimateResult dec = decimate(*grid, d);
            INFO(file << " k " << k << ": " << dec.cells_before << " -> " << dec.cells_after << " cells");
            REQUIRE(dec.cells_after < dec.cells_before);
            REQUIRE(dec.max_level_difference <= k);

            // The CLI path: save, read back through read_volume (resampled exactly).
            const std::string path = "test_mesh_adaptive_k" + std::to_string(k) + ".vdb";
            save_adaptive(path, dec.volume);
            const Volume vol = read_volume(path);
            std::remove(path.c_str());
            REQUIRE(vol.adaptive_levels > 1);
            REQUIRE(vol.adaptive_k == k);
            const auto dense = resample(dec.volume);

            const auto r = testing::mesh_and_verify(*vol.grid, e["isovalue"].as_number(), testing::inside_of(e), 0.5);
            // Certified against the resampled adaptive interpolant, independently resampled.
            VerifyOptions vo;
            vo.isovalue = e["isovalue"].as_number();
            vo.inside = testing::inside_of(e);
            vo.eps_voxels = 0.5;
            const VerifyReport rep = verify_surface(*dense, r.mesh.surface, vo);
            INFO(rep.summary());
            CHECK(rep.reference.determined);
            CHECK(rep.topology_verdict == "pass");
            CHECK(rep.passed());
            CHECK(r.mesh.stats.max_cells_e <= r.mesh.stats.bound_e);
            CHECK(r.mesh.stats.max_cells_n <= r.mesh.stats.bound_n);
        }
    }
}
