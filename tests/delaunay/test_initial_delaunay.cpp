// build_initial_delaunay (src/delaunay/initial_delaunay.h): with two threads it inserts in parallel
// into CGAL's concurrent triangulation and copies the result (its own copy, with array maps and
// parallel pointer setting, in place of copy_tds). The copy must be the triangulation the
// sequential insertion builds: the same cells over the same vertices, every vertex keeping its
// point and info, every incidence and neighbour pointer right (is_valid), on the cospherical
// points of a grid (the degenerate case of the protective layer) mixed with grid-edge points.
#include "delaunay/initial_delaunay.h"

#include <isodel/errors.h>
#include <isodel/interrupt.h>

#include <catch2/catch.hpp>

#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <random>
#include <string>
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
void build(Delaunay& dt, const std::vector<std::pair<Point, VertexInfo>>& points, int threads,
           const isodel::InterruptScope* scope = nullptr)
{
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    build_initial_delaunay(dt, points, scope);
}

/// A n^3 grid (cospherical points) and 3000 points on its edges, with ids and mixed kinds.
std::vector<std::pair<Point, VertexInfo>> grid_and_edge_points(int n)
{
    std::vector<std::pair<Point, VertexInfo>> points;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> t(0.05, 0.95);
    std::uniform_int_distribution<int> cell(0, n - 2);
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
    return points;
}

/// Records the Delaunay stage's polls; cancels at the \p cancel_at-th when it is non-zero.
struct PollCounter final : isodel::Interrupter {
    std::vector<std::uint64_t> done;
    std::uint64_t total = 0;
    std::size_t cancel_at = 0;
    bool progress(std::uint64_t d, std::uint64_t t, const char* unit) override
    {
        CHECK(std::string(unit) == "points");
        done.push_back(d);
        total = t;
        return cancel_at != 0 && done.size() >= cancel_at;
    }
};

} // namespace

TEST_CASE("the parallel initial Delaunay and its copy equal the sequential one", "[mesher][initial_delaunay]")
{
    const auto points = grid_and_edge_points(28);
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

TEST_CASE("the initial Delaunay polls for a cancel as the points go in", "[mesher][initial_delaunay]")
{
    // The largest single step of a run: a cancel (Ctrl-C in Python) must stop it part-way, not
    // wait for its end. 42^3 + 3000 points, inserted sequentially (the parallel insertion is
    // one CGAL call, initial_delaunay.h).
    const auto points = grid_and_edge_points(42);
    {
        const int threads = 1;
        CAPTURE(threads);
        PollCounter polls;
        {
            isodel::InterruptScope scope(&polls, "delaunay");
            Delaunay dt;
            build(dt, points, threads, &scope);
            REQUIRE(dt.number_of_vertices() == points.size());
        }
        REQUIRE(polls.total == points.size());
        REQUIRE(polls.done.size() >= 4); // several polls, spread over the insertion
        CHECK(std::is_sorted(polls.done.begin(), polls.done.end()));
        CHECK(polls.done.back() >= points.size() / 2);

        PollCounter cancelling;
        cancelling.cancel_at = 2;
        isodel::InterruptScope scope(&cancelling, "delaunay");
        Delaunay dt;
        CHECK_THROWS_AS(build(dt, points, threads, &scope), isodel::Cancelled);
        CHECK(cancelling.done.size() == 2); // it stopped at the poll that asked
        CHECK(cancelling.done.back() < points.size());
    }
}
