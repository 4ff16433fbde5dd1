// Partitioned meshing on real volumes (its acceptance criterion: "partitioned and unpartitioned
// runs give meshes that both verify"): the CT skull, both blurred-atom proteins and the EMD-3001
// cryo-EM map (sheared transform) are meshed unpartitioned, in blocks of 24 voxels (8 to 27
// blocks each; much smaller blocks multiply the collars and the seams the merge must fix, and
// cost more than they save) and in three blocks of about equal work, and each mesh is
// certified by isodel verify (topology against the independent reference, Hausdorff distance,
// exact Delaunay conformity) and matched against the manifest's expected topology
// where it is settled. Label "corpus".
#include <catch2/catch.hpp>

#include "support/skip.h"

#include "support/mesher_test_support.h"

using namespace isodel;

TEST_CASE("partitioned and unpartitioned meshes of the shared volumes both verify", "[corpus][mesher][partition]")
{
    const auto manifest = testing::read_manifest();
    if (!manifest.is_array()) {
        ISODEL_SKIP("../shared/data not found at " << testing::shared_data());
    }
    for (const std::string file : {"ct/skull_2.9.vdb", "protein/1hpv_molmap_6A_2A.vdb", "protein/1hpv_blobby_1A.vdb",
                                   "em/emd3001.vdb"}) {
        const testing::Json* entry = testing::manifest_entry(manifest, file);
        REQUIRE(entry != nullptr);
        const auto& e = *entry;
        const auto grid = testing::read_vdb(testing::shared_data() + "/" + file, testing::json_string(e, "grid_name"));
        // Unpartitioned, cubes of 24 voxels, and three blocks of about equal work (--block-count 3).
        for (const auto& [blocks, count] : {std::pair<int, int>{0, 0}, {24, 0}, {0, 3}}) {
            INFO(file << ", blocks of " << blocks << " voxels (0 = unpartitioned), block count " << count);
            MeshOptions mo;
            mo.isovalue = testing::json_number(e, "isovalue");
            mo.inside = testing::inside_of(e);
            mo.eps_voxels = 0.5;
            mo.block_voxels = blocks;
            mo.block_count = count;
            const MeshResult m = mesh_isosurface(*grid, mo);
            VerifyOptions vo;
            vo.isovalue = mo.isovalue;
            vo.inside = *mo.inside;
            vo.eps_voxels = 0.5;
            const VerifyReport rep = verify_surface(*grid, m.surface, vo);
            INFO(rep.summary());
            CHECK(rep.passed());
            CHECK(rep.topology_verdict == TopologyVerdict::Pass);
            if (count > 0) CHECK(m.stats.partition.blocks == count);
            if (blocks > 0 || count > 0) {
                CHECK(m.stats.partition.blocks > 1);
                CHECK(m.stats.partition.exchange_rounds >= 1);
            }
            if (testing::json_has(e, "expected_topology") && testing::json_has(e.at("expected_topology"), "genus")) {
                std::vector<int> genera;
                for (const auto& c : m.stats.components) genera.push_back(c.genus);
                std::sort(genera.begin(), genera.end());
                CHECK(genera == testing::expected_genera(e));
            }
        }
    }
}
