// A batch of candidate points enters the triangulation in origin order, skipping each one that
// lies closer than half its spacing to a point accepted earlier in the batch (looked for in the
// hash cells within min(2, ceil(r / cell)) of its own) or that is already a vertex
// (src/delaunay/point_insertion.h). Checked against that rule written out directly, on clusters
// of candidates where both verdicts occur many times. The vertex a candidate names
// (Candidate::near) only starts the walk to its point: the same vertices, ids and triangulation
// as without it, with removed and far vertices named too.
#include <catch2/catch.hpp>

#include "delaunay/point_insertion.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>
#include <tuple>
#include <vector>

using namespace isodel;
using namespace isodel::mesher;

TEST_CASE("point insertion: a candidate is skipped near an earlier accepted one or on a vertex, in origin order",
          "[mesher][insertion]")
{
    const double cell = 0.25;
    for (unsigned seed = 1; seed <= 3; ++seed) {
        INFO("seed " << seed);
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> U(0.0, 1.0);
        Delaunay dt;
        std::uint32_t id = 0;
        for (int z = 0; z <= 4; ++z)
            for (int y = 0; y <= 4; ++y)
                for (int x = 0; x <= 4; ++x) dt.insert(Point(x, y, z))->info() = VertexInfo{id++, PointKind::Grid};
        FacetCache cache;
        // Clusters around 40 centres (so many candidates fall near each other), spacings from a
        // tenth of a hash cell to 3 cells (r beyond the 2-cell window too), some on grid points.
        std::vector<Candidate> candidates;
        std::vector<Point> centres;
        for (int i = 0; i < 40; ++i) centres.emplace_back(0.5 + 3 * U(rng), 0.5 + 3 * U(rng), 0.5 + 3 * U(rng));
        for (std::uint32_t i = 0; i < 3000; ++i) {
            Point p;
            if (i % 97 == 0) {
                p = Point(std::floor(5 * U(rng)), std::floor(5 * U(rng)), std::floor(5 * U(rng)));
            } else {
                const Point& c = centres[i % centres.size()];
                p = Point(c.x() + 0.6 * (U(rng) - 0.5), c.y() + 0.6 * (U(rng) - 0.5), c.z() + 0.6 * (U(rng) - 0.5));
            }
            const double spacing = cell * (0.1 + 5.9 * U(rng) * U(rng));
            // Origins in a shuffled order: the batch sorts them.
            candidates.push_back({p, PointKind::Topology, spacing, FacetKey{{(i * 7919u) % 3000u, 0, 0}}});
        }

        // The rule, directly: origin order; the window of cells; exact duplicates of vertices.
        std::vector<Candidate> sorted = candidates;
        std::sort(sorted.begin(), sorted.end(), [](const Candidate& a, const Candidate& b) { return a.origin < b.origin; });
        std::vector<Point> expected, vertices;
        for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) vertices.push_back(v->point());
        const auto cell_of = [&](double x) { return long(std::floor(x / cell)); };
        int skipped_near = 0, skipped_vertex = 0, beyond_window = 0;
        for (const Candidate& c : sorted) {
            const double r = 0.5 * c.spacing;
            const long reach = std::min<long>(2, long(std::ceil(r / cell)));
            bool close = false;
            for (const Point& q : expected) {
                const bool in_window = std::abs(cell_of(q.x()) - cell_of(c.p.x())) <= reach &&
                                       std::abs(cell_of(q.y()) - cell_of(c.p.y())) <= reach &&
                                       std::abs(cell_of(q.z()) - cell_of(c.p.z())) <= reach;
                if (CGAL::squared_distance(q, c.p) < r * r) {
                    if (in_window) close = true;
                    else ++beyond_window;
                }
            }
            if (close) {
                ++skipped_near;
                continue;
            }
            if (std::find(vertices.begin(), vertices.end(), c.p) != vertices.end()) {
                ++skipped_vertex;
                continue;
            }
            expected.push_back(c.p);
            vertices.push_back(c.p);
        }
        CHECK(skipped_near > 100);
        CHECK(skipped_vertex > 0);
        CHECK(beyond_window > 0);
        // More occupied cells than the table's first 1024 slots hold at half load: it grows.
        std::set<std::tuple<long, long, long>> occupied;
        for (const Point& q : expected) occupied.emplace(cell_of(q.x()), cell_of(q.y()), cell_of(q.z()));
        CHECK(occupied.size() > 512);

        const std::uint32_t first = id;
        const InsertionResult got = insert_candidates(dt, cache, candidates, id, cell);
        REQUIRE(got.inserted.size() == expected.size());
        CHECK(id == first + expected.size());
        for (std::size_t i = 0; i < expected.size(); ++i) {
            CHECK(got.inserted[i]->point() == expected[i]);
            CHECK(got.inserted[i]->info().id == first + i);
        }
        CHECK(dt.is_valid());
        CHECK(dt.number_of_vertices() == 125 + expected.size());
    }
}

