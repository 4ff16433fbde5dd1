// The grid-cell check (Theorem 3, src/closed_ball/grid_cell_check.h) answers in two ways: cell by cell
// when most grid points are pending (the first check: every Voronoi vertex computed once), and
// star by star otherwise. Both must give every grid point the same candidate, the crossing
// farthest from it, and keep the same points pending.
#include <catch2/catch.hpp>

#include "support/mesher_test_support.h"

#include "closed_ball/grid_cell_check.h"
#include "octree/sample_field.h"

#include <random>

using namespace isodel;
using namespace isodel::mesher;

TEST_CASE("grid-cell check: the cell-by-cell scan equals the star-by-star check", "[mesher][grid_cell_check]")
{
    std::size_t violations = 0;
    for (unsigned seed = 1; seed <= 3; ++seed) {
        INFO("random 6^3 volume, seed " << seed);
        const auto grid = testing::random_volume(6, seed, false);
        const octree::SampleField field(grid, 0.0, Inside::Above);
        // The 8^3 grid points and random points standing in for E: Voronoi cells of grid points
        // then reach across Sigma in many places.
        Delaunay dt;
        std::uint32_t id = 0;
        for (int z = 0; z <= 7; ++z)
            for (int y = 0; y <= 7; ++y)
                for (int x = 0; x <= 7; ++x) dt.insert(Point(x, y, z))->info() = VertexInfo{id++, PointKind::Grid};
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> u(0.5, 6.5);
        for (int i = 0; i < 120; ++i) {
            const Vertex_handle v = dt.insert(Point(u(rng), u(rng), u(rng)));
            v->info() = VertexInfo{id++, PointKind::Edge};
        }
        std::vector<Vertex_handle> all;
        for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
            if (v->info().kind == PointKind::Grid) all.push_back(v);
        std::sort(all.begin(), all.end(), [](Vertex_handle a, Vertex_handle b) { return a->info().id < b->info().id; });

        // All of G, then every other grid point (cells with non-pending grid points too): both
        // still a quarter of the vertices or more, the cell-by-cell path.
        std::vector<Vertex_handle> half;
        for (std::size_t i = 0; i < all.size(); i += 2) half.push_back(all[i]);
        for (const auto* subset : {&all, &half}) {
            REQUIRE(4 * subset->size() >= dt.number_of_vertices());
            std::vector<Vertex_handle> pending = *subset;
            const std::vector<Candidate> by_cells = grid_cell_violations(dt, field, pending, 1000);

            std::vector<Candidate> by_stars;
            std::vector<Vertex_handle> still;
            for (const Vertex_handle& g : *subset) {
                std::vector<Vertex_handle> one{g}; // one of ~630 pending: the star path
                const auto c = grid_cell_violations(dt, field, one, 1000);
                by_stars.insert(by_stars.end(), c.begin(), c.end());
                still.insert(still.end(), one.begin(), one.end());
            }
            REQUIRE(by_cells.size() == by_stars.size());
            for (std::size_t i = 0; i < by_cells.size(); ++i) {
                CHECK(by_cells[i].p == by_stars[i].p);
                CHECK(by_cells[i].spacing == by_stars[i].spacing);
                CHECK(by_cells[i].origin == by_stars[i].origin);
            }
            CHECK(pending == still);
            violations += by_cells.size();
        }
    }
    CHECK(violations > 20);
}
