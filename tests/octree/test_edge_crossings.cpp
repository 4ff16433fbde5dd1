// E, the crossings of Sigma with grid edges (octree/edge_crossings.h), found by scanning only the
// 8^3 blocks where an edge can change sign: the leaf nodes, the faces of tiles, and the faces of
// the domain and the active box where the sample inside may be inside. Pinned down here: on
// sparse level sets, fog volumes with active and inactive tiles (Sigma passing between a tile and
// voxels), a background that is itself inside, and data touching the box, the points, their
// order and the crossed cells are exactly those of a scan of every sample of the box; and they
// do not depend on the thread count.
#include "octree/edge_crossings.h"
#include "octree/sample_field.h"

#include <catch2/catch.hpp>

#include <openvdb/tools/Composite.h>
#include <openvdb/tools/LevelSetSphere.h>

#include <tbb/global_control.h>

#include <cmath>
#include <random>
#include <set>
#include <tuple>

using isodel::Inside;
using isodel::octree::EdgeCrossings;
using isodel::octree::EdgePoint;
using openvdb::Coord;
using openvdb::CoordBBox;

namespace {

/// n^3 samples uniform in [-1, 1] (quantized: in steps of 0.5), padded by a layer of -1.
openvdb::FloatGrid::Ptr noise_volume(int n, unsigned seed, bool quantized)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    auto grid = openvdb::FloatGrid::create(-1.f);
    auto acc = grid->getAccessor();
    for (int z = 1; z <= n; ++z)
        for (int y = 1; y <= n; ++y)
            for (int x = 1; x <= n; ++x) {
                const double v = U(rng);
                acc.setValueOn(Coord(x, y, z), float(quantized ? std::round(2 * v) / 2 : v));
            }
    for (int a = 0; a < 3; ++a) // the padding layer, so the active box is (n + 2)^3
        for (const int at : {0, n + 1}) {
            Coord c(1);
            c[a] = at;
            acc.setValueOn(c, -1.f);
        }
    return grid;
}

/// The reference: every edge of the box, axis by axis, then put in the order z, y, x, axis.
EdgeCrossings scan_whole_box(const isodel::octree::SampleField& field)
{
    EdgeCrossings out;
    const isodel::octree::SampleField::Reader reader(field);
    CoordBBox box = field.domain();
    box.expand(1);
    for (int axis = 0; axis < 3; ++axis)
        for (auto it = box.begin(); it; ++it) {
            const Coord lower = *it, upper = lower.offsetBy(axis == 0, axis == 1, axis == 2);
            if (!box.isInside(upper)) continue;
            const double f0 = reader.phi(lower), f1 = reader.phi(upper);
            if (f0 > 0 && f1 > 0) continue;
            if (!(f0 > 0) && !(f1 > 0)) continue;
            openvdb::Vec3d at = lower.asVec3d();
            at[axis] += f0 / (f0 - f1);
            out.points.push_back({at, lower, axis});
        }
    std::stable_sort(out.points.begin(), out.points.end(), [](const EdgePoint& p, const EdgePoint& q) {
        return std::make_tuple(p.lower.z(), p.lower.y(), p.lower.x(), p.axis) <
               std::make_tuple(q.lower.z(), q.lower.y(), q.lower.x(), q.axis);
    });
    return out;
}

/// The crossed cells, independently: a trilinear cell holds part of Sigma iff its corners do not
/// all have one sign.
std::set<Coord> mixed_cells(const isodel::octree::SampleField& field)
{
    std::set<Coord> out;
    const isodel::octree::SampleField::Reader reader(field);
    CoordBBox cells = field.domain();
    cells.expand(2);
    for (auto it = cells.begin(); it; ++it) {
        double corner[8];
        reader.cell_corners(*it, corner);
        int inside = 0;
        for (double c : corner) inside += c > 0;
        if (inside != 0 && inside != 8) out.insert(*it);
    }
    return out;
}

void require_same_as_whole_box(const openvdb::FloatGrid::Ptr& grid, double iso, Inside inside)
{
    const isodel::octree::SampleField field(grid, iso, inside);
    const EdgeCrossings sparse = isodel::octree::edge_crossings(field);
    const EdgeCrossings dense = scan_whole_box(field);
    REQUIRE(sparse.points.size() == dense.points.size());
    CHECK(!dense.points.empty());
    for (std::size_t i = 0; i < dense.points.size(); ++i) {
        INFO("point " << i << " of " << dense.points.size());
        REQUIRE(sparse.points[i].lower == dense.points[i].lower);
        REQUIRE(sparse.points[i].axis == dense.points[i].axis);
        REQUIRE(sparse.points[i].index_pos == dense.points[i].index_pos);
    }
    const std::set<Coord> mask(sparse.crossed_cells.begin(), sparse.crossed_cells.end());
    CHECK(mask.size() == sparse.crossed_cells.size());
    CHECK(mask == mixed_cells(field));
}

} // namespace

