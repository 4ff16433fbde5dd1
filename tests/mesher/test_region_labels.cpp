// Inside/outside labels of the Delaunay cells (src/mesher/region_labels.h): CellIndex numbers
// every cell of the triangulation 0..n-1 exactly once, also after removals leave free slots in
// CGAL's container (the labels are stored by it; Compact_container::index() was O(sqrt n) per
// call, which made the flood fill the slowest step of labelling a million cells).
#include <catch2/catch.hpp>

#include "mesher_test_support.h"

#include "mesher/region_labels.h"

#include <random>

using namespace isodel;
using namespace isodel::mesher;

TEST_CASE("CellIndex numbers every cell once, after insertions and removals", "[mesher][region_labels]")
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 10.0);
    Delaunay dt;
    std::vector<Vertex_handle> vs;
    for (int i = 0; i < 20000; ++i) vs.push_back(dt.insert(Point(u(rng), u(rng), u(rng))));
    // Removals free slots in the middle of the container's blocks; later insertions reuse some.
    for (std::size_t i = 0; i < vs.size(); i += 3) dt.remove(vs[i]);
    for (int i = 0; i < 2000; ++i) dt.insert(Point(u(rng), u(rng), u(rng)));
    REQUIRE(dt.is_valid());

    const CellIndex index(dt);
    const std::size_t n = dt.tds().number_of_cells();
    CHECK(index.size() == n);
    std::vector<char> seen(n, 0);
    std::size_t out_of_range = 0, repeated = 0;
    for (auto c = dt.all_cells_begin(); c != dt.all_cells_end(); ++c) {
        const std::size_t i = index(c);
        if (i >= n) {
            ++out_of_range;
            continue;
        }
        repeated += seen[i];
        seen[i] = 1;
    }
    CHECK(out_of_range == 0);
    CHECK(repeated == 0);
    CHECK(std::count(seen.begin(), seen.end(), 1) == std::ptrdiff_t(n));
}
