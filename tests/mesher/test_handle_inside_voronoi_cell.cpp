// A handle of Sigma inside one Voronoi cell: CBP_VC checks that a vertex's restricted facets form
// one cycle, which a torus minus a disk also does, so such a handle can vanish from M with every
// Voronoi edge and facet a closed ball (paper Theorem 5 says cubic cells rule this out; measured,
// they do not). tunnel_shoulders seeds the necks of one cell's interior saddles; this volume has
// a handle it does not catch. Known defect, kept as a reproducer ([!mayfail]).
#include <catch2/catch.hpp>

#include "mesher_test_support.h"
#include "../verify/verify_test_support.h"

using namespace isodel;

TEST_CASE("closed ball: a handle inside one Voronoi cell stays in M (held-out random seed 253)",
          "[mesher][closed_ball][!mayfail]")
{
    // testing::random_volume(5, 253), plain, eps 0.5 voxel (2026-11-26): M has genus [0, 0, 6]
    // with 515 vertices; the reference gives [0, 0, 7] at every R from 16 to 64 (4 critical
    // planes). cbp_audit finds no Voronoi edge crossing Sigma twice and no Voronoi facet with more
    // than two boundary crossings or an interior loop, and every crease cut of
    // MeshOptions::certify's list gives genus 6: the defect is not the crease cut's.
    testing::require_certified(*testing::random_volume(5, 253, false), {0.5}, {0, 0, 7});
}
