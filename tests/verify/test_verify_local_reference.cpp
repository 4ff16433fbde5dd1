// The Hausdorff check's local reference (src/verify/local_reference.h): its cache of refined
// cells must not change a single bound. Query points sweep a random volume (plain and quantized:
// ties at v) so that consecutive queries share cells and many cells share a column; each bound
// with the cache must equal, bit for bit, the bound of a reference that refines every cell anew,
// also when a tiny cache is cleared over and over. A cache that mixed up cells (e.g. a key that
// forgot a coordinate) would hand a query another cell's triangles.
#include <catch2/catch.hpp>

#include "support/verify_test_support.h"

#include "verify/local_reference.h"

#include <cmath>

using namespace isodel;
using openvdb::Vec3d;

TEST_CASE("local reference: the cached bounds equal the bounds refined anew", "[verify][hausdorff]")
{
    for (const bool quantized : {false, true}) {
        INFO((quantized ? "quantized" : "plain") << " random volume");
        const auto grid = testing::random_volume(4, 5u, quantized);
        const verify::TrilinearField field(*grid, 0.0, Inside::Above);
        verify::Coord base;
        const std::vector<verify::Coord> cells = verify::crossed_cells(field, base);
        REQUIRE(cells.size() > 30);
        const verify::CrossedCellSet crossed(cells, base);
        verify::LocalReference fresh(field, crossed, 0), cached(field, crossed), tiny(field, crossed, 3);
        std::size_t queries = 0, found = 0;
        // Points every 0.47 voxel over the padded box, balls of 0.6 and 1.2 voxels (world = index
        // here): each ball meets 8 to 64 cells, neighbours in z among them.
        for (double z = 0.2; z < 5.8; z += 0.47)
            for (double y = 0.2; y < 5.8; y += 0.47)
                for (double x = 0.2; x < 5.8; x += 0.47)
                    for (const double r : {0.6, 1.2}) {
                        const Vec3d p = field.to_world(Vec3d(x, y, z));
                        double b0 = 1e300, b1 = 1e300, b2 = 1e300;
                        const bool f0 = fresh.search(p, r, b0), f1 = cached.search(p, r, b1), f2 = tiny.search(p, r, b2);
                        ++queries;
                        found += f0;
                        if (f0 != f1 || f0 != f2 || b0 != b1 || b0 != b2) {
                            INFO("p = " << p[0] << " " << p[1] << " " << p[2] << ", r = " << r << ": " << b0 << " " << b1 << " " << b2);
                            CHECK(f1 == f0);
                            CHECK(f2 == f0);
                            CHECK(b1 == b0);
                            CHECK(b2 == b0);
                        }
                        if (f0 && !(b0 >= 0 && b0 < 1e300)) FAIL("bound " << b0 << " at " << p[0] << " " << p[1] << " " << p[2]);
                    }
        INFO(queries << " queries, " << found << " found");
        CHECK(found > queries / 2);
        // The cache was used (hits) and the tiny one was cleared (it could not hold a ball's cells).
        CHECK(cached.cache_hits() > 10 * cells.size());
        CHECK(tiny.cache_hits() < cached.cache_hits());
        CHECK(fresh.cache_hits() == 0);
    }
}
