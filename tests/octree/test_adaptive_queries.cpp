// Queries on random adaptive grids: point location, neighbours, E points on leaf edges, G, and
// the segment walk (paper Sections 4.1-4.3 on an octree).
#include "support/adaptive_random.h"

#include "support/adaptive_reference.h"
#include "octree/edge_crossings.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

using namespace isodel::octree;

TEST_CASE("leaf containing a point and neighbour symmetry", "[octree][queries]")
{
    auto g = testing::random_adaptive(11, 1, 18, 4);
    AdaptiveGrid::Reader r(*g);
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-1, 18);
    for (int i = 0; i < 500; ++i) {
        const Vec3d p(u(rng), u(rng), u(rng));
        const auto c = leaf_containing(r, p);
        REQUIRE(c);
        const CoordBBox n = c->nodes();
        for (int ax = 0; ax < 3; ++ax) {
            CHECK(p[ax] >= n.min()[ax]);
            CHECK(p[ax] <= n.max()[ax]);
        }
        for (const auto& nb : neighbours(r, *c)) {
            const auto back = neighbours(r, nb.cell);
            const bool found = std::any_of(back.begin(), back.end(), [&](const Neighbour& x) {
                return x.cell == *c && x.contact == nb.contact;
            });
            CHECK(found);
        }
    }
}

TEST_CASE("every E point lies on Sigma and on a leaf edge", "[octree][queries]")
{
    for (unsigned seed = 1; seed <= 10; ++seed)
        for (int k = 1; k <= 3; ++k) {
            auto g = testing::random_adaptive(200 + seed, k, 18, 4, seed % 2 == 0);
            const SampleField field(g->samples_ptr(), 0.0, isodel::Inside::Above);
            const auto E = adaptive_edge_crossings(*g, field);
            REQUIRE(!E.empty());
            InterpolantReader ir(*g);
            const double range = field.value_max() - field.value_min();
            double worst = 0;
            std::set<std::pair<Coord, int>> seen;
            for (const auto& e : E) {
                CHECK(seen.insert({e.edge.start, e.edge.axis}).second); // each leaf edge once
                if (!g->domain().isInside(e.edge.start) || !g->domain().isInside(e.edge.end()))
                    continue; // outside-ring edge: phi beyond the domain is outside_phi
                const auto F = ir.eval(e.point);
                REQUIRE(F);
                worst = std::max(worst, std::abs(field.phi_of_value(*F)));
            }
            INFO("seed " << seed << " k " << k << " |E| " << E.size());
            CHECK(worst <= 1e-12 * range);
            // G holds both endpoints of every crossed leaf edge inside the domain.
            const auto G = adaptive_protective_layer(*g, field);
            for (const auto& e : E)
                if (g->domain().isInside(e.edge.start) && g->domain().isInside(e.edge.end())) {
                    CHECK(std::binary_search(G.begin(), G.end(), e.edge.start));
                    CHECK(std::binary_search(G.begin(), G.end(), e.edge.end()));
                }
        }
}

TEST_CASE("uniform grid: E points equal the uniform edge crossings", "[octree][queries]")
{
    auto s = testing::random_samples(12, 9);
    AdaptiveGrid g(s, 1);
    // v = 0.05 keeps the background 0 strictly outside, so both paths read the ring through the
    // grid (a background at or inside v makes SampleField treat the ring as outside, a rule the
    // adaptive grid does not apply: sample_field.h, "Domain").
    const SampleField field(s, 0.05, isodel::Inside::Above);
    const auto A = adaptive_edge_crossings(g, field);
    const auto U = edge_crossings(field);
    REQUIRE(A.size() == U.points.size());
    std::set<std::pair<Coord, int>> ua;
    for (const auto& p : U.points) ua.insert({p.lower, p.axis});
    for (const auto& e : A) CHECK(ua.count({e.edge.start, e.edge.axis}) == 1);
}

TEST_CASE("segment walk returns the leaves in order, covering the segment", "[octree][queries]")
{
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-3, 21);
    for (unsigned seed = 1; seed <= 6; ++seed) {
        auto g = testing::random_adaptive(300 + seed, 1 + seed % 3, 18, 4);
        AdaptiveGrid::Reader r(*g);
        for (int i = 0; i < 200; ++i) {
            Vec3d a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
            if (i % 10 == 0) b = Vec3d(a.x(), a.y(), b.z()); // axis-aligned, on lattice lines
            if (i % 10 == 1) a = Vec3d(std::round(a.x()), std::round(a.y()), std::round(a.z()));
            const auto pieces = walk_segment(r, a, b);
            for (std::size_t j = 0; j < pieces.size(); ++j) {
                const auto& pc = pieces[j];
                CHECK(pc.t0 <= pc.t1);
                if (j) CHECK(pc.t0 == pieces[j - 1].t1);
                if (j) CHECK(pc.cell != pieces[j - 1].cell);
                CHECK(r.is_leaf(pc.cell));
                const Vec3d m = a + (b - a) * (0.5 * (pc.t0 + pc.t1));
                const CoordBBox n = pc.cell.nodes();
                for (int ax = 0; ax < 3; ++ax) {
                    CHECK(m[ax] >= n.min()[ax] - 1e-9);
                    CHECK(m[ax] <= n.max()[ax] + 1e-9);
                }
            }
            // Coverage: the pieces span the part of [0,1] inside the domain.
            const CoordBBox& d = g->domain();
            auto in_dom = [&](double t) {
                const Vec3d p = a + (b - a) * t;
                for (int ax = 0; ax < 3; ++ax)
                    if (p[ax] < d.min()[ax] || p[ax] > d.max()[ax]) return false;
                return true;
            };
            for (int s = 0; s <= 20; ++s) {
                const double t = s / 20.0;
                if (!in_dom(t)) continue;
                REQUIRE(!pieces.empty());
                CHECK(t >= pieces.front().t0 - 1e-12);
                CHECK(t <= pieces.back().t1 + 1e-12);
            }
        }
    }
}
