// `isodel info` reports what the mesher's work follows on a sparse grid, next to its box: the
// active voxels, the leaf nodes and the tiles (active ones apart), as text and as --json. The
// counts are checked against OpenVDB's own on a grid built with known leaves and tiles.
#include <catch2/catch.hpp>

#include "support/json.h"
#include "support/test_files.h"

#include <openvdb/openvdb.h>

using namespace isodel::test;

TEST_CASE("isodel info: active voxels, leaf nodes and tiles of a sparse grid", "[cli][info][sparse]")
{
    TempDir dir, scratch;
    auto grid = openvdb::FloatGrid::create(0.f);
    grid->setName("density");
    // Two active 8^3 tiles and one inactive one, then voxels in three leaf nodes far apart.
    grid->tree().fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(7, 7, 15)), 1.f, true);
    grid->tree().fill(openvdb::CoordBBox(openvdb::Coord(64), openvdb::Coord(71)), 2.f, false);
    for (const openvdb::Coord c : {openvdb::Coord(-500, 3, 3), openvdb::Coord(900, 0, 0), openvdb::Coord(0, 2000, 1)})
        grid->tree().setValueOn(c, 0.5f);
    openvdb::io::File(dir / "sparse.vdb").write({grid});
    REQUIRE(grid->tree().leafCount() == 3);

    const RunResult json = run_isodel("info " + shell_quote(dir / "sparse.vdb") + " --json", scratch.path());
    REQUIRE(json.status == 0);
    const auto j = nlohmann::json::parse(json.out);
    CHECK(j["active_voxels"].get<long long>() == 2 * 512 + 3);
    CHECK(j["leaf_nodes"].get<long long>() == 3);
    CHECK(j["tiles"].get<long long>() == 3);
    CHECK(j["active_tiles"].get<long long>() == 2);

    const RunResult text = run_isodel("info " + shell_quote(dir / "sparse.vdb"), scratch.path());
    REQUIRE(text.status == 0);
    CHECK(text.out.find("1027 in 3 leaf nodes of 8^3 and 2 active tiles (3 tiles in all)") != std::string::npos);
}
