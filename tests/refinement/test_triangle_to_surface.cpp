// The M -> Sigma half of the mesher's Hausdorff check (src/refinement/triangle_to_surface.h): a
// triangle it passes lies within its covering bound (limit + leaf / sqrt(3)) of Sigma' at every
// point, measured independently (exact root isolation along 400 rays from each of 120 points of
// the triangle); a pit of Sigma' between its first samples is found; and it is not a check that
// fails everything: small triangles lying on Sigma pass.
#include <catch2/catch.hpp>

#include "support/verify_test_support.h"

#include "refinement/triangle_to_surface.h"
#include "octree/face_slabs.h"
#include "octree/segment_walk.h"

#include <cmath>
#include <optional>
#include <random>

using namespace isodel;
using openvdb::Vec3d;

namespace {

/// The point of Sigma' on the ray from c along dir (c inside, one crossing within 2r).
Vec3d on_sigma(const octree::SampleField::Reader& reader, const Vec3d& c, const Vec3d& dir, double r)
{
    const Vec3d b = c + dir * (2 * r);
    const auto sc = octree::segment_crossings(reader, c, b, 256);
    REQUIRE(!sc.overflow);
    REQUIRE(sc.t.size() == 1);
    return c + (b - c) * sc.t.front();
}

/// An upper bound of d(x, Sigma') (index = world here): the nearest crossing along 400 rays of
/// length `reach` (Fibonacci sphere; the closest point's direction is within ~6 degrees of one).
double distance_up(const octree::SampleField::Reader& reader, const Vec3d& x, double reach)
{
    double best = INFINITY;
    const int n = 400;
    for (int i = 0; i < n; ++i) {
        const double z = 1 - (2 * i + 1.0) / n, r = std::sqrt(1 - z * z), phi = i * 2.399963229728653;
        const Vec3d d(r * std::cos(phi), r * std::sin(phi), z);
        const auto sc = octree::segment_crossings(reader, x, x + d * reach, 64);
        if (!sc.t.empty()) best = std::min(best, sc.t.front() * reach);
    }
    return best;
}

/// The field read through the mesher's slabs for \p eps (voxels; index = world here), and the
/// check with the mesher's parameters: limit 0.7 eps, leaves of eps / 4, so every passed point
/// is within `bound` = limit + leaf / sqrt(3).
struct Setup {
    Setup(openvdb::FloatGrid::Ptr grid, double eps)
        : field(make_field(grid, eps)), reader(field), limit(0.7 * eps), leaf(0.25 * eps),
          bound(limit + leaf / std::sqrt(3.0)),
          to_surface(reader, openvdb::math::Mat3d::identity(), 0.5, limit, leaf, 2 * eps)
    {
    }
    static octree::SampleField make_field(openvdb::FloatGrid::Ptr grid, double eps)
    {
        octree::SampleField f(grid, 0.0, Inside::Above);
        f.set_face_slabs(octree::face_slabs_for_eps(eps));
        return f;
    }
    octree::SampleField field;
    octree::SampleField::Reader reader;
    double limit, leaf, bound;
    mutable mesher::detail::TriangleToSurface to_surface;
};

} // namespace

