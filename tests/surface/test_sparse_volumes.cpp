// Sparse VDB volumes: the work before the Delaunay triangulation visits the stored leaf nodes
// and the tiles' faces, never the bounding box (octree/edge_crossings.h), and the result is the
// mesh of the same F. Pinned down here, end to end through mesh_isosurface and the verifier:
//  - two narrow-band spheres 1536 voxels apart mesh as the same two spheres 128 voxels apart,
//    translated: the same vertices, bit for bit up to the translation, and the same triangles.
//    The points' ids, which order every later decision, follow OpenVDB's tree order for G, so
//    the second sphere moves by whole 128^3 internal nodes: the order within each sphere, and
//    so each choice between symmetric candidates, is then the same. The points lie on a dyadic
//    lattice (geometry/point_lattice.h), so the translation is exact and the exact predicates
//    decide the same way at both places, nearly cospherical vertices included.
//  - a fog volume whose core is a tile, with Sigma between the tile and the voxels around it;
//  - data whose inside reaches the faces of its active box (Sigma closed along the box);
//  - the same mesh at 1 and 2 threads.
#include <catch2/catch.hpp>

#include "support/mesher_test_support.h"

#include <openvdb/tools/Composite.h>
#include <openvdb/tools/LevelSetSphere.h>

#include <isodel/errors.h>
#include <isodel/interrupt.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

using namespace isodel;

namespace {

openvdb::FloatGrid::Ptr sphere_pair(float distance)
{
    auto a = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(6.f, openvdb::Vec3f(64.f), 1.f, 3.f);
    auto b = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(5.f, openvdb::Vec3f(64.f + distance), 1.f, 3.f);
    openvdb::tools::csgUnion(a->tree(), b->tree());
    a->setGridClass(openvdb::GRID_LEVEL_SET);
    return a;
}

MeshOptions options(double iso, Inside inside, int threads = 0)
{
    MeshOptions mo;
    mo.isovalue = iso;
    mo.inside = inside;
    mo.eps_voxels = 0.5;
    mo.threads = threads;
    return mo;
}

/// The vertices of \p m with those beyond \p split (on x) moved back by \p shift (exactly: the
/// coordinates are on the point lattice and the shift is whole voxels), and the triangles as
/// triples of those keys, both sorted: the mesh up to the order of its vertices and up to the
/// translation.
struct Canonical {
    std::vector<std::array<double, 3>> vertices;
    std::vector<std::array<std::array<double, 3>, 3>> triangles;
};

Canonical canonical(const SurfaceMesh& m, double split, double shift)
{
    std::vector<std::array<double, 3>> key(m.vertices.size());
    for (std::size_t i = 0; i < m.vertices.size(); ++i) {
        const auto& v = m.vertices[i];
        const double s = v[0] > split ? shift : 0.0;
        for (int a = 0; a < 3; ++a) key[i][a] = v[a] - s;
    }
    Canonical c;
    c.vertices = key;
    std::sort(c.vertices.begin(), c.vertices.end());
    for (const auto& t : m.triangles) {
        std::array<std::array<double, 3>, 3> k{{key[t[0]], key[t[1]], key[t[2]]}};
        std::rotate(k.begin(), std::min_element(k.begin(), k.end()), k.end()); // keeps orientation
        c.triangles.push_back(k);
    }
    std::sort(c.triangles.begin(), c.triangles.end());
    return c;
}

} // namespace

TEST_CASE("sparse volumes: a far-apart pair meshes as the compact pair, translated", "[surface][sparse]")
{
    const auto near = testing::mesh_and_verify(*sphere_pair(128.f), options(0.0, Inside::Below));
    const auto far = testing::mesh_and_verify(*sphere_pair(1536.f), options(0.0, Inside::Below));
    INFO(near.report.summary());
    INFO(far.report.summary());
    CHECK(near.report.passed());
    CHECK(far.report.passed());
    CHECK(far.genera == std::vector<int>{0, 0});
    const Canonical a = canonical(near.mesh.surface, 128.0, 128.0), b = canonical(far.mesh.surface, 800.0, 1536.0);
    CHECK(a.vertices == b.vertices);
    CHECK(a.triangles.size() == b.triangles.size());
    std::vector<std::array<std::array<double, 3>, 3>> only_a;
    std::set_difference(a.triangles.begin(), a.triangles.end(), b.triangles.begin(), b.triangles.end(),
                        std::back_inserter(only_a));
    INFO("triangles differing: " << only_a.size() << " of " << a.triangles.size());
    CHECK(only_a.empty());
}

