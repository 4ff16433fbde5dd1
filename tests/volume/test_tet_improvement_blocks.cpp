// Tet improvement by blocks (src/volume/tet_improvement_blocks.cpp): blocks improved
// concurrently and merged must give a valid mesh (positive tets, M and its triangles kept, the
// inside region bounded by M, volumes unchanged), the same one with 1 and 2 threads, and still
// improve it -- also with blocks of a few voxels, where most tets have a vertex on a block's
// boundary and vertex insertions and collapses from many blocks are merged at once. The last
// block, improved as its pieces that share no vertex, must give the tets it gives in one piece.
#include <catch2/catch.hpp>

#include "support/mesher_test_support.h"
#include "support/volume_mesh_checks.h"

#include "volume/tet_improvement.h"
#include "volume/tet_quality.h"

#include <isodel/mesh.h>

#include <tbb/global_control.h>

using namespace isodel;
using namespace isodel::mesher;

namespace {

/// The level set {F = 0} (inside above) at eps 0.5 voxel with the Delaunay tets of both
/// regions, not improved, checked valid.
MeshResult delaunay_tets(const openvdb::FloatGrid& grid)
{
    MeshOptions mo;
    mo.isovalue = 0.0;
    mo.inside = Inside::Above;
    mo.eps_voxels = 0.5;
    mo.tets = TetRegion::Both;
    mo.improve_tets = false;
    MeshResult del = mesh_isosurface(grid, mo);
    testing::require_volume_mesh(del, TetRegion::Both, "Delaunay");
    return del;
}

/// The tets of \p m as their corners' coordinates (sorted, with the orientation's sign) and
/// region, sorted: the mesh up to vertex numbering.
std::vector<std::pair<std::array<std::array<double, 3>, 4>, int>> tets_by_position(const TetMesh& m)
{
    std::vector<std::pair<std::array<std::array<double, 3>, 4>, int>> out;
    for (std::size_t t = 0; t < m.tets.size(); ++t) {
        std::array<std::array<double, 3>, 4> p;
        for (int j = 0; j < 4; ++j) p[std::size_t(j)] = m.vertices[std::size_t(m.tets[t][std::size_t(j)])];
        const auto d = [&](int j, int k) { return p[std::size_t(j)][std::size_t(k)] - p[0][std::size_t(k)]; };
        const double vol = d(1, 0) * (d(2, 1) * d(3, 2) - d(2, 2) * d(3, 1)) - d(1, 1) * (d(2, 0) * d(3, 2) - d(2, 2) * d(3, 0)) +
                           d(1, 2) * (d(2, 0) * d(3, 1) - d(2, 1) * d(3, 0));
        std::sort(p.begin(), p.end());
        out.push_back({p, 4 * m.tet_region[t] + (vol > 0 ? 1 : vol < 0 ? -1 : 0)});
    }
    std::sort(out.begin(), out.end());
    return out;
}

} // namespace

TEST_CASE("tet improvement by blocks: valid, improving, and the same with 1 and 2 threads",
          "[mesher][volume_mesh][tet_improvement]")
{
    // A sphere of radius 7.2 in a 26^3 grid at voxel 0.5, both regions.
    const auto grid = testing::make_grid(26, 0.5, openvdb::Vec3d(1.0, -2.0, 0.5), [](const openvdb::Vec3d& x) {
        return testing::sphere_f(x, openvdb::Vec3d(12.37, 12.11, 12.53), 7.2);
    });
    const MeshResult del = delaunay_tets(*grid);
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

TEST_CASE("tet improvement by blocks: the last block's pieces improved apart give the tets of one block",
          "[mesher][volume_mesh][tet_improvement]")
{
    // Two spheres far apart: the bad tets left near block boundaries form a piece around each.
    const auto grid = testing::make_grid(34, 0.5, openvdb::Vec3d(0.3, -1.0, 0.7), [](const openvdb::Vec3d& x) {
        return std::max(testing::sphere_f(x, openvdb::Vec3d(5.37, 5.11, 5.53), 3.7),
                        testing::sphere_f(x, openvdb::Vec3d(12.4, 10.6, 11.9), 3.3));
    });
    const MeshResult del = delaunay_tets(*grid);
    const std::size_t nm = del.surface.vertices.size();

    for (const double block : {2.5, 3.0}) {
        INFO("blocks of " << block << " (" << block / 0.5 << " voxels)");
        TetImprovementParams params;
        params.block_size = block;
        TetMesh apart = del.tets, whole = del.tets;
        const TetImprovementStats sa = improve_tets(apart, nm, params);
        params.split_last_block = false;
        const TetImprovementStats sw = improve_tets(whole, nm, params);
        INFO("last block: " << sa.last_block_pieces << " pieces");
        CHECK(sa.last_block_pieces > 1);
        CHECK(sw.last_block_pieces == 1);
        CHECK(sa.vertices_inserted + sa.vertices_removed + sa.vertices_moved > 0);
        CHECK(apart.vertices.size() == whole.vertices.size());
        CHECK(apart.tets.size() == whole.tets.size());
        CHECK(tets_by_position(apart) == tets_by_position(whole));
        CHECK(sa.vertices_moved == sw.vertices_moved);
        CHECK(sa.vertices_inserted == sw.vertices_inserted);
        CHECK(sa.vertices_removed == sw.vertices_removed);
    }
}
