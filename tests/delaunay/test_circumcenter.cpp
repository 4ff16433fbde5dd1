// robust_circumcenter(Cell_handle) (src/delaunay/circumcenter.h) keeps each cell's Voronoi vertex
// in the cell (cell_base.h). The kept value must be, bit for bit, what a fresh computation gives,
// whatever happened since: cells destroyed by insertions and removals and their storage reused
// by new cells (an uninitialised state byte fails here), and threads asking for the same cells
// at once, as the checks do through overlapping vertex stars. A copied triangulation is checked
// too, though a copied cache would hold the right values (same points, same ids): what a copy
// must not have is a state byte saying ready over no value. The points are a grid (cospherical:
// the nearly flat cells that take the exact fallback) and grid-edge points, as in the mesher.
#include "delaunay/circumcenter.h"
#include "delaunay/vertex_star.h"

#include <catch2/catch.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <random>
#include <vector>

using namespace isodel::mesher;

namespace {

/// The uncached computation, as circumcenter.h defines it.
Point fresh(const Cell_handle& c)
{
    std::array<Vertex_handle, 4> v{c->vertex(0), c->vertex(1), c->vertex(2), c->vertex(3)};
    std::sort(v.begin(), v.end(), [](Vertex_handle a, Vertex_handle b) { return a->info().id < b->info().id; });
    return robust_circumcenter(v[0]->point(), v[1]->point(), v[2]->point(), v[3]->point());
}

bool same(const Point& a, const Point& b) { return a.x() == b.x() && a.y() == b.y() && a.z() == b.z(); }

/// Cells whose kept circumcentre differs from a fresh one. First through the stars of all
/// vertices in parallel, as the mesher's checks ask: a cell lies in four stars, so threads ask
/// for one cell at once (the first to claim it writes, the others compute it themselves); then
/// every cell once more, which reads the kept value.
std::size_t mismatches(const Delaunay& dt)
{
    std::vector<Vertex_handle> vertices;
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) vertices.push_back(v);
    std::vector<char> bad_star(vertices.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, vertices.size(), 1), [&](const auto& r) {
        std::vector<Cell_handle> star;
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            gather_star(vertices[i], star);
            for (const Cell_handle& c : star)
                if (!dt.is_infinite(c) && !same(robust_circumcenter(c), fresh(c))) bad_star[i] = 1;
        }
    });
    std::vector<Cell_handle> cells;
    for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) cells.push_back(c);
    std::vector<char> bad(cells.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.size(), 16), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i)
            if (!same(robust_circumcenter(cells[i]), fresh(cells[i]))) bad[i] = 1;
    });
    return std::size_t(std::count(bad_star.begin(), bad_star.end(), 1) + std::count(bad.begin(), bad.end(), 1));
}

} // namespace

TEST_CASE("a cell's kept circumcentre is a fresh computation's, through insertions, removals and copies",
          "[mesher][circumcenter]")
{
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> t(0.05, 0.95);
    std::uniform_int_distribution<int> cell(0, 10);
    std::uint32_t id = 0;
    std::vector<std::pair<Point, VertexInfo>> points;
    for (int x = 0; x < 12; ++x)
        for (int y = 0; y < 12; ++y)
            for (int z = 0; z < 12; ++z) points.push_back({Point(x, y, z), VertexInfo{id++, PointKind::Grid}});
    Delaunay dt(points.begin(), points.end());
    REQUIRE(dt.is_valid());
    REQUIRE(mismatches(dt) == 0);

    // Grid-edge points into the filled triangulation: the conflict cells die, and their storage
    // is handed to the new cells, whose circumcentres differ from the old ones.
    std::vector<Vertex_handle> inserted;
    for (int i = 0; i < 600; ++i) {
        double c[3] = {double(cell(rng)), double(cell(rng)), double(cell(rng))};
        c[i % 3] += t(rng);
        const Vertex_handle v = dt.insert(Point(c[0], c[1], c[2]));
        v->info() = VertexInfo{id++, PointKind::Edge};
        inserted.push_back(v);
        if (i % 100 == 99) REQUIRE(mismatches(dt) == 0);
    }
    // Removals: the hole's new cells again reuse freed storage.
    for (std::size_t i = 0; i < inserted.size(); i += 3) dt.remove(inserted[i]);
    REQUIRE(dt.is_valid());
    REQUIRE(mismatches(dt) == 0);
    for (int i = 0; i < 200; ++i) {
        double c[3] = {double(cell(rng)), double(cell(rng)), double(cell(rng))};
        c[(i + 1) % 3] += t(rng);
        dt.insert(Point(c[0], c[1], c[2]))->info() = VertexInfo{id++, PointKind::Topology};
    }
    REQUIRE(mismatches(dt) == 0);

    // A copy starts with its own caches, and a copy assigned over a filled triangulation too.
    const Delaunay copy(dt);
    REQUIRE(copy.number_of_finite_cells() == dt.number_of_finite_cells());
    REQUIRE(mismatches(copy) == 0);
    Delaunay other(points.begin(), points.begin() + 500);
    REQUIRE(mismatches(other) == 0);
    other = dt;
    REQUIRE(mismatches(other) == 0);
}
