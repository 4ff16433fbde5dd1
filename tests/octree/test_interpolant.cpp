// Continuity of the adaptive interpolant (hanging-node constraints, interpolant.h) and its
// restriction to segments (paper Section 4.3: a cubic for trilinear).
#include "support/adaptive_random.h"

#include "support/adaptive_reference.h"
#include "octree/interpolant.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace isodel::octree;

TEST_CASE("uniform grid: F interpolates the samples, no constraints", "[octree][interpolant]")
{
    auto s = testing::random_samples(6, 2);
    AdaptiveGrid g(s, 1);
    InterpolantReader ir(g);
    auto acc = s->getConstAccessor();
    for (auto it = g.domain().begin(); it; ++it) CHECK(ir.node_value(*it) == double(acc.getValue(*it)));
    const double c[8] = {0, 1, 2, 3, 4, 5, 6, 7};
    CHECK(trilinear().eval(c, Vec3d(0.5, 0.5, 0.5)) == Approx(3.5));
}

TEST_CASE("F agrees from both sides of every coarse-fine interface", "[octree][interpolant]")
{
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> u01(0, 1);
    std::size_t interfaces = 0, points = 0;
    for (int k = 1; k <= 3; ++k)
        for (unsigned seed = 1; seed <= 8; ++seed) {
            auto g = testing::random_adaptive(100 + seed, k, 18, 4);
            InterpolantReader ir(*g);
            double worst = 0;
            for (int l = 1; l <= g->max_level(); ++l)
                for (const CellId& c : g->leaves(l))
                    for (const auto& n : neighbours(ir.cells(), c)) {
                        if (n.cell.level >= c.level) continue; // coarse-fine pairs, coarse side = c
                        ++interfaces;
                        // Shared part of the closed spans: a face, an edge or a vertex.
                        CoordBBox a = c.nodes(), b = n.cell.nodes();
                        Vec3d lo, hi;
                        for (int ax = 0; ax < 3; ++ax) {
                            lo[ax] = std::max(a.min()[ax], b.min()[ax]);
                            hi[ax] = std::min(a.max()[ax], b.max()[ax]);
                        }
                        for (int i = 0; i < 6; ++i) {
                            Vec3d p;
                            for (int ax = 0; ax < 3; ++ax) p[ax] = lo[ax] + u01(rng) * (hi[ax] - lo[ax]);
                            const double fc = ir.eval_in(c, p), ff = ir.eval_in(n.cell, p);
                            worst = std::max(worst, std::abs(fc - ff));
                            ++points;
                        }
                    }
            INFO("k = " << k << " seed = " << seed);
            CHECK(worst <= 1e-12 * 2.0); // samples in [-1, 1]: value range 2
        }
    CHECK(interfaces > 1000);
    WARN("interface continuity: " << interfaces << " coarse-fine contacts, " << points << " points");
}

TEST_CASE("restriction to a segment inside a cell is the cubic of F", "[octree][interpolant]")
{
    auto g = testing::random_adaptive(7, 2, 18, 4);
    InterpolantReader ir(*g);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u01(0, 1);
    for (int l = 0; l <= g->max_level(); ++l) {
        std::vector<CellId> cells = l ? g->leaves(l) : std::vector<CellId>{CellId{Coord(0, 0, 0), 0}};
        if (!l && ir.cells().leaf_level(Coord(0, 0, 0)) != 0) continue;
        for (std::size_t i = 0; i < std::min<std::size_t>(cells.size(), 20); ++i) {
            const CellId& c = cells[i];
            Vec3d a, b;
            for (int ax = 0; ax < 3; ++ax) {
                a[ax] = c.origin[ax] + u01(rng) * c.size();
                b[ax] = c.origin[ax] + u01(rng) * c.size();
            }
            const Cubic q = restrict_to_segment(ir, c, a, b);
            for (double t : {0.0, 0.17, 0.5, 0.83, 1.0})
                CHECK(q(t) == Approx(ir.eval_in(c, a + (b - a) * t)).margin(1e-12));
        }
    }
}
