// The seed octree (octree/seed_octree.h): a leaf is coarse only off Sigma or where the input is
// strictly monotone along two axes on the band cells of its span and rim, so every crossed region
// keeps a crossing on a leaf edge; the grid stays k-balanced and its coarse leaves keep their
// certificate after balancing.
#include "octree/balance.h"
#include "octree/edge_crossings.h"
#include "octree/seed_octree.h"
#include "seeding/adaptive_points.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <set>

namespace {

using isodel::Inside;
using isodel::octree::AdaptiveGrid;
using isodel::octree::CellId;
using isodel::octree::Coord;
using isodel::octree::SampleField;

// n^3 samples at index 0..n-1 of f (index space), active everywhere, voxel size 1.
openvdb::FloatGrid::Ptr dense_grid(int n, const std::function<double(double, double, double)>& f)
{
    auto g = openvdb::FloatGrid::create(-1.0f);
    auto acc = g->getAccessor();
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                acc.setValueOn(Coord(i, j, k), float(f(i, j, k)));
    return g;
}

bool certified(const std::function<double(double, double, double)>& f)
{
    const SampleField field(dense_grid(20, f), 0.0, Inside::Above);
    const SampleField::Reader r(field);
    return isodel::octree::seed_leaf_certified(r, CellId{Coord(4, 4, 4), 3}); // span 4..12, rim 3..13
}

} // namespace

TEST_CASE("seed octree: a leaf is certified by two monotone axes on its span and rim", "[octree][seed_octree]")
{
    // A tilted plane: monotone along all three axes.
    CHECK(certified([](double x, double y, double z) { return (x - 8.3) + 0.4 * (y - 8.1) + 0.3 * (z - 8.2); }));
    // Off Sigma: every node of the span of one sign, whatever the shape.
    CHECK(certified([](double x, double y, double z) { return 1.0 + std::cos(x) * std::cos(y) * std::cos(z) + 0.1; }));
    // A trough: monotone along z only (x turns at x = 8, y is flat): refused.
    CHECK_FALSE(certified([](double x, double, double z) { return (z - 8.3) + 0.05 * (x - 8.0) * (x - 8.0); }));
    // The same trough tilted along y: z and y are monotone: accepted.
    CHECK(certified(
        [](double x, double y, double z) { return (z - 8.3) + 0.05 * (x - 8.0) * (x - 8.0) + 0.2 * (y - 8.1); }));
    // A blob inside the leaf: no monotone axis.
    CHECK_FALSE(certified([](double x, double y, double z) {
        return 2.3 - std::sqrt((x - 8.2) * (x - 8.2) + (y - 7.9) * (y - 7.9) + (z - 8.1) * (z - 8.1));
    }));
    // Monotone along x on the span but not in the rim (x turns at 3.6, in the rim cell 3..4);
    // y turns inside: only z is left, refused. With the turn outside the rim (2.6): x and z pass.
    const auto bowl = [](double x0) {
        return [x0](double x, double y, double z) {
            return (z - 8.3) + 0.05 * (x - x0) * (x - x0) + 0.05 * (y - 8.0) * (y - 8.0);
        };
    };
    CHECK_FALSE(certified(bowl(3.6)));
    CHECK(certified(bowl(2.6)));
}

namespace {

// Crossed unit cells (corners of both signs) of the field, grouped by 26-adjacency: each group
// holds at least one component of Sigma and every component lies in one group.
std::vector<std::vector<Coord>> crossed_groups(const SampleField& field, int n)
{
    const SampleField::Reader r(field);
    std::map<Coord, int> crossed;
    for (int k = 0; k + 1 < n; ++k)
        for (int j = 0; j + 1 < n; ++j)
            for (int i = 0; i + 1 < n; ++i) {
                bool pos = false, neg = false;
                for (int m = 0; m < 8; ++m)
                    (r.phi(Coord(i + (m & 1), j + ((m >> 1) & 1), k + ((m >> 2) & 1))) > 0 ? pos : neg) = true;
                if (pos && neg) crossed[Coord(i, j, k)] = -1;
            }
    std::vector<std::vector<Coord>> groups;
    for (auto& [c, g] : crossed) {
        if (g >= 0) continue;
        groups.emplace_back();
        std::vector<Coord> stack{c};
        g = int(groups.size()) - 1;
        while (!stack.empty()) {
            const Coord u = stack.back();
            stack.pop_back();
            groups.back().push_back(u);
            for (int dz = -1; dz <= 1; ++dz)
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const auto it = crossed.find(u.offsetBy(dx, dy, dz));
                        if (it != crossed.end() && it->second < 0) {
                            it->second = g;
                            stack.push_back(it->first);
                        }
                    }
        }
    }
    return groups;
}

} // namespace

TEST_CASE("seed octree: every crossed region keeps a crossing on a leaf edge; balanced; leaves stay certified",
          "[octree][seed_octree]")
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> pos(4.0, 36.0), rad(0.8, 6.0);
    std::size_t coarse_at_sigma = 0, groups_seen = 0;
    for (int trial = 0; trial < 12; ++trial) {
        INFO("trial " << trial);
        // A smooth sphere (which coarsens) and a few small and large blobs (which must not vanish).
        struct Ball {
            openvdb::Vec3d c;
            double r;
        };
        std::vector<Ball> balls{{{20.3, 19.8, 20.1}, 12.0}};
        for (int b = 0; b < 5; ++b)
            balls.push_back({{pos(rng), pos(rng), pos(rng)}, rad(rng)});
        const auto grid = dense_grid(41, [&](double x, double y, double z) {
            double v = -1e9;
            for (const Ball& b : balls)
                v = std::max(v, b.r - (openvdb::Vec3d(x, y, z) - b.c).length());
            return v;
        });
        const SampleField field(grid, 0.0, Inside::Above);
        isodel::octree::SeedOctreeOptions so;
        so.k = 1 + trial % 2;
        so.max_level = 4;
        const AdaptiveGrid g = isodel::octree::seed_octree(field, so);
        CHECK(isodel::octree::max_level_difference(g) <= so.k);

        const AdaptiveGrid::Reader leaves(g);
        const SampleField::Reader r(field);
        for (int l = 1; l <= g.max_level(); ++l)
            for (const CellId& c : g.leaves(l)) {
                CHECK(isodel::octree::seed_leaf_certified(r, c)); // balance only split certified leaves
            }
        // Each group of crossed cells has a crossed unit edge on a leaf edge: an E point.
        std::set<Coord> e_cells;
        const auto e = isodel::octree::edge_crossings(field);
        for (const auto& p : e.points)
            if (isodel::mesher::on_leaf_edge(leaves, p.lower, p.axis))
                for (const Coord& u : isodel::octree::cells_around_edge(p.lower, p.axis))
                    e_cells.insert(u);
        for (const auto& group : crossed_groups(field, 41)) {
            ++groups_seen;
            const bool seeded =
                std::any_of(group.begin(), group.end(), [&](const Coord& u) { return e_cells.count(u) > 0; });
            CHECK(seeded);
            for (const Coord& u : group)
                coarse_at_sigma += leaves.leaf(u) && leaves.leaf(u)->level >= 2;
        }
    }
    CHECK(groups_seen > 12);       // the blobs are separate components in most trials
    CHECK(coarse_at_sigma > 1000); // and the sphere did coarsen at Sigma
}