TEST_CASE("sparse volumes: the same mesh at 1 and 2 threads", "[surface][sparse]")
{
    const auto grid = sphere_pair(1536.f);
    const MeshResult one = mesh_isosurface(*grid, options(0.0, Inside::Below, 1));
    const MeshResult two = mesh_isosurface(*grid, options(0.0, Inside::Below, 2));
    CHECK(one.surface.vertices == two.surface.vertices);
    CHECK(one.surface.triangles == two.surface.triangles);
}

TEST_CASE("sparse volumes: a fog volume with a tile core", "[surface][sparse]")
{
    for (const bool active : {true, false}) {
        INFO((active ? "active" : "inactive") << " tile core");
        auto grid = openvdb::FloatGrid::create(0.f);
        grid->setGridClass(openvdb::GRID_FOG_VOLUME);
        grid->tree().fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(15)), 1.f, active);
        auto acc = grid->getAccessor();
        for (int z = -4; z <= 19; ++z)
            for (int y = -4; y <= 19; ++y)
                for (int x = -4; x <= 19; ++x) {
                    const int d = std::max({-x, x - 15, -y, y - 15, -z, z - 15});
                    if (d > 0) acc.setValueOn(openvdb::Coord(x, y, z), float(1.0 - 0.22 * d));
                }
        // 0.9: Sigma between the tile and its first voxels; 0.5: two voxels further out.
        for (const double iso : {0.9, 0.5}) {
            INFO("iso " << iso);
            const auto r = testing::mesh_and_verify(*grid, options(iso, Inside::Above));
            INFO(r.report.summary());
            CHECK(r.report.passed());
            CHECK(r.genera == std::vector<int>{0});
        }
    }
}

TEST_CASE("sparse volumes: the inside reaching the faces of the active box", "[surface][sparse]")
{
    // A ball centred on a corner of its box: Sigma is closed along three faces of the box.
    auto grid = openvdb::FloatGrid::create(-1.f);
    auto acc = grid->getAccessor();
    for (int z = 0; z < 12; ++z)
        for (int y = 0; y < 12; ++y)
            for (int x = 0; x < 12; ++x)
                acc.setValueOn(openvdb::Coord(x, y, z), float(8.3 - std::sqrt(double(x * x + y * y + z * z))));
    const auto r = testing::mesh_and_verify(*grid, options(0.0, Inside::Above));
    INFO(r.report.summary());
    CHECK(r.report.passed());
    CHECK(r.genera == std::vector<int>{0});
}

namespace {

/// Records the counted progress of the "points" stage; cancels at the first count if asked.
struct LeafCounter final : Interrupter {
    bool cancel = false;
    std::string stage;
    std::vector<std::uint64_t> done;
    std::uint64_t total = 0;
    std::string unit;
    void start(const char* name) override { stage = name; }
    bool progress(std::uint64_t d, std::uint64_t t, const char* u) override
    {
        if (stage != "points") return false;
        done.push_back(d);
        total = t;
        unit = u;
        return cancel;
    }
};

} // namespace

TEST_CASE("sparse volumes: the points stage counts leaves, not the box, and hears a cancel", "[surface][sparse]")
{
    const auto grid = sphere_pair(1536.f);
    LeafCounter counter;
    const MeshResult r = mesh_isosurface(*grid, options(0.0, Inside::Below), &counter);
    REQUIRE(r.surface.triangles.size() > 0);
    const std::uint64_t leaves = grid->tree().leafCount();
    CHECK(counter.unit == "leaves");
    REQUIRE_FALSE(counter.done.empty());
    CHECK(std::is_sorted(counter.done.begin(), counter.done.end()));
    CHECK(counter.done.back() == counter.total);
    // Every leaf node is a block; the other blocks sit at tile and domain faces, a handful per
    // leaf. The box holds 1.6e5 times as many leaf-sized blocks as the spheres have leaves.
    CHECK(counter.total >= leaves);
    CHECK(counter.total <= 4 * leaves);
    CHECK(grid->evalActiveVoxelBoundingBox().volume() / 512 > 1000 * counter.total);

    LeafCounter cancelling;
    cancelling.cancel = true;
    CHECK_THROWS_AS(mesh_isosurface(*grid, options(0.0, Inside::Below), &cancelling), isodel::Cancelled);
    CHECK(cancelling.done.size() == 1);
}
