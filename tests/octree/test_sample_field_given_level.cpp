// A field read at a given level v* (the adaptive path's coarse fields read the input's v*,
// sample_field.h) skips the saddle scan, which decides only the tie rule's own shift: it must be
// the scanned field with that level set, sample for sample, and accept or refuse the value range
// as the scanned field does (v at the end of the range: accepted only through a tie).
#include "octree/sample_field.h"
#include "support/random_volume.h"

#include <isodel/errors.h>

#include <catch2/catch.hpp>

using namespace isodel::octree;

namespace {

void check_same_field(const SampleField& given, const SampleField& scanned)
{
    CHECK(given.effective_isovalue() == scanned.effective_isovalue());
    CHECK(given.value_min() == scanned.value_min());
    CHECK(given.value_max() == scanned.value_max());
    CHECK(given.outside_phi() == scanned.outside_phi());
    CHECK(given.domain() == scanned.domain());
    CHECK(given.lattice() == scanned.lattice());
    SampleField::Reader a(given), b(scanned);
    CoordBBox around = scanned.domain();
    around.expand(2);
    for (auto it = around.beginZYX(); it; ++it) REQUIRE(a.phi(*it) == b.phi(*it));
}

} // namespace

TEST_CASE("a field at a given level is the scanned field with that level", "[octree][sample_field]")
{
    for (bool tie : {false, true}) {
        INFO((tie ? "a sample at v" : "no sample at v"));
        // Quantized samples: many at v; continuous ones: none (the shift is then 0).
        const auto g = isodel::testing::random_volume(8, 5, tie);
        for (isodel::Inside side : {isodel::Inside::Above, isodel::Inside::Below}) {
            SampleField scanned(g, 0.0, side);
            CHECK((scanned.effective_isovalue() < 0.0) == tie);
            const double v_star = -0.125;
            scanned.set_effective_isovalue(v_star);
            check_same_field(SampleField(g, 0.0, side, v_star), scanned);
        }
    }
}

TEST_CASE("a field at a given level accepts and refuses the value range as the scanned one", "[octree][sample_field]")
{
    // Every sample >= v, the smallest exactly v: the level set is the tie rule's thin feature,
    // accepted only because a sample equals v.
    auto g = openvdb::FloatGrid::create(1.f);
    auto acc = g->getAccessor();
    for (int z = 0; z < 4; ++z)
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x) acc.setValueOn(Coord(x, y, z), 1.f);
    acc.setValueOn(Coord(1, 2, 1), 0.f);
    const SampleField scanned(g, 0.0, isodel::Inside::Below);
    CHECK(scanned.effective_isovalue() < 0.0); // accepted, shifted below v
    const SampleField given(g, 0.0, isodel::Inside::Below, scanned.effective_isovalue());
    CHECK(given.effective_isovalue() == scanned.effective_isovalue());
    // No sample at v: the level set is empty either way.
    acc.setValueOn(Coord(1, 2, 1), 0.5f);
    CHECK_THROWS_AS(SampleField(g, 0.0, isodel::Inside::Below), isodel::InvalidInput);
    CHECK_THROWS_AS(SampleField(g, 0.0, isodel::Inside::Below, -0.01), isodel::InvalidInput);
}
