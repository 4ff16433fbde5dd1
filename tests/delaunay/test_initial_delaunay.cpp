// build_initial_delaunay (src/delaunay/initial_delaunay.h): with two threads it inserts in parallel
// into CGAL's concurrent triangulation and copies the result (its own copy, with array maps and
// parallel pointer setting, in place of copy_tds). The copy must be the triangulation the
// sequential insertion builds: the same cells over the same vertices, every vertex keeping its
// point and info, every incidence and neighbour pointer right (is_valid), on the cospherical
// points of a grid (the degenerate case of the protective layer) mixed with grid-edge points.
#include "delaunay/initial_delaunay.h"

#include <catch2/catch.hpp>

#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <random>
#include <vector>

using namespace isodel::mesher;

namespace {

std::vector<std::array<std::uint32_t, 4>> finite_cells(const Delaunay& dt)
{
    std::vector<std::array<std::uint32_t, 4>> out;
    for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
        std::array<std::uint32_t, 4> k;
        for (int i = 0; i < 4; ++i) k[i] = c->vertex(i)->info().id;
        std::sort(k.begin(), k.end());
        out.push_back(k);
    }
    std::sort(out.begin(), out.end());
    return out;
}

// Into \p dt itself: a returned triangulation could be a deep copy (copy_tds), not the one
// build_initial_delaunay made.
void build(Delaunay& dt, const std::vector<std::pair<Point, VertexInfo>>& points, int threads)
{
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    build_initial_delaunay(dt, points);
}

} // namespace

TEST_CASE("the parallel initial Delaunay and its copy equal the sequential one", "[mesher][initial_delaunay]")
{
    // A 28^3 grid (21952 points: above the parallel threshold) and points on grid edges.
    std::vector<std::pair<Point, VertexInfo>> points;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> t(0.05, 0.95);
    std::uniform_int_distribution<int> cell(0, 26);
    const int n = 28;
    for (int x = 0; x < n; ++x)
        for (int y = 0; y < n; ++y)
            for (int z = 0; z < n; ++z) points.push_back({Point(0.5 * x, 0.5 * y, 0.5 * z), VertexInfo{}});
    for (int i = 0; i < 3000; ++i) {
        const int axis = i % 3;
        double c[3] = {double(cell(rng)), double(cell(rng)), double(cell(rng))};
        c[axis] += t(rng);
        points.push_back({Point(0.5 * c[0], 0.5 * c[1], 0.5 * c[2]), VertexInfo{}});
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
        points[i].second.id = std::uint32_t(i);
        points[i].second.kind = i % 3 == 0 ? PointKind::Grid : i % 3 == 1 ? PointKind::Edge : PointKind::Topology;
    }

    Delaunay seq, par;
    build(seq, points, 1);
    build(par, points, 2);
    REQUIRE(seq.is_valid());
    REQUIRE(par.is_valid());
    REQUIRE(par.dimension() == 3);
    REQUIRE(par.number_of_vertices() == points.size());
    REQUIRE(par.number_of_cells() == seq.number_of_cells());
    // Every vertex keeps its point and info, and its stored cell holds it (set_cell).
    std::size_t wrong = 0;
    for (auto v = par.finite_vertices_begin(); v != par.finite_vertices_end(); ++v) {
        const auto& [p, info] = points[v->info().id];
        wrong += v->point() != p || v->info().kind != info.kind || !v->cell()->has_vertex(v);
    }
    REQUIRE(wrong == 0);
    REQUIRE(finite_cells(par) == finite_cells(seq));
}