TEST_CASE("triangle to surface: a passed triangle is within the covering bound of Sigma' at every point; small ones pass",
          "[mesher][hausdorff]")
{
    // A sheet z = 7.5 - 1.5 |x - 8| + 1.5 |y - 8| sampled on a 16^3 grid (voxel 1, so index =
    // world): a ridge on the grid plane x = 8 and a valley on y = 8, creases where a triangle
    // across them stands off Sigma' between its vertices, so a check that samples too sparsely
    // passes triangles it should not. F increases with z along every vertical line: one
    // crossing each. Sigma' is read through the mesher's slabs for eps = 0.1 voxel.
    const auto grid = testing::make_grid(16, 1.0, Vec3d(0.0), [&](const Vec3d& x) {
        return x[2] - 7.5 + 1.5 * std::abs(x[0] - 8) - 1.5 * std::abs(x[1] - 8);
    });
    const Setup setup(grid, 0.1);
    const octree::SampleField::Reader& reader = setup.reader;
    const double bound = setup.bound;
    auto& to_surface = setup.to_surface;

    std::mt19937 rng(7);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    int passed = 0, failed = 0, small_passed = 0, small = 0;
    for (int trial = 0; trial < 200; ++trial) {
        // Three points of Sigma' around a random (x, y) near the creases, 0.05 to 1.5 voxels
        // from it.
        const double cx = 6 + 4 * U(rng), cy = 6 + 4 * U(rng), size = 0.05 + 1.45 * U(rng);
        Vec3d p[3];
        for (int k = 0; k < 3; ++k) {
            const double t = 2.0 * M_PI * k / 3 + 0.6 * (U(rng) - 0.5);
            p[k] = on_sigma(reader, Vec3d(cx + size * std::cos(t), cy + size * std::sin(t), 2.0), Vec3d(0, 0, 1), 5.5);
        }
        const double off[3] = {0, 0, 0};
        std::optional<Vec3d> at;
        const bool ok = to_surface.check(p[0], p[1], p[2], off, p[0], at);
        ok ? ++passed : ++failed;
        // Sigma' is planar away from the two grid planes (F is linear there, and so is its
        // trilinear interpolant): a small triangle there lies on it.
        if (size < 0.2 && std::abs(cx - 8) > 0.3 && std::abs(cy - 8) > 0.3) {
            ++small;
            small_passed += ok;
        }
        if (!ok) continue;
        // Every point of a passed triangle (a barycentric grid of 15 per edge) within the bound.
        double worst = 0;
        const int n = 14;
        for (int i = 0; i <= n; ++i)
            for (int j = 0; i + j <= n; ++j) {
                const Vec3d x = (p[0] * (n - i - j) + p[1] * i + p[2] * j) / n;
                worst = std::max(worst, distance_up(reader, x, 4 * bound));
            }
        INFO("trial " << trial << ": size " << size << ", worst " << worst << ", bound " << bound);
        CHECK(worst <= 1.01 * bound);
    }
    INFO("passed " << passed << ", failed " << failed << ", small " << small_passed << " / " << small);
    CHECK(passed > 20);
    CHECK(failed > 20); // large ones across a crease stand off it by more than the bound
    CHECK(small_passed == small);
}

TEST_CASE("triangle to surface: a pit of Sigma' under the middle of a triangle, between its first samples, fails it",
          "[mesher][hausdorff]")
{
    // The plane z = 10.4 with a conical pit of radius 2.4 and depth 6 at (10, 10) (F = z - 10.4
    // + 6 max(0, 1 - r / 2.4)), and a triangle of circumradius 7 centred over the pit with its
    // vertices on the plane. Its edge midpoints are 3.5 from the centre, where the cells' samples
    // are all beyond the pit: on the plane too, so the four halves' corners all lie on Sigma'.
    // The centre is 2.2 from it. At eps = 2 voxels the bound is 1.69: the halves must be split
    // again (their corner reach is 3.5), and the samples that finds in the pit fail the
    // triangle. A covering radius taken too small (a fifth of it) passes it.
    const auto grid = testing::make_grid(21, 1.0, Vec3d(0.0), [&](const Vec3d& x) {
        const double r = std::hypot(x[0] - 10, x[1] - 10);
        return x[2] - 10.4 + 6 * std::max(0.0, 1 - r / 2.4);
    });
    const Setup setup(grid, 2.0);
    const octree::SampleField::Reader& reader = setup.reader;
    const double bound = setup.bound;
    auto& to_surface = setup.to_surface;
    Vec3d p[3];
    for (int k = 0; k < 3; ++k) {
        const double t = 2.0 * M_PI * k / 3 + 0.1;
        p[k] = on_sigma(reader, Vec3d(10 + 7 * std::cos(t), 10 + 7 * std::sin(t), 3.0), Vec3d(0, 0, 1), 5.5);
    }
    // The plane of Sigma' (z = 10.4 moved by the slab map), and the midpoints on it.
    for (int k = 0; k < 3; ++k) {
        CHECK(std::abs(p[k][2] - p[0][2]) < 1e-9);
        CHECK(std::abs(octree::phi_at(reader, (p[k] + p[(k + 1) % 3]) * 0.5)) < 1e-9);
    }
    CHECK(std::abs(p[0][2] - 10.4) < 0.05);
    const Vec3d centre = (p[0] + p[1] + p[2]) / 3.0;
    const double d_centre = distance_up(reader, centre, 8.0);
    INFO("d(centre, Sigma') <= " << d_centre << ", bound " << bound);
    REQUIRE(d_centre > 2.0); // an upper bound of the distance; the cone's wall is 2.2 away
    const double off[3] = {0, 0, 0};
    std::optional<Vec3d> at;
    CHECK_FALSE(to_surface.check(p[0], p[1], p[2], off, p[0], at));
    // The point it reports to insert lies on Sigma', in the pit.
    REQUIRE(at);
    CHECK(std::abs(octree::phi_at(reader, *at)) < 1e-6);
    CHECK(std::hypot((*at)[0] - 10, (*at)[1] - 10) < 2.4 + 1.8); // its cells' samples reach the pit
}
