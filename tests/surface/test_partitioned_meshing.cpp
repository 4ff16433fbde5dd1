// Partitioned meshing (paper Fig. 8, src/surface/partitioned_meshing.h): blocks with protective
// collars tile the domain, a clipped field is the parent's field inside its box, and the merged
// mesh keeps every guarantee (checked by isodel verify, independent of the mesher) whatever the
// block size, identically for 1 and 2 threads.
#include <catch2/catch.hpp>

#include "octree/face_slabs.h"
#include "octree/protective_layer.h"
#include "surface/block_mesher.h"
#include "surface/partitioned_meshing.h"
#include "support/mesher_test_support.h"

#include <isodel/errors.h>

#include <atomic>
#include <cmath>
#include <map>

using namespace isodel;

namespace {

openvdb::FloatGrid::Ptr torus_grid()
{
    return testing::make_grid(32, 1.0, openvdb::Vec3d(0.0), [](const openvdb::Vec3d& x) {
        return testing::torus_f(x, openvdb::Vec3d(15.5, 15.3, 15.7), 8.0, 3.0);
    });
}

MeshResult mesh_blocks(const openvdb::FloatGrid& grid, int block_voxels, double eps_voxels, int threads = 0,
                       bool release = false)
{
    MeshOptions mo;
    mo.release_blocks = release;
    mo.isovalue = 0.0;
    mo.inside = Inside::Above;
    mo.eps_voxels = eps_voxels;
    mo.block_voxels = block_voxels;
    mo.threads = threads;
    return mesh_isosurface(grid, mo);
}

VerifyReport verify(const openvdb::FloatGrid& grid, const SurfaceMesh& mesh, double eps_voxels)
{
    VerifyOptions vo;
    vo.isovalue = 0.0;
    vo.inside = Inside::Above;
    vo.eps_voxels = eps_voxels;
    return verify_surface(grid, mesh, vo);
}

} // namespace

TEST_CASE("the blocks' cores tile the domain's cells once, their boxes add the collar", "[mesher][partition]")
{
    const auto grid = torus_grid();
    openvdb::FloatGrid::ConstPtr g = grid;
    const octree::SampleField field(g, 0.0, Inside::Above);
    const auto collar = mesher::collar_voxels(field);
    CHECK(collar == std::array<int, 3>{6, 6, 6}); // 2r + 4, r = 1 on cubic voxels
    const auto blocks = mesher::partition_domain(field, 7, collar);
    const openvdb::CoordBBox cells(field.domain().min(), field.domain().max().offsetBy(-1));
    std::map<openvdb::Coord, int> owners;
    for (const auto& b : blocks) {
        CHECK(b.box.min() == b.core.min().offsetBy(-6));
        CHECK(b.box.max() == b.core.max().offsetBy(1 + 6));
        for (auto it = b.core.beginZYX(); it; ++it)
            if (cells.isInside(*it)) ++owners[*it];
    }
    CHECK(owners.size() == cells.volume());
    for (const auto& [c, n] : owners) REQUIRE(n == 1);
}

TEST_CASE("a clipped field is its parent inside the box and outside beyond it", "[mesher][partition]")
{
    const auto grid = torus_grid();
    openvdb::FloatGrid::ConstPtr g = grid;
    const octree::SampleField field(g, 0.0, Inside::Above);
    const openvdb::CoordBBox box(openvdb::Coord(3, 5, 7), openvdb::Coord(20, 18, 16));
    const octree::SampleField clipped(field, box);
    CHECK(clipped.effective_isovalue() == field.effective_isovalue());
    const octree::SampleField::Reader a(field), b(clipped);
    std::size_t inside = 0;
    for (int z = -2; z < 35; ++z)
        for (int y = -2; y < 35; ++y)
            for (int x = -2; x < 35; ++x) {
                const openvdb::Coord c(x, y, z);
                if (box.isInside(c)) {
                    REQUIRE(b.phi(c) == a.phi(c));
                    ++inside;
                } else {
                    REQUIRE(b.phi(c) == clipped.outside_phi());
                }
            }
    CHECK(inside == box.volume());
    CHECK_THROWS_AS(octree::SampleField(field, openvdb::CoordBBox(openvdb::Coord(100), openvdb::Coord(110))),
                    InvalidInput);
}

