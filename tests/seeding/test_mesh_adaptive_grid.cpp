// Property IV on the leaves: mesh_isosurface(AdaptiveVolume) takes E from leaf edges, G from
// the leaves around crossed leaves and counts the voxel bound in leaves (
// src/seeding/adaptive_points.h). Pinned down here:
//  - its E points are exactly the octree module's own leaf-edge crossings (an independent
//    implementation, tests/support/adaptive_reference.h), and its G contains that module's layer;
//  - leaves_in_box and is_leaf_node agree with brute force over unit cells;
//  - on random k-balanced grids (k = 1, 2) whose coarse leaves Sigma crosses, the mesh verifies
//    (topology, Hausdorff, Delaunay) against the resampled dense F, the measured voxel bounds
//    stay within 3k+1 (E) and the stated N bound, with fewer E and G points than meshing the
//    dense resampling, with --snap too, and 1 and 2 threads give the same mesh.
#include <catch2/catch.hpp>

#include "seeding/adaptive_points.h"
#include "support/adaptive_reference.h"
#include "octree/edge_crossings.h"
#include "octree/protective_layer.h"
#include "octree/resample.h"
#include "support/adaptive_random.h"

#include <isodel/adaptive.h>
#include <isodel/mesh.h>
#include <isodel/verify.h>

#include <algorithm>
#include <set>

using namespace isodel;
using octree::AdaptiveGrid;
using octree::CellId;

namespace {

AdaptiveVolume volume_of(const AdaptiveGrid& g)
{
    AdaptiveVolume v;
    v.samples = openvdb::ConstPtrCast<openvdb::FloatGrid>(g.samples_ptr());
    v.levels = g.masks();
    v.domain = g.domain();
    v.k = g.k();
    return v;
}

} // namespace

TEST_CASE("adaptive E points are the leaf-edge crossings and G holds the leaf layer", "[mesher][adaptive]")
{
    for (unsigned seed = 1; seed <= 6; ++seed)
        for (int k : {1, 2}) {
            INFO("seed " << seed << " k " << k);
            const auto g = octree::testing::random_adaptive(seed, k, 12, 2);
            REQUIRE(g->max_level() >= 1);
            const auto dense = octree::resample_dense(*g);
            const octree::SampleField field(dense, 0.0, Inside::Above);
            const octree::SampleField raw(g->samples_ptr(), 0.0, Inside::Above);
            const AdaptiveGrid::Reader r(*g);

            auto e = octree::edge_crossings(field);
            std::vector<openvdb::Vec3d> mine;
            std::size_t beyond = 0;
            openvdb::CoordBBox lattice = g->domain();
            lattice.expand(-1);
            for (const auto& p : e.points) {
                openvdb::Coord upper = p.lower;
                upper[p.axis] += 1;
                // Compared inside the sample lattice: on the domain's outer ring the mesher
                // reads a background equal to v as outside (octree/sample_field.h, "Domain"),
                // the octree module does not yet (a known gap of decimated grids).
                if (!lattice.isInside(p.lower) || !lattice.isInside(upper)) {
                    ++beyond;
                    continue;
                }
                if (mesher::on_leaf_edge(r, p.lower, p.axis)) mine.push_back(p.index_pos);
            }
            std::vector<openvdb::Vec3d> theirs;
            for (const auto& x : octree::adaptive_edge_crossings(*g, raw))
                if (lattice.isInside(x.edge.start) && lattice.isInside(x.edge.end())) theirs.push_back(x.point);
            CHECK(beyond > 0);
            REQUIRE(mine.size() == theirs.size());
            // Matched by nearest point (a lexicographic sort pairs near-ties unpredictably).
            double worst = 0;
            for (const auto& p : mine) {
                double best = INFINITY;
                for (const auto& t : theirs) best = std::min(best, (t - p).length());
                worst = std::max(worst, best);
            }
            CHECK(worst < 1e-5); // the dense samples are the leaves' values rounded to float

            const auto layer = mesher::adaptive_protective_layer(*g, e.crossed_cells, {1, 1, 1});
            const std::set<openvdb::Coord> have(layer.begin(), layer.end());
            std::size_t missing = 0;
            for (const auto& c : octree::adaptive_protective_layer(*g, raw)) missing += !have.count(c);
            CHECK(missing == 0);
            CHECK(layer.size() < std::size_t(octree::protective_layer(field, e.crossed_cells).points.size()));
        }
}

