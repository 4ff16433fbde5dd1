// Snapping (paper Section 5, `--snap`, src/seeding/snap_edge_points.h): three E points around one
// sample, one per axis, within eps / 2, give way to the sample; anything else is left alone; and
// the snapped mesh keeps every guarantee while having fewer vertices.
#include <catch2/catch.hpp>

#include "support/mesher_test_support.h"

#include "seeding/snap_edge_points.h"

#include <isodel/volume.h>

using namespace isodel;

namespace {

/// E points of phi = f(x) - 0 on a 5^3 grid (index = world).
struct Case {
    openvdb::FloatGrid::Ptr grid;
    std::unique_ptr<octree::SampleField> field;
    octree::EdgeCrossings e;
};

Case make_case(const std::function<double(const openvdb::Vec3d&)>& f)
{
    Case c;
    c.grid = testing::make_grid(5, 1.0, openvdb::Vec3d(0.0), f);
    c.field = std::make_unique<octree::SampleField>(c.grid, 0.0, Inside::Above);
    c.e = octree::edge_crossings(*c.field);
    return c;
}

} // namespace

TEST_CASE("snap: a corner cut off within the radius snaps its three points", "[mesher][snap]")
{
    // The plane x + y + z = 3.3 cuts the edges from (1,1,1) along +x, +y, +z at 0.3.
    const Case c = make_case([](const openvdb::Vec3d& x) { return x[0] + x[1] + x[2] - 3.3; });
    const auto near = mesher::snap_edge_points(c.e.points, *c.field, 0.35);
    CHECK(near.is_snapped_grid_point(openvdb::Coord(1, 1, 1)));
    std::size_t n = 0;
    for (std::size_t i = 0; i < c.e.points.size(); ++i)
        if (near.snapped[i]) {
            ++n;
            // Only points on the edges of snapped samples, within the radius of one.
            bool close = false;
            for (const auto& g : near.grid_points) close |= (c.e.points[i].index_pos - g.asVec3d()).length() < 0.35;
            CHECK(close);
        }
    CHECK(n == 3 * near.grid_points.size());
    const auto far = mesher::snap_edge_points(c.e.points, *c.field, 0.25);
    CHECK_FALSE(far.is_snapped_grid_point(openvdb::Coord(1, 1, 1)));
}

TEST_CASE("snap: two sheets around a sample, or six crossings, are not snapped", "[mesher][snap]")
{
    // A slab |x - 2| < 0.2 - (y - 2) / 2 (inside): the sample (2,2,2) has three crossings within
    // 0.45, at 0.2 on both x edges (two sheets) and at 0.4 on the +y edge.
    const Case slab = make_case([](const openvdb::Vec3d& x) { return 0.2 - std::abs(x[0] - 2.0) - 0.5 * (x[1] - 2.0); });
    CHECK_FALSE(mesher::snap_edge_points(slab.e.points, *slab.field, 0.45).is_snapped_grid_point(openvdb::Coord(2, 2, 2)));
    // A blob around one sample: all six edges crossed at 0.2; snapping would swallow it.
    const Case blob = make_case([](const openvdb::Vec3d& x) { return 0.2 - (x - openvdb::Vec3d(2.0)).length(); });
    CHECK_FALSE(mesher::snap_edge_points(blob.e.points, *blob.field, 0.4).is_snapped_grid_point(openvdb::Coord(2, 2, 2)));
}

TEST_CASE("snap: snapped meshes keep the guarantees with fewer vertices", "[mesher][snap]")
{
    const auto path = std::string(ISODEL_TEST_DATA) + "/torus.vdb";
    ReadOptions ro;
    const auto grid = read_volume(path, ro).grid;
    const Inside inside = grid->getGridClass() == openvdb::GRID_LEVEL_SET ? Inside::Below : Inside::Above;
    const auto plain = testing::mesh_and_verify(*grid, 0.0, inside, 0.5);
    MeshOptions mo;
    mo.isovalue = 0.0;
    mo.inside = inside;
    mo.eps_voxels = 0.5;
    mo.snap = true;
    const MeshResult snapped = mesh_isosurface(*grid, mo);
    VerifyOptions vo;
    vo.isovalue = 0.0;
    vo.inside = inside;
    vo.eps_voxels = 0.5;
    const VerifyReport r = verify_surface(*grid, snapped.surface, vo);
    INFO(r.summary());
    CHECK(r.passed());
    CHECK(snapped.stats.snapped > 0);
    CHECK(snapped.surface.vertices.size() < plain.mesh.surface.vertices.size());
}
