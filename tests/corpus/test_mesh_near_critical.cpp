// cells/random_n16_s4 of ../shared/data: 16^3 uniform random samples, a cell saddle 3e-5 and face
// saddles 1e-4 from v. Its reference topology (12 components, one of genus 338) was undetermined
// until verify put lattice planes through near-critical points (src/verify/refined_lattice.h).
// Around a grid edge whose samples are both near v and across which F turns back both ways,
// Sigma is four steep trilinear patches; the crease cut that came before the face slabs
// (octree/face_slabs.h) meshed genus 340 and 341 at eps 0.25 and 0.1 until it was kept away from
// such edges, and that guard broke other volumes (tests/refinement/test_knife_edge_creases.cpp).
#include <catch2/catch.hpp>

#include "support/mesher_test_support.h"


using namespace isodel;

TEST_CASE("knife-edge creases: random_n16_s4 of ../shared/data has genus 338 at every eps", "[corpus][mesher][crease]")
{
    const std::string path = testing::shared_data() + "/cells/random_n16_s4.vdb";
    if (!testing::shared_file_present(path)) return;
    std::vector<int> genera(12, 0);
    genera.back() = 338;
    testing::require_certified(*testing::read_vdb(path, ""), {0.5, 0.25, 0.1}, genera);
}
