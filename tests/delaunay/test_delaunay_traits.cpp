// The mesher's Delaunay traits (src/delaunay/delaunay_traits.h) answer an in-sphere test that
// CGAL's filter cannot decide by a box-corner test, then in 320-bit integers
// (geometry/exact_in_sphere, tested on its own in tests/geometry), before EPICK's evaluation.
// The answers must be EPICK's: on five lattice points at a time (cospherical in every
// cube, and often so across cubes too, where the shortcut must not answer) and with grid-edge
// points among them, every sign equals EPICK's; and a triangulation built with the traits is
// the one EPICK builds. The lattice spacing is not a power of two and the origin is off zero,
// so the coordinates are rounded as the mesher's grid points are.
#include "delaunay/delaunay.h"

#include <catch2/catch.hpp>

#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <array>
#include <random>
#include <vector>

using namespace isodel::mesher;

namespace {

constexpr double kOrigin[3] = {-3.7, 12.34567, 101.25};
constexpr double kSpacing[3] = {0.45, 0.45, 0.6};

/// Grid point (i, j, k), moved by f along axis `axis` (a grid-edge point when 0 < f < 1).
Point lattice(int i, int j, int k, int axis = -1, double f = 0)
{
    const int ijk[3] = {i, j, k};
    double c[3];
    for (int a = 0; a < 3; ++a) c[a] = kOrigin[a] + (ijk[a] + (a == axis ? f : 0.0)) * kSpacing[a];
    return {c[0], c[1], c[2]};
}

} // namespace

TEST_CASE("the traits' in-sphere test is EPICK's on lattice and grid-edge points", "[mesher][delaunay_traits]")
{
    std::mt19937_64 rng(7);
    // Half the tuples from one cube's corners, half from a 3 x 3 x 3 block (up to eight cubes).
    std::uniform_int_distribution<int> cube(0, 1), block(0, 2);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const auto traits_test = DelaunayTraits().side_of_oriented_sphere_3_object();
    const auto epick_test = K().side_of_oriented_sphere_3_object();
    std::size_t differ = 0, box = 0, box_not_zero = 0, zero_off_box = 0;
    for (int n = 0; n < 200000; ++n) {
        std::array<Point, 5> p;
        auto& near = n % 2 ? cube : block;
        const int edge_points = n % 3; // 0, 1 or 2 of the five on grid edges
        for (int i = 0; i < 5; ++i)
            p[i] = i < edge_points ? lattice(near(rng), near(rng), near(rng), int(unit(rng) * 3), unit(rng))
                                   : lattice(near(rng), near(rng), near(rng));
        const auto expected = epick_test(p[0], p[1], p[2], p[3], p[4]);
        if (traits_test(p[0], p[1], p[2], p[3], p[4]) != expected) ++differ;
        if (InSphereAfterFilter::on_one_box({&p[0], &p[1], &p[2], &p[3], &p[4]})) {
            ++box;
            if (expected != CGAL::ON_ORIENTED_BOUNDARY) ++box_not_zero;
        } else if (expected == CGAL::ON_ORIENTED_BOUNDARY) {
            ++zero_off_box;
        }
    }
    INFO("box corners " << box << ", exact zeros off a box " << zero_off_box);
    CHECK(differ == 0);
    CHECK(box_not_zero == 0);
    // The sample reaches both kinds of exact zero: the shortcut's, and cospherical points that
    // are not one box's corners (those must go to EPICK's exact evaluation).
    CHECK(box > 10000);
    CHECK(zero_off_box > 1000);
}

TEST_CASE("a triangulation built with the traits is EPICK's", "[mesher][delaunay_traits]")
{
    // A 7^3 block of grid points (every cube cospherical), grid-edge points and random points.
    std::vector<Point> points;
    for (int i = 0; i < 7; ++i)
        for (int j = 0; j < 7; ++j)
            for (int k = 0; k < 7; ++k) points.push_back(lattice(i, j, k));
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int n = 0; n < 300; ++n) {
        const int i = int(unit(rng) * 6), j = int(unit(rng) * 6), k = int(unit(rng) * 6);
        points.push_back(n % 2 ? lattice(i, j, k, int(unit(rng) * 3), unit(rng))
                               : lattice(i, j, k, 0, 0) + K::Vector_3(unit(rng), unit(rng), unit(rng)));
    }
    std::shuffle(points.begin(), points.end(), rng);

    using Cell = std::array<std::uint32_t, 4>;
    const auto sorted_cells = [](const auto& dt, const auto& id_of) {
        std::vector<Cell> cells;
        for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
            Cell ids{id_of(c->vertex(0)), id_of(c->vertex(1)), id_of(c->vertex(2)), id_of(c->vertex(3))};
            std::sort(ids.begin(), ids.end());
            cells.push_back(ids);
        }
        std::sort(cells.begin(), cells.end());
        return cells;
    };

    Delaunay ours;
    for (std::uint32_t i = 0; i < points.size(); ++i) ours.insert(points[i])->info() = VertexInfo{i, PointKind::Grid};
    using EpickDelaunay = CGAL::Delaunay_triangulation_3<
        K, CGAL::Triangulation_data_structure_3<CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, K>,
                                                CGAL::Delaunay_triangulation_cell_base_3<K>>>;
    EpickDelaunay epick;
    for (std::uint32_t i = 0; i < points.size(); ++i) epick.insert(points[i])->info() = i;

    REQUIRE(ours.is_valid());
    const auto a = sorted_cells(ours, [](const auto& v) { return v->info().id; });
    const auto b = sorted_cells(epick, [](const auto& v) { return v->info(); });
    CHECK(a.size() > 2000);
    CHECK(a == b);
}
