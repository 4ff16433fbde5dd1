// The facet-loop certificate (src/closed_ball/monotone_in_plane.h): a direction in a plane along
// which F' never decreases on the box. A cap of Sigma under a plane parallel to it meets the
// plane in a loop and is refused; the same cap cut by planes it crosses is certified; on a
// random smooth field F' is measured non-decreasing along every direction returned, with and
// without face slabs.
#include <catch2/catch.hpp>

#include "closed_ball/monotone_in_plane.h"
#include "octree/segment_walk.h"

#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace isodel;
using octree::Vec3d;

namespace {

/// F = 4 - z - 0.05 ((x - 8)^2 + (y - 8)^2) on 17^3 samples: inside (above 0) a cap with its top
/// at (8, 8, 4).
openvdb::FloatGrid::Ptr cap()
{
    auto grid = openvdb::FloatGrid::create(-100.0f);
    auto acc = grid->getAccessor();
    for (int z = 0; z <= 16; ++z)
        for (int y = 0; y <= 16; ++y)
            for (int x = 0; x <= 16; ++x)
                acc.setValue({x, y, z}, float(4.0 - z - 0.05 * ((x - 8) * (x - 8) + (y - 8) * (y - 8))));
    return grid;
}

/// A sum of Gaussian blobs on 25^3 samples (a smooth field with extrema and saddles); \p mid
/// receives the middle of its value range.
openvdb::FloatGrid::Ptr blobs(unsigned seed, double& mid)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> pos(2, 22), w(-1, 1), r(3, 7);
    struct Blob {
        Vec3d c;
        double a, s;
    };
    std::vector<Blob> b;
    for (int i = 0; i < 6; ++i)
        b.push_back({Vec3d(pos(rng), pos(rng), pos(rng)), w(rng), r(rng)});
    auto grid = openvdb::FloatGrid::create(0.0f);
    auto acc = grid->getAccessor();
    double lo = 1e300, hi = -1e300;
    for (int z = 0; z <= 24; ++z)
        for (int y = 0; y <= 24; ++y)
            for (int x = 0; x <= 24; ++x) {
                double v = 0;
                for (const Blob& o : b)
                    v += o.a * std::exp(-(Vec3d(x, y, z) - o.c).lengthSqr() / (o.s * o.s));
                acc.setValue({x, y, z}, float(v));
                lo = std::min(lo, double(float(v)));
                hi = std::max(hi, double(float(v)));
            }
    mid = 0.5 * (lo + hi);
    return grid;
}

} // namespace

TEST_CASE("monotone in plane: a plane parallel to a cap is refused, planes across it are certified",
          "[mesher][facet-loops]")
{
    const octree::SampleField f(cap(), 0.0, Inside::Above);
    const octree::SampleField::Reader r(f);
    // z = 3.5 cuts the cap in a circle of radius sqrt(10) round (8, 8): a loop in the box.
    CHECK_FALSE(mesher::monotone_direction_in_plane(r, {3, 3, 3.4}, {13, 13, 3.6}, {0, 0, 1}));
    // Tilted a little, still a loop.
    CHECK_FALSE(mesher::monotone_direction_in_plane(r, {3, 3, 3.0}, {13, 13, 4.0}, {0.05, 0.02, 1}));
    // x = 8 through the top: F decreases along z everywhere, and z lies in the plane.
    const auto u = mesher::monotone_direction_in_plane(r, {7.9, 3, 2}, {8.1, 13, 5}, {1, 0, 0});
    REQUIRE(u);
    CHECK(u->x() == 0);
    CHECK(u->z() < 0);
    // Off the top, x in [10, 14], y in [2, 6]: dF/dx < 0 < dF/dy, so F grows along (-1, 1, 0),
    // which lies in the plane of normal (1, 1, 1): no axis lies in that plane.
    const auto v = mesher::monotone_direction_in_plane(r, {10, 2, 1}, {14, 6, 3}, {1, 1, 1});
    REQUIRE(v);
    CHECK(std::abs(v->dot(Vec3d(1, 1, 1))) <= 1e-12 * v->length());
}

TEST_CASE("monotone in plane: F' never decreases along a returned direction (random fields, slabs)",
          "[mesher][facet-loops]")
{
    std::size_t certified = 0, refused = 0;
    for (unsigned seed = 1; seed <= 6; ++seed)
        for (double h : {0.0, 0.05}) {
            double mid = 0;
            const auto grid = blobs(seed, mid);
            octree::SampleField f(grid, mid, Inside::Above);
            f.set_face_slabs(octree::FaceSlabs{h});
            const octree::SampleField::Reader r(f);
            std::mt19937 rng(seed * 7 + unsigned(h * 100));
            std::uniform_real_distribution<double> corner(1, 17), size(0.5, 6), comp(-1, 1), t01(0, 1);
            for (int trial = 0; trial < 300; ++trial) {
                const Vec3d lo(corner(rng), corner(rng), corner(rng));
                const Vec3d hi = lo + Vec3d(size(rng), size(rng), size(rng));
                Vec3d N(comp(rng), comp(rng), comp(rng));
                if (trial % 5 == 0) N[trial % 3] = 0; // axis-parallel planes too
                const auto u = mesher::monotone_direction_in_plane(r, lo, hi, N);
                if (!u) {
                    ++refused;
                    continue;
                }
                ++certified;
                INFO("seed " << seed << " h " << h << " box " << lo << ".." << hi << " N " << N << " u " << *u);
                REQUIRE(std::abs(u->dot(N)) <= 1e-12 * u->length() * N.length());
                // Lines along u through random points of the box, clipped to it.
                const Vec3d d = *u / u->length();
                for (int line = 0; line < 8; ++line) {
                    const Vec3d p(lo.x() + t01(rng) * (hi.x() - lo.x()), lo.y() + t01(rng) * (hi.y() - lo.y()),
                                  lo.z() + t01(rng) * (hi.z() - lo.z()));
                    double prev = octree::phi_at(r, p);
                    for (int s = 1; s <= 40; ++s) {
                        const Vec3d q = p + d * (0.05 * s);
                        if (q.x() > hi.x() || q.y() > hi.y() || q.z() > hi.z() || q.x() < lo.x() || q.y() < lo.y() ||
                            q.z() < lo.z())
                            break;
                        const double now = octree::phi_at(r, q);
                        CHECK(now >= prev - 1e-9);
                        prev = now;
                    }
                }
            }
        }
    INFO(certified << " certified, " << refused << " refused");
    CHECK(certified > 100);
    CHECK(refused > 100);
}