TEST_CASE("partitioned meshes verify: topology, eps and Delaunay conformity", "[mesher][partition]")
{
    const auto torus = torus_grid();
    for (int block : {6, 11, 40}) {
        INFO("torus, blocks of " << block << " voxels");
        const MeshResult r = mesh_blocks(*torus, block, 0.25);
        const VerifyReport rep = verify(*torus, r.surface, 0.25);
        INFO(rep.summary());
        CHECK(rep.passed());
        CHECK(rep.topology_verdict == TopologyVerdict::Pass);
        CHECK(r.stats.components.size() == 1);
        CHECK(r.stats.partition.blocks == int(std::pow((32 + 1 + block - 1) / block, 3)));
        // The blocks did the refinement; the merge only fixes seams.
        if (block < 40) CHECK(r.stats.partition.block_points > r.stats.partition.seam_points);
    }
    // Random volumes: every refinement phase, features cut by many block faces. Quantized ones
    // (samples at v: the tie rule's thin features, ~10^3 vertices) are smaller.
    for (unsigned seed : {3u, 11u, 19u, 23u}) {
        for (bool quantized : {false, true}) {
            INFO("random volume seed " << seed << (quantized ? " quantized" : ""));
            const auto grid = testing::random_volume(quantized ? 5 : 10, seed, quantized);
            const MeshResult r = mesh_blocks(*grid, 4, 0.25);
            const VerifyReport rep = verify(*grid, r.surface, 0.25);
            INFO(rep.summary());
            CHECK(rep.passed());
            CHECK(rep.topology_verdict == TopologyVerdict::Pass);
            CHECK(r.stats.partition.exchange_rounds >= 1);
        }
    }
}

TEST_CASE("partitioned meshing gives the same mesh with 1 and 2 threads", "[mesher][partition][determinism]")
{
    // 8 blocks of 8 voxels, each box (collar 4) most of the volume: the blocks overlap as much
    // as they can, and two threads mesh them in a different order than one. (Every block here
    // touches the domain's faces; blocks owning a core on all sides are in the case above.)
    const auto grid = testing::random_volume(12, 7, false);
    const MeshResult a = mesh_blocks(*grid, 8, 0.25, 1);
    const MeshResult b = mesh_blocks(*grid, 8, 0.25, 2);
    CHECK(a.stats.partition.blocks == 8);
    CHECK(a.surface.vertices == b.surface.vertices);
    CHECK(a.surface.triangles == b.surface.triangles);
    CHECK(a.stats.partition.block_points == b.stats.partition.block_points);
}

TEST_CASE("released blocks are rebuilt from their points, the same at 1 and 2 threads, and verify",
          "[mesher][partition][release_blocks]")
{
    // MeshOptions::release_blocks frees each block's triangulation after each pass and builds it
    // again from E, G and its points when a neighbour's arrive. The rebuilt block checks every
    // element again where the kept one checks what changed, so the two may insert different
    // points (the same guarantees); the run is still a function of the blocks alone.
    const auto grid = torus_grid();
    for (const int b : {8, 12}) {
        INFO("B = " << b);
        const MeshResult kept = mesh_blocks(*grid, b, 0.5, 2);
        REQUIRE(kept.stats.partition.exchanged_points > 0); // or nothing is rebuilt
        CHECK(kept.stats.partition.block_rebuilds == 0);
        const MeshResult one = mesh_blocks(*grid, b, 0.5, 1, true);
        const MeshResult two = mesh_blocks(*grid, b, 0.5, 2, true);
        CHECK(two.stats.partition.block_rebuilds > 0);
        CHECK(one.stats.partition.block_rebuilds == two.stats.partition.block_rebuilds);
        CHECK(one.surface.vertices == two.surface.vertices);
        CHECK(one.surface.triangles == two.surface.triangles);
        // E and G come from the field, whatever happens to the blocks.
        CHECK(two.stats.e_points == kept.stats.e_points);
        CHECK(two.stats.g_points == kept.stats.g_points);
        const VerifyReport rep = verify(*grid, two.surface, 0.5);
        INFO(rep.summary());
        CHECK(rep.passed());
        REQUIRE(two.stats.components.size() == 1);
        CHECK(two.stats.components[0].genus == 1);
    }
    MeshOptions mo;
    mo.release_blocks = true; // without blocks
    CHECK_THROWS_WITH(mesh_isosurface(*grid, mo), Catch::Contains("release_blocks"));
}

