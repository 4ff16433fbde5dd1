// Property IV: after decimation (k = 1 and 2) the mesh of the decimated F, built on the leaves
// (mesh_isosurface(AdaptiveVolume): E on leaf edges, G from leaves, the voxel bound counted in
// leaves and held to 3k+1), still has properties I-III, certified by isodel verify against the
// adaptive interpolant resampled on the finest grid. The skull and a blurred-atom protein of ../shared/data are decimated with a tolerance of
// 5% of their value range, large enough that Sigma runs through coarse cells (at 1% the skull's
// bone surface keeps every crossed cell fine and the test would not exercise coarse cells).
// A .vdb adaptive file read by read_volume gives the same resampled grid (src/io/read_vdb.cpp);
// the round trip through a file is checked too. Label "corpus".
#include <catch2/catch.hpp>

#include "support/skip.h"

#include "support/mesher_test_support.h"

#include <isodel/adaptive.h>
#include <isodel/volume.h>

#include <cstdio>

using namespace isodel;

TEST_CASE("decimated volumes mesh with guarantees I-III against their resampled grid", "[corpus][mesher][adaptive]")
{
    const auto manifest = testing::read_manifest();
    if (!manifest.is_array()) {
        ISODEL_SKIP("../shared/data not found at " << testing::shared_data());
    }
    for (const std::string file : {"ct/skull_2.9.vdb", "protein/1hpv_molmap_6A_2A.vdb"}) {
        const testing::Json* entry = testing::manifest_entry(manifest, file);
        REQUIRE(entry != nullptr);
        const auto& e = *entry;
        auto grid = testing::read_vdb(testing::shared_data() + "/" + file, testing::json_string(e, "grid_name"));
        const double range = e.at("value_range")[1].get<double>() - e.at("value_range")[0].get<double>();
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

            // Meshed on the leaves (E on leaf edges, G from leaves, bound counted in leaves) ...
            MeshOptions mo;
            mo.isovalue = testing::json_number(e, "isovalue");
            mo.inside = testing::inside_of(e);
            mo.eps_voxels = 0.5;
            const MeshResult m = mesh_isosurface(dec.volume, mo);
            // ... and certified against the adaptive interpolant, independently resampled.
            VerifyOptions vo;
            vo.isovalue = mo.isovalue;
            vo.inside = *mo.inside;
            vo.eps_voxels = 0.5;
            const VerifyReport rep = verify_surface(*dense, m.surface, vo);
            INFO(rep.summary());
            CHECK(rep.reference.determined);
            CHECK(rep.topology_verdict == TopologyVerdict::Pass);
            CHECK(rep.passed());
            CHECK(m.stats.bound_e == 3 * k + 1);
            CHECK(m.stats.max_cells_e <= m.stats.bound_e);
            CHECK(m.stats.max_cells_n <= m.stats.bound_n);
            // The leaves give fewer points than the dense resampling (read back from the file).
            const MeshResult u = mesh_isosurface(*vol.grid, mo);
            INFO("E " << m.stats.e_points << " vs " << u.stats.e_points << ", G " << m.stats.g_points << " vs "
                      << u.stats.g_points);
            CHECK(m.stats.e_points <= u.stats.e_points);
            CHECK(m.stats.g_points < u.stats.g_points);
        }
    }
}
