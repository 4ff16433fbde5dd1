// CBP_VF's loop clause (src/closed_ball/facet_loops.h): a needle of Sigma running up a grid edge
// pierces Voronoi facets as closed loops that no Voronoi edge sees. The values below are the
// neighbourhood of sample (20,10,27) of the blurred-atom map 1hpv_molmap_6A_2A (../shared/data),
// where a void of one sample narrows into a needle whose tip ends on the z edge above it; before
// the loop check M pinched the tip off as a separate tiny component.
#include <catch2/catch.hpp>

#include "support/mesher_test_support.h"

using namespace isodel;

namespace {

openvdb::FloatGrid::Ptr needle_void(double scale)
{
    // 4 x 4 x 4 samples minus the isovalue, rows y, columns x, from the real map.
    const double v[4][4][4] = {
        {{13.22107, 2.74497, 4.56875, 14.73871}, {8.24115, 0.62765, 0.16441, 2.83716},
         {11.74137, 5.32044, -0.37412, 3.11284}, {7.85579, 3.94094, 0.82297, 2.42204}},
        {{3.75492, 1.93515, 6.94675, 5.98724}, {3.73395, -0.30994, 0.57258, 0.87099},
         {14.94981, 5.20794, -1.11309, 2.33144}, {17.60975, 7.74001, 1.68180, 3.19062}},
        {{11.40341, 4.30167, 10.01909, 9.17951}, {6.95452, 0.08655, 1.26521, 1.33801},
         {7.04512, 2.30001, 3.94274, 0.00108}, {9.35369, 5.39783, 9.91345, 6.20385}},
        {{16.47394, 8.42457, 3.37031, 5.53929}, {13.73815, 3.23196, -0.32599, -2.32395},
         {12.11137, 7.04527, 8.24501, -1.44863}, {9.98925, 11.57327, 17.51325, 6.28262}},
    };
    // Inside = above the isovalue 0; a ring of positive samples closes every void.
    auto grid = openvdb::FloatGrid::create(float(5.0 * scale));
    auto acc = grid->getAccessor();
    for (int z = -1; z <= 4; ++z)
        for (int y = -1; y <= 4; ++y)
            for (int x = -1; x <= 4; ++x) {
                const bool core = x >= 0 && x < 4 && y >= 0 && y < 4 && z >= 0 && z < 4;
                acc.setValue(openvdb::Coord(x, y, z), float(scale * (core ? v[z][y][x] : 5.0)));
            }
    return grid;
}

} // namespace

TEST_CASE("a needle void up a grid edge stays one component", "[mesher][facet-loops]")
{
    for (double scale : {1.0, 0.5}) {
        auto grid = needle_void(scale);
        for (double eps : {0.5, 0.25}) {
            INFO("scale " << scale << ", eps " << eps << " voxel");
            const auto r = testing::mesh_and_verify(*grid, 0.0, Inside::Above, eps);
            INFO(r.report.summary());
            CHECK(r.report.reference.determined);
            CHECK(r.report.topology_verdict == TopologyVerdict::Pass);
            CHECK(r.report.passed());
        }
    }
}
