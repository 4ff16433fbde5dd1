// Inside/outside labels of the Delaunay cells (src/volume/region_labels.h): the flood fill
// labels every cell, changes the label exactly across the restricted facets, puts the infinite
// cells outside and the cells at the centre of a sphere inside, and refuses a restricted set
// that bounds no region.
#include <catch2/catch.hpp>

#include "support/mesher_test_support.h"

#include "volume/region_labels.h"
#include "closed_ball/restricted_facets.h"

#include <isodel/errors.h>

using namespace isodel;
using namespace isodel::mesher;

namespace {

/// Sigma = the zero set of \p f sampled on an n^3 lattice of unit voxels: the lattice points (G)
/// and the crossings of the lattice edges (E, where the interpolant is linear), triangulated,
/// with the facet records of the cache computed.
struct LatticeSetup {
    openvdb::FloatGrid::Ptr grid;
    octree::SampleField field;
    Delaunay dt;
    FacetCache cache;
    LatticeSetup(int n, const std::function<double(const openvdb::Vec3d&)>& f)
        : grid(testing::make_grid(n, 1.0, openvdb::Vec3d(0.0), f)), field(grid, 0.0, Inside::Above)
    {
        auto acc = grid->getConstAccessor();
        const auto value = [&](int x, int y, int z) { return double(acc.getValue(openvdb::Coord(x, y, z))); };
        std::uint32_t id = 0;
        for (int z = 0; z < n; ++z)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    dt.insert(Point(x, y, z))->info() = VertexInfo{id++, PointKind::Grid};
                    const double a = value(x, y, z);
                    for (int axis = 0; axis < 3; ++axis) {
                        const int d[3] = {axis == 0, axis == 1, axis == 2};
                        if (x + d[0] >= n || y + d[1] >= n || z + d[2] >= n) continue;
                        const double b = value(x + d[0], y + d[1], z + d[2]);
                        if ((a > 0) == (b > 0)) continue;
                        const double t = a / (a - b);
                        dt.insert(Point(x + t * d[0], y + t * d[1], z + t * d[2]))->info() =
                            VertexInfo{id++, PointKind::Edge};
                    }
                }
        cache.update(dt, field, 64);
    }
};

} // namespace

TEST_CASE("region labels: every cell labelled, flipped exactly across M, the sphere's centre inside",
          "[mesher][region_labels]")
{
    const openvdb::Vec3d c(4.5, 4.5, 4.5);
    LatticeSetup s(10, [&](const openvdb::Vec3d& x) { return testing::sphere_f(x, c, 2.8); });
    std::size_t restricted = 0;
    for (const auto& e : s.cache.active()) restricted += e.record->crossings == 1;
    REQUIRE(restricted > 50);

    label_regions(s.dt, s.cache);
    std::size_t unlabelled = 0, infinite_inside = 0;
    for (auto cell = s.dt.all_cells_begin(); cell != s.dt.all_cells_end(); ++cell) {
        unlabelled += cell->region_label() != 1 && cell->region_label() != 2;
        infinite_inside += s.dt.is_infinite(cell) && cell->region_label() != 2;
    }
    CHECK(unlabelled == 0);
    CHECK(infinite_inside == 0);
    // Across every finite facet, the labels differ iff the facet is one of M's.
    std::size_t flipped = 0, wrong = 0;
    for (auto f = s.dt.finite_facets_begin(); f != s.dt.finite_facets_end(); ++f) {
        const Facet m = s.dt.mirror_facet(*f);
        const bool differ = f->first->region_label() != m.first->region_label();
        bool in_m = false;
        for (const auto& e : s.cache.active())
            if ((e.facet == *f || e.facet == m) && e.record->crossings == 1) in_m = true;
        flipped += differ;
        wrong += differ != in_m;
    }
    CHECK(wrong == 0);
    CHECK(flipped == restricted);
    // The cell holding the centre, two voxels from Sigma, is inside.
    CHECK(s.dt.locate(Point(c[0], c[1], c[2]))->region_label() == 1);
    // Labelling again over scrambled bytes (every cell inside, every side marked) gives the same
    // labels: the fill starts from nothing, whatever the cells hold.
    std::vector<std::int8_t> first;
    for (auto cell = s.dt.all_cells_begin(); cell != s.dt.all_cells_end(); ++cell) {
        first.push_back(cell->region_label());
        cell->set_region_label(1);
        cell->set_restricted_sides(0xF);
    }
    label_regions(s.dt, s.cache);
    std::size_t i = 0, changed = 0;
    for (auto cell = s.dt.all_cells_begin(); cell != s.dt.all_cells_end(); ++cell) changed += cell->region_label() != first[i++];
    CHECK(changed == 0);
}

TEST_CASE("region labels: a sheet that reaches the hull bounds no region and is refused", "[mesher][region_labels]")
{
    // Sigma = the plane x = 3.3 across the whole box: both sides meet the infinite cells, so
    // the fill reaches the far side both across M and around it.
    LatticeSetup s(7, [](const openvdb::Vec3d& x) { return x[0] - 3.3; });
    REQUIRE_FALSE(s.cache.active().empty());
    CHECK_THROWS_AS(label_regions(s.dt, s.cache), GuaranteeViolated);
}
