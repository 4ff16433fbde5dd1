// cells/random_n16_s4 of ../shared/data: 16^3 uniform random samples, a cell saddle 3e-5 and face
// saddles 1e-4 from v. Its reference topology (12 components, one of genus 338) was undetermined
// until verify put lattice planes through near-critical points (src/verify/refined_lattice.h).
// At eps 0.5 isodel's mesh has genus 338 (certified, in the corpus runner); at 0.25 and 0.1 it has
// 340 and 341 - the crease cut next to a grid edge with both samples near v, an OPEN DEFECT of
// issue 4 (see tests/mesher/test_crease_near_grid_edge.cpp). [!mayfail] until it is fixed.
#include <catch2/catch.hpp>

#include "../mesher/mesher_test_support.h"


using namespace isodel;

TEST_CASE("crease cut: random_n16_s4 of ../shared/data has genus 338 at every eps", "[corpus][mesher][crease][!mayfail]")
{
    const std::string path = testing::shared_data() + "/cells/random_n16_s4.vdb";
    if (!testing::shared_file_present(path)) return;
    std::vector<int> genera(12, 0);
    genera.back() = 338;
    testing::require_certified(*testing::read_vdb(path, ""), {0.5, 0.25, 0.1}, genera);
}