TEST_CASE("point insertion: the vertex a candidate names only starts the walk", "[mesher][insertion]")
{
    // The same candidates inserted from the vertices they name (random ones, some far from the
    // point, some removed before) and from the last inserted point: the same vertices, ids and
    // triangulation.
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    const auto grid = [](Delaunay& dt, std::uint32_t& id) {
        for (int z = 0; z <= 5; ++z)
            for (int y = 0; y <= 5; ++y)
                for (int x = 0; x <= 5; ++x) dt.insert(Point(x, y, z))->info() = VertexInfo{id++, PointKind::Grid};
    };
    std::vector<Candidate> named, unnamed;
    for (std::uint32_t i = 0; i < 2000; ++i) {
        const Point p(5 * U(rng), 5 * U(rng), 5 * U(rng));
        const FacetKey origin{{(i * 7919u) % 2000u, 0, 0}};
        named.push_back({p, PointKind::Topology, 0.01, origin, std::uint32_t(U(rng) * 216)});
        unnamed.push_back({p, PointKind::Topology, 0.01, origin});
    }
    Delaunay a, b;
    std::uint32_t id_a = 0, id_b = 0;
    grid(a, id_a);
    grid(b, id_b);
    FacetCache cache_a, cache_b;
    // Index a's vertices, then remove three that candidates name: those start from elsewhere.
    std::vector<Vertex_handle> gone;
    for (auto v = a.finite_vertices_begin(); v != a.finite_vertices_end(); ++v)
        if (v->info().id == 5 || v->info().id == 100 || v->info().id == 150) gone.push_back(v);
    REQUIRE(cache_a.cell_near(a, 100) != Cell_handle());
    cache_a.remove(a, gone);
    cache_b.remove(b, [&] {
        std::vector<Vertex_handle> g;
        for (auto v = b.finite_vertices_begin(); v != b.finite_vertices_end(); ++v)
            if (v->info().id == 5 || v->info().id == 100 || v->info().id == 150) g.push_back(v);
        return g;
    }());
    CHECK(cache_a.cell_near(a, 100) == Cell_handle());
    CHECK(cache_a.cell_near(a, 9999) == Cell_handle());

    const InsertionResult ga = insert_candidates(a, cache_a, named, id_a, 0.25);
    const InsertionResult gb = insert_candidates(b, cache_b, unnamed, id_b, 0.25);
    REQUIRE(ga.inserted.size() == gb.inserted.size());
    CHECK(ga.inserted.size() > 1500);
    for (std::size_t i = 0; i < ga.inserted.size(); ++i) {
        CHECK(ga.inserted[i]->point() == gb.inserted[i]->point());
        CHECK(ga.inserted[i]->info().id == gb.inserted[i]->info().id);
    }
    // The index follows the insertions: an inserted point's cell has it as a vertex.
    const Cell_handle c = cache_a.cell_near(a, ga.inserted.back()->info().id);
    REQUIRE(c != Cell_handle());
    CHECK(c->has_vertex(ga.inserted.back()));
    const auto cells = [](const Delaunay& dt) {
        std::vector<std::array<std::uint32_t, 4>> out;
        for (auto cc = dt.finite_cells_begin(); cc != dt.finite_cells_end(); ++cc) {
            std::array<std::uint32_t, 4> ids{cc->vertex(0)->info().id, cc->vertex(1)->info().id, cc->vertex(2)->info().id,
                                             cc->vertex(3)->info().id};
            std::sort(ids.begin(), ids.end());
            out.push_back(ids);
        }
        std::sort(out.begin(), out.end());
        return out;
    };
    CHECK(a.is_valid());
    CHECK(cells(a) == cells(b));
}
