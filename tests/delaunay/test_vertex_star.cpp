// gather_star (src/delaunay/vertex_star.h), the thread-safe replacement for CGAL's incident_cells
// that FacetCache::update and the Theorem-3 check use from several threads: it must find exactly
// the cells CGAL finds around every vertex, on random points and on the cospherical grid points
// of the protective layer (the degenerate case symbolic perturbation resolves), and stay right
// when threads gather overlapping stars at once.
#include "delaunay/vertex_star.h"

#include <catch2/catch.hpp>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace isodel::mesher;

namespace {

std::vector<Cell_handle> sorted(std::vector<Cell_handle> cells)
{
    std::sort(cells.begin(), cells.end());
    return cells;
}

/// gather_star's walk with a linear search of the list for the cells reached, as it was before
/// the hash set: the order the callers rely on (facet_loops.cpp) must be this one.
std::vector<Cell_handle> reference_walk(Vertex_handle v)
{
    std::vector<Cell_handle> out{v->cell()};
    for (std::size_t i = 0; i < out.size(); ++i) {
        const int iv = out[i]->index(v);
        for (int j = 0; j < 4; ++j)
            if (j != iv && std::find(out.begin(), out.end(), out[i]->neighbor(j)) == out.end())
                out.push_back(out[i]->neighbor(j));
    }
    return out;
}

void require_same_stars(const Delaunay& dt)
{
    std::vector<Vertex_handle> vertices;
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) vertices.push_back(v);
    std::vector<std::vector<Cell_handle>> expected(vertices.size()), got(vertices.size());
    for (std::size_t i = 0; i < vertices.size(); ++i) dt.incident_cells(vertices[i], std::back_inserter(expected[i]));
    // Concurrently: neighbouring stars overlap, which is what CGAL's visit marks could not take.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, vertices.size(), 8), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) gather_star(vertices[i], got[i]);
    });
    std::size_t infinite = 0;
    for (std::size_t i = 0; i < vertices.size(); ++i) {
        REQUIRE(got[i].size() == expected[i].size());
        REQUIRE(sorted(got[i]) == sorted(expected[i]));
        REQUIRE(got[i] == reference_walk(vertices[i]));
        infinite += std::count_if(got[i].begin(), got[i].end(), [&](Cell_handle c) { return dt.is_infinite(c); });
    }
    REQUIRE(infinite > 0); // hull vertices' stars include infinite cells
}

} // namespace

TEST_CASE("vertex star: the cells around each vertex, as CGAL's incident_cells finds them", "[mesher][vertex_star]")
{
    SECTION("random points")
    {
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> u(0, 1);
        std::vector<Point> pts;
        for (int i = 0; i < 3000; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
        const Delaunay dt(pts.begin(), pts.end());
        require_same_stars(dt);
    }
    SECTION("a cubic grid with a few off-grid points (cospherical: symbolic perturbation)")
    {
        std::vector<Point> pts;
        for (int z = 0; z < 12; ++z)
            for (int y = 0; y < 12; ++y)
                for (int x = 0; x < 12; ++x) pts.emplace_back(0.5 * x, 0.5 * y, 0.5 * z);
        std::mt19937 rng(11);
        std::uniform_real_distribution<double> u(0.3, 5.2);
        for (int i = 0; i < 200; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
        const Delaunay dt(pts.begin(), pts.end());
        require_same_stars(dt);
    }
    SECTION("hubs: vertices with thousands of cells (the per-thread set grows past its first size)")
    {
        // Points on two spheres around two centres: each centre's star is a cone over its
        // sphere's hull, ~2 cells per sphere point.
        std::mt19937 rng(5);
        std::normal_distribution<double> n(0, 1);
        std::vector<Point> pts{Point(0, 0, 0), Point(10, 0, 0)};
        for (int k = 0; k < 2; ++k)
            for (int i = 0; i < (k == 0 ? 1500 : 90); ++i) {
                const double x = n(rng), y = n(rng), z = n(rng), r = std::sqrt(x * x + y * y + z * z);
                pts.emplace_back(10 * k + x / r, y / r, z / r);
            }
        const Delaunay dt(pts.begin(), pts.end());
        std::vector<Cell_handle> hub;
        gather_star(dt.nearest_vertex(Point(0, 0, 0)), hub);
        REQUIRE(hub.size() > 2000);
        require_same_stars(dt);
    }
}
