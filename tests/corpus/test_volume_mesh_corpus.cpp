// DELVOLMESH (paper Section 4.1) on the shared volumes at eps = 0.5 voxel: the skull, both proteins, the
// EMD-3001 map, both level sets and every analytic shape of ../shared/data (the cells/ volumes are
// covered by test_mesh_corpus's surfaces). Every tet positively oriented, inside volume ==
// volume enclosed by M to 1e-9 relative, the inside region's boundary == M's triangles exactly;
// the quality figures are printed (one line per volume; off_* = over the tets with no vertex on M).
// Label "corpus".
#include <catch2/catch.hpp>

#include "support/skip.h"

#include "support/mesher_test_support.h"
#include "support/volume_mesh_checks.h"

#include <chrono>
#include <cstdio>

using namespace isodel;

TEST_CASE("shared volumes: tetrahedral meshes conform to M", "[corpus][volume_mesh]")
{
    const auto manifest = testing::read_manifest();
    if (!manifest.is_array()) {
        ISODEL_SKIP("../shared/data not found at " << testing::shared_data());
    }
    // (file, region): "both" where the box is small enough to keep the run short.
    const std::vector<std::pair<std::string, TetRegion>> cases = {
        {"ct/skull_2.9.vdb", TetRegion::Both},
        {"protein/1hpv_molmap_6A_2A.vdb", TetRegion::Both},
        {"levelset/bunny.vdb", TetRegion::Inside},
        {"analytic/torus.vdb", TetRegion::Both},
        {"analytic/genus3.vdb", TetRegion::Inside},
        {"analytic/nested_spheres.vdb", TetRegion::Inside},
        {"analytic/dumbbell_thin_neck.vdb", TetRegion::Inside},
        {"analytic/tangle_cube.vdb", TetRegion::Inside},
        {"analytic/ellipsoid_aniso.vdb", TetRegion::Inside},
        {"protein/1hpv_blobby_1A.vdb", TetRegion::Inside},
        {"em/emd3001.vdb", TetRegion::Inside},
        {"levelset/eight.vdb", TetRegion::Inside},
        {"analytic/dumbbell_thin_neck_density.vdb", TetRegion::Inside},
        {"analytic/gyroid_ball.vdb", TetRegion::Inside},
        {"analytic/marschner_lobb.vdb", TetRegion::Inside},
        {"analytic/tangle_cube_half.vdb", TetRegion::Inside},
    };
    std::printf("%-34s %9s %9s %9s %10s %10s %10s %9s %7s %7s %8s\n", "volume", "triangles", "tets_in", "tets_out",
                "vol_relerr", "min_dih", "max_dih", "max_r/e", "off_dih", "off_r/e", "tets_s");
    for (const auto& [file, region] : cases) {
        const testing::Json* entry = nullptr;
        for (const auto& e : manifest)
            if (testing::json_string(e, "file") == file) entry = &e;
        REQUIRE(entry != nullptr);
        auto grid = testing::read_vdb(testing::shared_data() + "/" + file, testing::json_string(*entry, "grid_name"));
        MeshOptions mo;
        mo.isovalue = testing::json_number(*entry, "isovalue");
        mo.inside = testing::inside_of(*entry);
        mo.eps_voxels = 0.5;
        mo.tets = region;
        MeshResult r;
        try {
            r = mesh_isosurface(*grid, mo);
        } catch (const std::exception& ex) {
            FAIL_CHECK(file << ": " << ex.what());
            continue;
        }
        const auto& t = r.stats.tets;
        const double rel = std::abs(t.volume_inside - t.volume_enclosed_by_surface) / t.volume_enclosed_by_surface;
        std::printf("%-34s %9zu %9zu %9zu %10.2e %10.5f %10.5f %9.1f %7.3f %7.4f %8.2f\n", file.c_str(),
                    r.stats.triangles, t.tets_inside, t.tets_outside, rel, t.min_dihedral_deg, t.max_dihedral_deg,
                    t.max_radius_edge, t.min_dihedral_deg_off_surface, t.max_radius_edge_off_surface,
                    r.stats.seconds["tets"]);
        std::fflush(stdout);
        testing::require_volume_mesh(r, region, file);
    }
}
