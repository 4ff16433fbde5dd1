// The covering bound of the mesher's Hausdorff refinement: no point of a triangle is farther
// than triangle_corner_reach() from the triangle's nearest corner, and for acute triangles the
// bound is the true maximum (a smaller value would certify triangles that are too far).
#include <catch2/catch.hpp>

#include "geometry/triangle_corner_reach.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace {

using openvdb::math::Vec3d;

/// max over a barycentric grid of n + 1 samples per edge of the distance to the nearest corner.
double sampled_reach(const Vec3d& a, const Vec3d& b, const Vec3d& c, int n)
{
    double best = 0;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; i + j <= n; ++j) {
            const double u = double(i) / n, v = double(j) / n;
            const Vec3d x = a * u + b * v + c * (1 - u - v);
            best = std::max(best, std::min({(x - a).length(), (x - b).length(), (x - c).length()}));
        }
    return best;
}

bool acute(const Vec3d& a, const Vec3d& b, const Vec3d& c)
{
    return (b - a).dot(c - a) > 0 && (a - b).dot(c - b) > 0 && (a - c).dot(b - c) > 0;
}

} // namespace

TEST_CASE("triangle corner reach: equilateral and right triangles have the known values", "[geometry]")
{
    using isodel::geometry::triangle_corner_reach;
    const Vec3d a(0, 0, 0), b(2, 0, 0), c(1, std::sqrt(3.0), 0);
    CHECK(std::abs(triangle_corner_reach(a, b, c) - 2 / std::sqrt(3.0)) < 1e-12); // L / sqrt(3)
    CHECK(std::abs(triangle_corner_reach(a, b, Vec3d(0, 2, 0)) - std::sqrt(2.0)) < 1e-12); // half the hypotenuse
    CHECK(triangle_corner_reach(a, b, Vec3d(4, 0, 0)) == 2.0);                           // collinear: half of 4
    CHECK(triangle_corner_reach(a, a, a) == 0.0);
}

TEST_CASE("triangle corner reach: bounds every point of random triangles, and is the maximum for acute ones",
          "[geometry]")
{
    using isodel::geometry::triangle_corner_reach;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> coord(-1.0, 1.0);
    int n_acute = 0, n_obtuse = 0;
    for (int t = 0; t < 400; ++t) {
        const Vec3d offset(1e3 * coord(rng), 1e3 * coord(rng), 1e3 * coord(rng)); // far from the origin too
        Vec3d a(coord(rng), coord(rng), coord(rng)), b(coord(rng), coord(rng), coord(rng)), c;
        if (t % 4 == 3) c = a + (b - a) * 0.5 + Vec3d(1e-3 * coord(rng), 1e-3 * coord(rng), 0); // needle / sliver
        else c = Vec3d(coord(rng), coord(rng), coord(rng));
        a += offset;
        b += offset;
        c += offset;
        const double reach = triangle_corner_reach(a, b, c);
        const double longest = std::max({(b - a).length(), (c - b).length(), (a - c).length()});
        const double sampled = sampled_reach(a, b, c, 120);
        INFO("triangle " << t << ": reach " << reach << ", sampled " << sampled << ", longest edge " << longest);
        CHECK(sampled <= reach * (1 + 1e-9) + 1e-12);
        CHECK(reach <= longest / std::sqrt(3.0) * (1 + 1e-9));
        if (acute(a, b, c)) {
            ++n_acute;
            // The grid misses the circumcentre by at most one grid step.
            CHECK(sampled >= reach - 2 * longest / 120);
        } else {
            ++n_obtuse;
        }
    }
    CHECK(n_acute > 50);
    CHECK(n_obtuse > 50);
}
