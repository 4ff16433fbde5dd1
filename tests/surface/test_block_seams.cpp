// Partitioned meshing without a global merge (src/surface/partitioned_meshing.h, block_mesher.h):
// features cut by block faces keep their topology, a block with nothing in it is harmless, the
// surface is the same for every block size up to the points near seams, and the assembly of the
// blocks' owned facets refuses anything but a closed, consistently oriented surface.
#include <catch2/catch.hpp>

#include "surface/partitioned_meshing.h"
#include "support/mesher_test_support.h"

#include <isodel/errors.h>

#include <algorithm>
#include <cmath>

using namespace isodel;

namespace {

double cylinder_f(const openvdb::Vec3d& x, const openvdb::Vec3d& a, const openvdb::Vec3d& b, double r)
{
    const openvdb::Vec3d ab = b - a;
    const double t = std::clamp((x - a).dot(ab) / ab.lengthSqr(), 0.0, 1.0);
    return r - (x - (a + t * ab)).length();
}

/// Blocks of 8 voxels cut planes at 8, 16, 24, 32: a dumbbell whose thin neck (radius 0.8
/// voxel) crosses x = 16, a torus whose hole and tube cross y = 24 and z = 16, and a blob of
/// radius 1.3 voxel around the corner (24, 24, 24) where eight blocks meet. The blocks at the
/// domain's low corner hold nothing.
openvdb::FloatGrid::Ptr seam_features()
{
    return testing::make_grid(40, 1.0, openvdb::Vec3d(0.0), [](const openvdb::Vec3d& x) {
        const openvdb::Vec3d a(11.3, 30.2, 9.7), b(21.6, 30.4, 9.9);
        double f = std::max(testing::sphere_f(x, a, 3.1), testing::sphere_f(x, b, 3.3));
        f = std::max(f, cylinder_f(x, a, b, 0.8));
        f = std::max(f, testing::torus_f(x, openvdb::Vec3d(29.4, 23.6, 16.3), 6.2, 2.1));
        f = std::max(f, testing::sphere_f(x, openvdb::Vec3d(24.1, 23.9, 24.2), 1.3));
        return f;
    });
}

MeshResult mesh_seams(const openvdb::FloatGrid& grid, int block_voxels, int threads)
{
    MeshOptions mo;
    mo.isovalue = 0.0;
    mo.inside = Inside::Above;
    mo.eps_voxels = 0.25;
    mo.block_voxels = block_voxels;
    mo.threads = threads;
    return mesh_isosurface(grid, mo);
}

std::vector<int> seam_genera(const MeshStats& s)
{
    std::vector<int> out;
    for (const auto& c : s.components) out.push_back(c.genus);
    std::sort(out.begin(), out.end());
    return out;
}

} // namespace

TEST_CASE("a neck, a handle and a blob cut by block faces keep their topology", "[mesher][partition]")
{
    const auto grid = seam_features();
    const MeshResult whole = mesh_seams(*grid, 0, 2);
    REQUIRE(whole.stats.components.size() == 3); // dumbbell, torus, blob
    for (int block : {8, 13}) {
        INFO("blocks of " << block << " voxels");
        const MeshResult r = mesh_seams(*grid, block, 2);
        VerifyOptions vo;
        vo.isovalue = 0.0;
        vo.inside = Inside::Above;
        vo.eps_voxels = 0.25;
        const VerifyReport rep = verify_surface(*grid, r.surface, vo);
        INFO(rep.summary());
        CHECK(rep.passed());
        CHECK(rep.topology_verdict == TopologyVerdict::Pass);
        CHECK(seam_genera(r.stats) == seam_genera(whole.stats));
        CHECK(r.stats.partition.exchange_rounds >= 1);
        // E and G are the unpartitioned run's, each counted by the block that owns it.
        CHECK(r.stats.e_points == whole.stats.e_points);
        CHECK(r.stats.g_points == whole.stats.g_points);
        // Blocks hold nothing at the domain's low corner: they add no triangle and no error.
        for (const auto& v : r.surface.vertices) CHECK(std::max({v[0], v[1], v[2]}) > 4.0);
    }
}

TEST_CASE("block seams: 1 and 2 threads give the same mesh", "[mesher][partition][determinism]")
{
    const auto grid = seam_features();
    const MeshResult a = mesh_seams(*grid, 8, 1);
    const MeshResult b = mesh_seams(*grid, 8, 2);
    CHECK(a.surface.vertices == b.surface.vertices);
    CHECK(a.surface.triangles == b.surface.triangles);
    CHECK(a.stats.partition.exchange_rounds == b.stats.partition.exchange_rounds);
}

TEST_CASE("the blocks' facets are assembled only into a closed, oriented surface", "[mesher][partition]")
{
    using mesher::BlockSurface;
    using mesher::WorldTriangle;
    const std::array<double, 3> p0{0, 0, 0}, p1{1, 0, 0}, p2{0, 1, 0}, p3{0, 0, 1};
    // A tetrahedron's boundary, outward, split over two blocks: merged by coordinates.
    BlockSurface a, b;
    a.triangles = {WorldTriangle{p0, p2, p1}, WorldTriangle{p0, p1, p3}};
    b.triangles = {WorldTriangle{p0, p3, p2}, WorldTriangle{p1, p2, p3}};
    SurfaceMesh mesh;
    REQUIRE(mesher::assemble_surface({a, b}, mesh));
    CHECK(mesh.vertices.size() == 4);
    CHECK(mesh.triangles.size() == 4);
    // A facet missing (its owner refused it): an open surface is refused, and nothing is kept.
    b.triangles.pop_back();
    CHECK_FALSE(mesher::assemble_surface({a, b}, mesh));
    CHECK(mesh.triangles.empty());
    // A facet owned twice, or one turned over, is refused as well.
    b.triangles = {WorldTriangle{p0, p3, p2}, WorldTriangle{p1, p2, p3}, WorldTriangle{p1, p2, p3}};
    CHECK_FALSE(mesher::assemble_surface({a, b}, mesh));
    b.triangles = {WorldTriangle{p0, p3, p2}, WorldTriangle{p1, p3, p2}};
    CHECK_FALSE(mesher::assemble_surface({a, b}, mesh));
    // A vertex off by one unit in the last place is another vertex: no tolerance.
    const std::array<double, 3> p1_next{std::nextafter(1.0, 2.0), 0, 0};
    b.triangles = {WorldTriangle{p0, p3, p2}, WorldTriangle{p1_next, p2, p3}};
    CHECK_FALSE(mesher::assemble_surface({a, b}, mesh));
}
