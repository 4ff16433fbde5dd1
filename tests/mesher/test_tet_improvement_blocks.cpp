// Tet improvement by blocks (src/mesher/tet_improvement_blocks.cpp): blocks improved
// concurrently and merged must give a valid mesh (positive tets, M and its triangles kept, the
// inside region bounded by M, volumes unchanged), the same one with 1 and 2 threads, and still
// improve it -- also with blocks of a few voxels, where most tets have a vertex on a block's
// boundary and vertex insertions and collapses from many blocks are merged at once.
#include <catch2/catch.hpp>

#include "mesher_test_support.h"
#include "volume_mesh_checks.h"

#include "mesher/tet_improvement.h"
#include "mesher/tet_quality.h"

#include <isodel/mesh.h>

#include <tbb/global_control.h>

using namespace isodel;
using namespace isodel::mesher;

TEST_CASE("tet improvement by blocks: valid, improving, and the same with 1 and 2 threads",
          "[mesher][volume_mesh][tet_improvement]")
{
    // A sphere of radius 7.2 in a 26^3 grid at voxel 0.5, both regions.
    const auto grid = testing::make_grid(26, 0.5, openvdb::Vec3d(1.0, -2.0, 0.5), [](const openvdb::Vec3d& x) {
        return testing::sphere_f(x, openvdb::Vec3d(12.37, 12.11, 12.53), 7.2);
    });
    MeshOptions mo;
    mo.isovalue = 0.0;
    mo.inside = Inside::Above;
    mo.eps_voxels = 0.5;
    mo.tets = TetRegion::Both;
    mo.improve_tets = false;
    const MeshResult del = mesh_isosurface(*grid, mo);
    testing::require_volume_mesh(del, TetRegion::Both, "Delaunay");
    const std::size_t nm = del.surface.vertices.size();

    for (const double block : {1.0, 2.5, 8.0}) {
        INFO("blocks of " << block << " (" << block / 0.5 << " voxels)");
        TetImprovementParams params;
        params.block_size = block;
        MeshResult one = del, two = del;
        TetImprovementStats s1, s2;
        {
            tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
            s1 = improve_tets(one.tets, nm, params);
        }
        {
            tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
            s2 = improve_tets(two.tets, nm, params);
        }
        CHECK(one.tets.vertices == two.tets.vertices);
        CHECK(one.tets.tets == two.tets.tets);
        CHECK(one.tets.tet_region == two.tets.tet_region);
        CHECK(s1.vertices_moved == s2.vertices_moved);

        measure_tet_quality(one.tets, nm, one.stats.tets);
        testing::require_volume_mesh(one, TetRegion::Both, "improved by blocks");
        CHECK(std::abs(one.stats.tets.volume_outside - del.stats.tets.volume_outside) <=
              1e-9 * del.stats.tets.volume_outside);
        INFO("Delaunay " << del.stats.tets.min_dihedral_deg << " deg, " << del.stats.tets.tets_below_10deg
                         << " under 10; improved " << one.stats.tets.min_dihedral_deg << " deg, "
                         << one.stats.tets.tets_below_10deg << " under 10; " << s1.vertices_inserted << " inserted, "
                         << s1.vertices_removed << " removed");
        CHECK(s1.vertices_moved > 0);
        CHECK(s1.vertices_inserted + s1.vertices_removed > 0);
        CHECK(one.stats.tets.min_dihedral_deg > del.stats.tets.min_dihedral_deg);
        CHECK(one.stats.tets.tets_below_10deg * 2 < del.stats.tets.tets_below_10deg);
    }
}
