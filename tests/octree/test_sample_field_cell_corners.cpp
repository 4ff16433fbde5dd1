// SampleField::Reader::cell_corners reads a cell's eight corners in one leaf probe when they share
// a leaf: it must give exactly the eight phi() reads everywhere, across leaf boundaries, over
// tiles, on the ring beyond the lattice, outside the domain and in a clipped field.
#include "octree/sample_field.h"

#include <catch2/catch.hpp>

#include <random>

using namespace isodel::octree;

namespace {

/// Random samples in [-1, 1] on [-5, 14]^3 (leaves of 8^3 from -8 to 16), a constant tile of
/// 8^3 at [16, 23]^3 beside them, background \p background.
openvdb::FloatGrid::Ptr patchwork_grid(float background)
{
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    auto g = openvdb::FloatGrid::create(background);
    auto acc = g->getAccessor();
    for (int z = -5; z <= 14; ++z)
        for (int y = -5; y <= 14; ++y)
            for (int x = -5; x <= 14; ++x) acc.setValueOn(Coord(x, y, z), u(rng));
    g->tree().fill(openvdb::CoordBBox(Coord(16), Coord(23)), 0.25f, true);
    return g;
}

void check_all_cells(const SampleField& f, const openvdb::CoordBBox& box)
{
    SampleField::Reader r(f);
    SampleField::Reader fresh(f); // separate accessor cache, so probes and reads interleave
    std::size_t n = 0, mismatches = 0;
    for (auto it = box.begin(); it; ++it) {
        const Coord c = *it;
        double corners[8];
        r.cell_corners(c, corners);
        for (int k = 0; k < 8; ++k) {
            ++n;
            if (corners[k] != fresh.phi(c.offsetBy(k & 1, (k >> 1) & 1, (k >> 2) & 1))) ++mismatches;
        }
    }
    CHECK(n == 8 * box.volume());
    CHECK(mismatches == 0);
}

} // namespace

TEST_CASE("cell corners: one leaf probe gives the eight phi reads, background = v (ring outside)",
          "[octree][sample_field]")
{
    const auto g = patchwork_grid(0.f);
    check_all_cells(SampleField(g, 0.0, isodel::Inside::Above), openvdb::CoordBBox(Coord(-9), Coord(25)));
    check_all_cells(SampleField(g, 0.1, isodel::Inside::Below), openvdb::CoordBBox(Coord(-9), Coord(25)));
}

TEST_CASE("cell corners: one leaf probe gives the eight phi reads, background read through the grid",
          "[octree][sample_field]")
{
    const auto g = patchwork_grid(-2.f);
    const SampleField f(g, 0.0, isodel::Inside::Above);
    check_all_cells(f, openvdb::CoordBBox(Coord(-9), Coord(25)));
    // A clipped field (a partition block): its domain ends inside leaves.
    check_all_cells(SampleField(f, openvdb::CoordBBox(Coord(-2, 0, 3), Coord(9, 13, 11))),
                    openvdb::CoordBBox(Coord(-6), Coord(17)));
}