TEST_CASE("edge crossings: sparse level sets far apart, as a scan of the whole box", "[octree][sparse]")
{
    auto a = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(6.f, openvdb::Vec3f(0.3f, 0.1f, -0.2f), 1.f, 3.f);
    auto b = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(4.f, openvdb::Vec3f(90.5f, -70.f, 61.f), 1.f, 3.f);
    openvdb::tools::csgUnion(*a, *b);
    require_same_as_whole_box(a, 0.0, Inside::Below);
    // Another level: a shell inside the narrow band.
    require_same_as_whole_box(a, 1.2, Inside::Below);
    // A large sphere: its inside is many tiles side by side, whose shared faces are not scanned.
    auto big = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(60.f, openvdb::Vec3f(0.5f), 1.f, 3.f);
    REQUIRE(big->tree().activeTileCount() + big->tree().inactiveVoxelCount() > 0);
    require_same_as_whole_box(big, 0.0, Inside::Below);
    require_same_as_whole_box(big, -2.5, Inside::Below);
}

TEST_CASE("edge crossings: fog volumes with active and inactive tiles", "[octree][sparse]")
{
    for (const bool active_tiles : {true, false}) {
        INFO((active_tiles ? "active" : "inactive") << " tiles");
        auto grid = openvdb::FloatGrid::create(0.f);
        grid->setGridClass(openvdb::GRID_FOG_VOLUME);
        // A 16^3 core of tiles at 1 (two 8^3 tiles per axis), then voxels around it falling off.
        grid->tree().fill(CoordBBox(Coord(0), Coord(15)), 1.f, active_tiles);
        auto acc = grid->getAccessor();
        for (int z = -3; z <= 18; ++z)
            for (int y = -3; y <= 18; ++y)
                for (int x = -3; x <= 18; ++x) {
                    const Coord c(x, y, z);
                    if (CoordBBox(Coord(0), Coord(15)).isInside(c)) continue;
                    const int d = std::max({-x, x - 15, -y, y - 15, -z, z - 15});
                    acc.setValueOn(c, float(1.0 - 0.3 * d + 0.01 * ((x * 7 + y * 3 + z) % 5)));
                }
        REQUIRE(grid->tree().hasActiveTiles() == active_tiles);
        // Sigma between the tile core and the first voxels, and further out.
        for (const double iso : {0.95, 0.5, 0.2}) {
            INFO("iso " << iso);
            require_same_as_whole_box(grid, iso, Inside::Above);
        }
        // A tile that is the only inside region: Sigma runs along the tile's faces.
        auto bare = openvdb::FloatGrid::create(0.f);
        bare->tree().fill(CoordBBox(Coord(8), Coord(23)), 1.f, active_tiles);
        // Active voxels around it keep the active box (the domain) larger than the tile.
        bare->tree().setValueOn(Coord(0, 0, 0), 0.25f);
        bare->tree().setValueOn(Coord(40, 40, 40), 0.75f);
        require_same_as_whole_box(bare, 0.5, Inside::Above);
    }
}

TEST_CASE("edge crossings: tiles on the background's side next to inside voxels", "[octree][sparse]")
{
    // A 32^3 tile at 0.2 (outside, like the background 0) wrapped in voxels at 0.9 (inside):
    // Sigma runs between the tile and the voxels, found from the voxels' leaves alone.
    auto grid = openvdb::FloatGrid::create(0.f);
    grid->tree().fill(CoordBBox(Coord(0), Coord(31)), 0.2f, true);
    auto acc = grid->getAccessor();
    for (int z = -2; z <= 33; ++z)
        for (int y = -2; y <= 33; ++y)
            for (int x = -2; x <= 33; ++x)
                if (!CoordBBox(Coord(0), Coord(31)).isInside(Coord(x, y, z))) acc.setValueOn(Coord(x, y, z), 0.9f);
    require_same_as_whole_box(grid, 0.5, Inside::Above);
}

TEST_CASE("edge crossings: a background that is inside crosses the whole domain boundary", "[octree][sparse]")
{
    auto grid = openvdb::FloatGrid::create(1.f);
    auto acc = grid->getAccessor();
    for (int z = 0; z < 12; ++z)
        for (int y = 0; y < 12; ++y)
            for (int x = 0; x < 12; ++x) acc.setValueOn(Coord(x, y, z), float(((x + 2 * y + 3 * z) % 7) / 7.0));
    require_same_as_whole_box(grid, 0.5, Inside::Above);
}

TEST_CASE("edge crossings: data touching the box, and dense random volumes", "[octree][sparse]")
{
    for (unsigned seed = 1; seed <= 4; ++seed) {
        INFO("seed " << seed);
        require_same_as_whole_box(noise_volume(9, seed, seed % 2 == 0), 0.0, Inside::Above);
        // The background (-1) at the isovalue: by the tie rule it is inside, the ring reads
        // "outside" (sample_field.h), and Sigma runs along the faces of the active box.
        require_same_as_whole_box(noise_volume(9, seed, false), -1.0, Inside::Above);
    }
}

TEST_CASE("edge crossings: the same points at 1 and 2 threads", "[octree][sparse]")
{
    auto a = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(20.f, openvdb::Vec3f(0.f), 1.f, 3.f);
    const isodel::octree::SampleField field(a, 0.0, Inside::Below);
    std::vector<std::tuple<Coord, int, openvdb::Vec3d>> runs[2];
    for (int threads : {1, 2}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
        for (const EdgePoint& p : isodel::octree::edge_crossings(field).points)
            runs[threads - 1].emplace_back(p.lower, p.axis, p.index_pos);
    }
    CHECK(runs[0].size() > 1000);
    CHECK(runs[0] == runs[1]);
}