TEST_CASE("a parked block rebuilt for points it has already keeps its owned facets",
          "[mesher][partition][release_blocks]")
{
    // A rebuild whose received points are all vertices already is followed by no refine(), so
    // its facet records are never computed: the block must go back to its parked state.
    const auto g = torus_grid();
    octree::SampleField field(g, 0.0, Inside::Above);
    field.set_face_slabs(octree::face_slabs_for_eps(0.5));
    MeshOptions mo;
    mo.isovalue = 0.0;
    mo.inside = Inside::Above;
    mo.eps_voxels = 0.5;
    mo.block_voxels = 12;
    const std::array<int, 3> r = octree::layer_radius(field);
    const int margin = *std::max_element(r.begin(), r.end()) + 2;
    int tried = 0;
    for (const auto& spec : mesher::partition_domain(field, 12, mesher::collar_voxels(field))) {
        mesher::BlockMesher block(field, spec, mo, margin, nullptr);
        if (block.empty()) continue;
        block.refine();
        const mesher::BlockSurface before = block.owned_surface();
        const std::vector<mesher::SeedPoint> own = block.take_new_points();
        if (before.triangles.empty() || own.empty()) continue;
        ++tried;
        block.park();
        REQUIRE(block.parked());
        CHECK(block.receive(own) == 0); // its own points: nothing new
        CHECK(block.rebuilds() == 1);
        CHECK(block.parked());
        CHECK(block.owned_surface().triangles == before.triangles);
    }
    CHECK(tried > 0);
}

TEST_CASE("partitioned meshing refuses adaptive grids and bad block sizes", "[mesher][partition]")
{
    const auto grid = torus_grid();
    openvdb::FloatGrid::ConstPtr g = grid;
    const octree::SampleField field(g, 0.0, Inside::Above);
    CHECK_THROWS_AS(mesher::partition_domain(field, 0, {4, 4, 4}), InvalidInput);
    // Blocks smaller than the collar are refused before any work; 4 is the smallest.
    // Refused before any work: no stage polls the interrupter (the blocks' merge used to refuse
    // them only after meshing every block).
    struct CountPolls final : Interrupter {
        std::atomic<int> calls{0};
        bool wasInterrupted(int) override { return ++calls < 0; }
    };
    MeshOptions mo;
    for (int b : {1, 2, 3}) {
        mo.block_voxels = b;
        CHECK_THROWS_WITH(check_mesh_options(mo), Catch::Contains("at least 4") && Catch::Contains("got " + std::to_string(b)));
        CountPolls polls;
        CHECK_THROWS_AS(mesh_isosurface(*grid, mo, &polls), InvalidInput);
        CHECK(polls.calls == 0);
    }
    mo.block_voxels = kMinBlockVoxels;
    CHECK_NOTHROW(check_mesh_options(mo));
    // A box so large that blocks of 8 would number 10^9: refused, not run for hours.
    auto far = openvdb::FloatGrid::create(-1.f);
    far->tree().setValueOn(openvdb::Coord(0), 1.f);
    far->tree().setValueOn(openvdb::Coord(8000), 1.f);
    const octree::SampleField wide(far, 0.0, Inside::Above);
    CHECK_THROWS_WITH(mesher::partition_domain(wide, 8, {4, 4, 4}), Catch::Contains("choose larger blocks"));
    CHECK(mesher::partition_domain(wide, 4000, {4, 4, 4}).size() == 27); // 8003 samples a side: 3 blocks
}


TEST_CASE("partitioned meshing stops when the interrupter asks, from inside the blocks", "[mesher][partition]")
{
    // Counts the calls and cancels at the third: the blocks' own rounds poll it (thread-safely),
    // so the run stops before the merge.
    struct CancelAt final : Interrupter {
        std::atomic<int> calls{0};
        bool wasInterrupted(int) override { return ++calls >= 3; }
    } intr;
    const auto grid = torus_grid();
    MeshOptions mo;
    mo.isovalue = 0.0;
    mo.inside = Inside::Above;
    mo.block_voxels = 8;
    CHECK_THROWS_AS(mesh_isosurface(*grid, mo, &intr), Cancelled);
    CHECK(intr.calls >= 3);
}
