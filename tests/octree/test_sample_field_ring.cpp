// The samples just beyond the lattice (sample_field.h, "Domain"): a dense file's grid has
// background 0, which may equal v (an MRC signed distance meshed at 0, the random and cell volumes
// of ../shared/data). That ring must read as outside and must not count as a tie with v; a
// background strictly outside (a fog volume's 0 below v) is still read through the grid.
#include "octree/sample_field.h"

#include <isodel/errors.h>

#include <catch2/catch.hpp>

#include <random>

using namespace isodel::octree;

namespace {

/// n^3 samples, all active, boundary layer -1, interior uniform in [-1, 1] away from 0.
openvdb::FloatGrid::Ptr dense_grid(int n, float background)
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.05f, 1.f);
    std::bernoulli_distribution sign(0.5);
    auto g = openvdb::FloatGrid::create(background);
    auto acc = g->getAccessor();
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const bool boundary = x == 0 || y == 0 || z == 0 || x == n - 1 || y == n - 1 || z == n - 1;
                acc.setValueOn(Coord(x, y, z), boundary ? -1.f : (sign(rng) ? 1.f : -1.f) * u(rng));
            }
    return g;
}

} // namespace

TEST_CASE("dense box with background = v: the ring is outside and not a tie", "[octree][sample_field]")
{
    const auto g = dense_grid(8, 0.f);
    const SampleField f(g, 0.0, isodel::Inside::Above);
    CHECK(f.effective_isovalue() == 0.0); // no sample, face saddle or ring sample equals v
    SampleField::Reader r(f);
    CHECK(r.phi(Coord(-1, 3, 3)) == f.outside_phi());
    CHECK(r.phi(Coord(3, 8, 3)) == f.outside_phi());
    CHECK(r.phi(Coord(3, 3, 3)) == f.phi_of_value(g->tree().getValue(Coord(3, 3, 3))));

    // The same for inside = below: the background 0 = v is on the inside side's boundary.
    const SampleField below(g, 0.0, isodel::Inside::Below);
    CHECK(below.effective_isovalue() == 0.0);
    CHECK(SampleField::Reader(below).phi(Coord(8, 8, 8)) == below.outside_phi());
}

TEST_CASE("background strictly outside: the ring reads it through the grid", "[octree][sample_field]")
{
    const auto g = dense_grid(8, -0.5f);
    const SampleField f(g, 0.0, isodel::Inside::Above);
    SampleField::Reader r(f);
    CHECK(r.phi(Coord(-1, 3, 3)) == f.phi_of_value(-0.5));
    CHECK(r.phi(Coord(-2, 3, 3)) == f.outside_phi()); // beyond the ring
}

TEST_CASE("an inactive sample at v inside the lattice is still a tie", "[octree][sample_field]")
{
    auto g = dense_grid(8, 0.f);
    g->tree().setValueOff(Coord(3, 3, 3), 0.f); // reads the background 0 = v
    const SampleField f(g, 0.0, isodel::Inside::Above);
    CHECK(f.effective_isovalue() < 0.0);
}

TEST_CASE("values stored beyond the ring are no samples: they neither widen the range nor tie", "[octree][sample_field]")
{
    // Background -0.5 is strictly outside (inside = above 0), so the ring reads it; an inactive
    // tile of 5 and one of 0 = v far beyond the ring are no samples of F.
    auto g = dense_grid(8, -0.5f);
    g->tree().addTile(1, Coord(800, 0, 0), 5.f, false);
    g->tree().addTile(1, Coord(-808, 0, 0), 0.f, false);
    const SampleField f(g, 0.0, isodel::Inside::Above);
    CHECK(f.value_max() < 1.0); // the interior samples' max (below 1 by construction), not 5
    CHECK(f.effective_isovalue() == 0.0);            // the tile at v is no tie
    // A level only the far tile reaches is refused: the level set within the domain is empty.
    CHECK_THROWS_AS(SampleField(g, 3.0, isodel::Inside::Above), isodel::InvalidInput);
    // A tile that reaches into the ring is a sample there: it widens the range.
    g->tree().addTile(1, Coord(-8, 0, 0), 5.f, false);
    CHECK(SampleField(g, 0.0, isodel::Inside::Above).value_max() == 5.0);
}
