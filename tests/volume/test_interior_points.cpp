// G', the points DELVOLMESH adds off Sigma (src/volume/interior_points.h): the graded subset
// follows its stated rule, checked against chessboard distances to G computed by brute force;
// it is a subset of the uniform samples; the outside box is grown to a multiple of the largest
// spacing and keeps its corners; MeshOptions::tet_size maps to the stated lattice levels.
#include <catch2/catch.hpp>

#include "support/mesher_test_support.h"

#include "octree/sample_field.h"
#include "volume/interior_points.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

using namespace isodel;
using namespace isodel::mesher;

namespace {

/// A sphere of radius \p r voxels in an n^3 grid, and a G made by hand: the samples within half
/// a voxel of the sphere. The rule is about distances to whatever G is, so any G serves.
struct SphereSetup {
    int n;
    double r;
    openvdb::Vec3d centre;
    openvdb::FloatGrid::Ptr grid;
    octree::SampleField field;
    openvdb::MaskGrid::Ptr g = openvdb::MaskGrid::create();
    std::vector<openvdb::Coord> g_list;
    explicit SphereSetup(int n_ = 34, double r_ = 11.0)
        : n(n_), r(r_), centre(n_ / 2 - 0.7, n_ / 2 - 0.9, n_ / 2 - 0.3),
          grid(testing::make_grid(n, 1.0, openvdb::Vec3d(0.0),
                                  [this](const openvdb::Vec3d& x) { return testing::sphere_f(x, centre, r); })),
          field(grid, 0.0, Inside::Above)
    {
        auto acc = g->getAccessor();
        for (int z = 0; z < n; ++z)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x)
                    if (std::abs(testing::sphere_f(openvdb::Vec3d(x, y, z), centre, r)) < 0.5) {
                        acc.setValueOn({x, y, z});
                        g_list.push_back({x, y, z});
                    }
    }
    int chessboard_distance_to_g(const openvdb::Coord& c) const
    {
        int best = 1 << 30;
        for (const auto& q : g_list) {
            const openvdb::Coord d = c - q;
            best = std::min(best, std::max({std::abs(d.x()), std::abs(d.y()), std::abs(d.z())}));
        }
        return best;
    }
};

/// The level the rule gives at distance d: the largest l <= max_level with 2^l <= 1 + grading d.
int expected_level(int d, const GradedSpacing& s)
{
    int l = 0;
    while (l < s.max_level && std::ldexp(1.0, l + 1) <= 1 + s.grading * d)
        ++l;
    return l;
}

} // namespace

TEST_CASE("graded G' keeps exactly the samples on the lattice its distance to G asks for", "[tets][interior_points]")
{
    // A large sphere (deep inside) and a small one in a large box (far outside: chessboard
    // distances up to 17, so the default's 8-voxel lattice, from 14 on, is reached).
    const bool small = GENERATE(false, true);
    const SphereSetup s = small ? SphereSetup(40, 6.0) : SphereSetup();
    std::array<std::size_t, 4> per_level{}; // default spacing, outside, small sphere
    for (const GradedSpacing spacing : {GradedSpacing{0.5, 3}, GradedSpacing{1.0, 2}, GradedSpacing{0.25, 10}}) {
        for (const TetRegion region : {TetRegion::Inside, TetRegion::Outside}) {
            const auto uniform = interior_points(s.field, *s.g, region);
            const auto graded = interior_points(s.field, *s.g, region, nullptr, &spacing);
            const openvdb::Coord anchor = volume_box(s.field, *s.g, &spacing).min();
            const std::set<openvdb::Coord> kept(graded.begin(), graded.end());
            REQUIRE(kept.size() == graded.size());
            // Outside, the graded box is larger: compare on the samples both hold.
            const openvdb::CoordBBox common = volume_box(s.field, *s.g);
            std::size_t checked = 0, coarse = 0;
            for (const auto& c : uniform) {
                const int level = expected_level(s.chessboard_distance_to_g(c), spacing);
                const int step = 1 << level;
                const openvdb::Coord r = c - anchor;
                const bool on_lattice = r.x() % step == 0 && r.y() % step == 0 && r.z() % step == 0;
                INFO("grading " << spacing.grading << " max level " << spacing.max_level << " at " << c);
                CHECK(kept.count(c) == (on_lattice ? 1u : 0u));
                ++checked;
                coarse += level > 0;
                if (small && region == TetRegion::Outside && spacing.grading == 0.5) ++per_level[std::size_t(level)];
            }
            // The small sphere's inside is a few hundred samples, all near G.
            const bool few = small && region == TetRegion::Inside;
            CHECK(checked > (few ? 100u : 1000u));
            if (!few) CHECK(coarse > 0); // the rule was exercised beyond the finest lattice
            for (const auto& c : graded)
                if (common.isInside(c))
                    CHECK(std::binary_search(
                        uniform.begin(), uniform.end(), c, [](const openvdb::Coord& a, const openvdb::Coord& b) {
                            return std::make_tuple(a.z(), a.y(), a.x()) < std::make_tuple(b.z(), b.y(), b.x());
                        }));
        }
    }
    if (small) {
        INFO("samples per level: " << per_level[0] << " " << per_level[1] << " " << per_level[2] << " "
                                   << per_level[3]);
        for (std::size_t l = 0; l < 4; ++l)
            CHECK(per_level[l] > 0);
    }
}

TEST_CASE("graded G' fills a box whose far faces hold lattice points, corners included", "[tets][interior_points]")
{
    const SphereSetup s;
    const GradedSpacing spacing{0.5, 3};
    const openvdb::CoordBBox box = volume_box(s.field, *s.g, &spacing);
    const openvdb::CoordBBox plain = volume_box(s.field, *s.g);
    CHECK(box.min() == plain.min());
    for (int a = 0; a < 3; ++a) {
        CHECK((box.max()[a] - box.min()[a]) % 8 == 0);
        CHECK(box.max()[a] >= plain.max()[a]);
        CHECK(box.max()[a] - plain.max()[a] < 8);
    }
    const auto pts = interior_points(s.field, *s.g, TetRegion::Outside, nullptr, &spacing);
    const std::set<openvdb::Coord> kept(pts.begin(), pts.end());
    for (int corner = 0; corner < 8; ++corner) {
        const openvdb::Coord c((corner & 1) ? box.max().x() : box.min().x(),
                               (corner & 2) ? box.max().y() : box.min().y(),
                               (corner & 4) ? box.max().z() : box.min().z());
        CHECK(kept.count(c) == 1);
    }
}

TEST_CASE("tet_size maps to the largest lattice level", "[tets][interior_points]")
{
    CHECK(graded_max_level(0, 0.5) == 3);    // default: 8 voxels
    CHECK(graded_max_level(4.0, 0.5) == 3);  // 8 voxels
    CHECK(graded_max_level(3.9, 0.5) == 2);  // rounded down
    CHECK(graded_max_level(0.5, 0.5) == 0);  // one voxel
    CHECK(graded_max_level(0.1, 0.5) == 0);  // below a voxel: the samples themselves
    CHECK(graded_max_level(1e9, 1.0) == 10); // clamped
    CHECK(graded_max_level(std::numeric_limits<double>::infinity(), 1.0) == 10);
    CHECK(graded_max_level(8.8, double(1.1f)) == 3); // a float32 voxel: 7.9999998 voxels is 8
}
