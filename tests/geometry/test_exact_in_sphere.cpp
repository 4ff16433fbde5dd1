// geometry::exact_in_sphere_sign (src/geometry/exact_in_sphere.h) must give EPICK's sign of
// side_of_oriented_sphere on every input it accepts, and decline the inputs its 320-bit
// integers cannot hold. The inputs are the mesher's hard cases and their neighbours:
// - five lattice points (cospherical in every cube, often across cubes: exact zeros),
//   with grid-edge points among them;
// - the same with one point moved by 1-3 ulps (nonzero determinants far below any
//   floating-point filter's reach: the sign is all that is left);
// - lattices scaled by 2^-70 and 2^70 (the integers' unit follows the data);
// - differences that span more than 60 bits or are not exact (declined; an integer unit that
//   ignored the span would overflow).
#include "geometry/exact_in_sphere.h"

#include <catch2/catch.hpp>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>
#include <cmath>
#include <random>

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using isodel::geometry::exact_in_sphere_sign;

namespace {

using Five = std::array<std::array<double, 3>, 5>;

struct Tally {
    std::size_t accepted = 0, differ = 0, zero = 0, nonzero = 0;
};

/// Compares with EPICK where accepted.
void check(const Five& x, Tally& tally)
{
    int sign = 7;
    if (!exact_in_sphere_sign(x[0].data(), x[1].data(), x[2].data(), x[3].data(), x[4].data(), sign)) return;
    ++tally.accepted;
    const auto P = [&](int i) { return K::Point_3(x[i][0], x[i][1], x[i][2]); };
    const int expected = int(K().side_of_oriented_sphere_3_object()(P(0), P(1), P(2), P(3), P(4)));
    if (sign != expected) ++tally.differ;
    ++(expected == 0 ? tally.zero : tally.nonzero);
}

/// Five points of a 3 x 3 x 3 lattice block (spacing not a power of two, origin off zero),
/// `edge` of them moved along a grid edge, scaled by 2^scale.
Five lattice_five(std::mt19937_64& rng, int edge, int scale)
{
    constexpr double origin[3] = {-3.7, 12.34567, 101.25}, spacing[3] = {0.45, 0.45, 0.6};
    std::uniform_int_distribution<int> near(0, 2);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    Five x;
    for (int i = 0; i < 5; ++i) {
        const int axis = i < edge ? int(unit(rng) * 3) : -1;
        const double f = unit(rng);
        for (int k = 0; k < 3; ++k)
            x[i][k] = std::ldexp(origin[k] + (near(rng) + (k == axis ? f : 0.0)) * spacing[k], scale);
    }
    return x;
}

} // namespace

TEST_CASE("exact in-sphere signs are EPICK's on lattice points, exact zeros included", "[geometry][exact_in_sphere]")
{
    std::mt19937_64 rng(3);
    for (const int scale : {0, -70, 70}) {
        Tally tally;
        for (int n = 0; n < 60000; ++n) check(lattice_five(rng, n % 3, scale), tally);
        INFO("scale 2^" << scale << ": accepted " << tally.accepted << ", zero " << tally.zero);
        CHECK(tally.differ == 0);
        CHECK(tally.accepted == 60000); // nearby points: exact differences, a narrow span
        CHECK(tally.zero > 5000);
        CHECK(tally.nonzero > 5000);
    }
}

TEST_CASE("exact in-sphere signs are EPICK's a few ulps away from cospherical", "[geometry][exact_in_sphere]")
{
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    Tally tally;
    std::size_t moved_off_zero = 0;
    for (int n = 0; n < 60000; ++n) {
        Five x = lattice_five(rng, 0, 0);
        Tally before;
        check(x, before);
        double& c = x[std::size_t(unit(rng) * 5)][std::size_t(unit(rng) * 3)];
        const double toward = unit(rng) < 0.5 ? -INFINITY : INFINITY;
        for (int ulps = 1 + int(unit(rng) * 3); ulps > 0; --ulps) c = std::nextafter(c, toward);
        Tally after;
        check(x, after);
        if (before.zero && after.nonzero) ++moved_off_zero;
        tally.accepted += after.accepted;
        tally.differ += after.differ;
    }
    CHECK(tally.differ == 0);
    CHECK(moved_off_zero > 1000); // determinants of a few ulps: the cases the sign is all about
}

TEST_CASE("exact in-sphere declines differences it cannot hold", "[geometry][exact_in_sphere]")
{
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> unit(-0.5, 0.5);
    std::uniform_int_distribution<int> small(0, 8), wide(0, 40), huge(-200, 200);
    const auto run = [&](auto&& five, std::size_t& declined) {
        Tally tally;
        for (int n = 0; n < 30000; ++n) {
            const std::size_t before = tally.accepted;
            check(five(), tally);
            if (tally.accepted == before) ++declined;
        }
        CHECK(tally.differ == 0);
        return tally.accepted;
    };
    // t at the origin: every difference exact, 53-bit mantissas scaled by 2^k. Spans of
    // 53 + 8 bits at most fit 60 bits in part; spans up to 53 + 40 bits mostly do not, and an
    // integer unit that ignored them would overflow.
    const auto exact_five = [&](std::uniform_int_distribution<int>& k) {
        return [&] {
            Five x;
            for (int i = 0; i < 4; ++i)
                for (double& c : x[i]) c = std::ldexp(unit(rng), k(rng));
            x[4] = {0.0, 0.0, 0.0};
            return x;
        };
    };
    std::size_t declined_small = 0, declined_wide = 0, declined_inexact = 0;
    CHECK(run(exact_five(small), declined_small) > 1000);
    CHECK(declined_small > 1000);
    run(exact_five(wide), declined_wide);
    CHECK(declined_wide > 25000);
    // Coordinates of wildly different magnitudes everywhere: inexact differences.
    run(
        [&] {
            Five x;
            for (auto& p : x) p = {std::ldexp(unit(rng), huge(rng)), std::ldexp(unit(rng), small(rng)), unit(rng)};
            return x;
        },
        declined_inexact);
    CHECK(declined_inexact > 25000);
    // Five equal points: every difference 0.
    const Five same{{{1.5, -2.25, 3.0}, {1.5, -2.25, 3.0}, {1.5, -2.25, 3.0}, {1.5, -2.25, 3.0}, {1.5, -2.25, 3.0}}};
    int sign = 7;
    REQUIRE(exact_in_sphere_sign(same[0].data(), same[1].data(), same[2].data(), same[3].data(), same[4].data(), sign));
    CHECK(sign == 0);
}