TEST_CASE("leaves_in_box and is_leaf_node agree with brute force", "[mesher][adaptive]")
{
    for (unsigned seed = 1; seed <= 4; ++seed) {
        const auto g = octree::testing::random_adaptive(seed, 1 + seed % 2, 12, 3);
        const AdaptiveGrid::Reader r(*g);
        std::mt19937 rng(seed);
        std::uniform_int_distribution<int> pos(-4, 14), len(0, 6);
        for (int t = 0; t < 200; ++t) {
            const openvdb::Coord lo(pos(rng), pos(rng), pos(rng));
            const openvdb::CoordBBox box(lo, lo.offsetBy(len(rng), len(rng), len(rng)));
            std::set<CellId> leaves;
            int outside = 0;
            for (auto u = box.begin(); u; ++u) {
                if (const auto l = r.leaf(*u)) leaves.insert(*l);
                else ++outside;
            }
            REQUIRE(mesher::leaves_in_box(r, box) == int(leaves.size()) + outside);
        }
        for (int t = 0; t < 500; ++t) {
            const openvdb::Coord n(pos(rng), pos(rng), pos(rng));
            bool corner = false;
            for (int m = 0; m < 8; ++m) {
                const auto u = n.offsetBy(-(m & 1), -((m >> 1) & 1), -((m >> 2) & 1));
                const auto l = r.leaf(u);
                const CellId c = l ? *l : CellId{u, 0};
                bool all = true;
                for (int a = 0; a < 3; ++a)
                    all = all && (n[a] == c.origin[a] || n[a] == c.origin[a] + c.size());
                corner = corner || all;
            }
            REQUIRE(mesher::is_leaf_node(r, n) == corner);
        }
    }
}

TEST_CASE("random adaptive grids mesh with guarantees I-III and the leaf voxel bound", "[mesher][adaptive]")
{
    std::size_t e_adaptive = 0, e_dense = 0, g_adaptive = 0, g_dense = 0, snapped = 0;
    for (unsigned seed = 1; seed <= 8; ++seed)
        for (int k : {1, 2}) {
            const bool smooth = seed % 2 == 0;
            INFO("seed " << seed << " k " << k << (smooth ? " smooth" : " random"));
            const auto g = octree::testing::random_adaptive(seed, k, 12, 2, smooth);
            const AdaptiveVolume av = volume_of(*g);
            MeshOptions mo;
            mo.isovalue = 0;
            mo.inside = Inside::Above;
            mo.eps_voxels = 0.5;
            mo.threads = 2;
            const MeshResult m = mesh_isosurface(av, mo);
            const auto dense = resample(av);
            VerifyOptions vo;
            vo.isovalue = 0;
            vo.inside = Inside::Above;
            vo.eps_voxels = 0.5;
            const VerifyReport rep = verify_surface(*dense, m.surface, vo);
            INFO(rep.summary());
            CHECK(rep.reference.determined);
            CHECK(rep.passed());
            CHECK(m.stats.bound_e == 3 * k + 1);
            CHECK(m.stats.max_cells_e <= m.stats.bound_e);
            CHECK(m.stats.max_cells_n <= m.stats.bound_n);

            const MeshResult u = mesh_isosurface(*dense, mo);
            e_adaptive += m.stats.e_points;
            e_dense += u.stats.e_points;
            g_adaptive += m.stats.g_points;
            g_dense += u.stats.g_points;
            if (seed <= 4) {
                // --snap on leaves: only G points may replace E points (adaptive_points.h).
                MeshOptions so = mo;
                so.snap = true;
                const MeshResult sm = mesh_isosurface(av, so);
                const VerifyReport srep = verify_surface(*dense, sm.surface, vo);
                INFO("snap: " << srep.summary());
                CHECK(srep.passed());
                snapped += sm.stats.snapped;
            }
            if (seed == 1) {
                mo.threads = 1;
                const MeshResult one = mesh_isosurface(av, mo);
                CHECK(one.surface.vertices == m.surface.vertices);
                CHECK(one.surface.triangles == m.surface.triangles);
            }
        }
    INFO("E " << e_adaptive << " vs " << e_dense << ", G " << g_adaptive << " vs " << g_dense);
    CHECK(e_adaptive < e_dense);
    CHECK(g_adaptive < g_dense);
    CHECK(snapped > 0);
}
