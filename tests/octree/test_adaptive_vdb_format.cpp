// The adaptive .vdb format (adaptive_vdb_format.h): save -> load exact, info, vdb_print.
#include "support/adaptive_random.h"

#include "octree/adaptive_vdb_format.h"

#include <isodel/adaptive.h>
#include <isodel/errors.h>

#include <catch2/catch.hpp>
#include <openvdb/points/PointDataGrid.h>

#include <cstdlib>
#include <filesystem>

using namespace isodel::octree;

namespace {
/// \p g as the public AdaptiveVolume save_adaptive writes (k stays its default, 1).
isodel::AdaptiveVolume volume_of(const AdaptiveGrid& g)
{
    isodel::AdaptiveVolume v;
    v.samples = openvdb::ConstPtrCast<openvdb::FloatGrid>(g.samples_ptr());
    v.levels = g.masks();
    v.domain = g.domain();
    return v;
}

template <typename GridT>
bool same_grid(const GridT& a, const GridT& b)
{
    if (a.activeVoxelCount() != b.activeVoxelCount()) return false;
    if (a.background() != b.background()) return false;
    auto bacc = b.getConstAccessor();
    // Active values (voxels and tiles), then every voxel of the allocated leaf nodes (inactive
    // values too). Inactive upper-level tiles hold the background: not iterated voxel by voxel.
    for (auto it = a.cbeginValueOn(); it; ++it) {
        CoordBBox box;
        it.getBoundingBox(box);
        for (auto c = box.begin(); c; ++c)
            if (bacc.getValue(*c) != *it || !bacc.isValueOn(*c)) return false;
    }
    if (a.tree().leafCount() != b.tree().leafCount()) return false;
    for (auto leaf = a.tree().cbeginLeaf(); leaf; ++leaf)
        for (auto v = leaf->cbeginValueAll(); v; ++v)
            if (bacc.getValue(v.getCoord()) != *v || bacc.isValueOn(v.getCoord()) != v.isValueOn())
                return false;
    auto aacc = a.getConstAccessor();
    for (auto it = b.cbeginValueOn(); it; ++it)
        if (!aacc.isValueOn(it.getCoord())) return false;
    return a.transform() == b.transform();
}
} // namespace

TEST_CASE("save -> load is exact; info reports levels, k, histogram", "[octree][format]")
{
    const auto dir = std::filesystem::temp_directory_path() / "isodel_adaptive_format_test";
    std::filesystem::create_directories(dir);
    for (unsigned seed = 1; seed <= 3; ++seed) {
        auto g = testing::random_adaptive(500 + seed, int(seed), 18, 4);
        isodel::AdaptiveVolume v;
        v.samples = openvdb::ConstPtrCast<openvdb::FloatGrid>(g->samples_ptr());
        v.levels = g->masks();
        v.domain = g->domain();
        v.k = int(seed);
        v.tolerance = 0.25;
        v.source = "random seed " + std::to_string(seed);
        const std::string path = (dir / ("a" + std::to_string(seed) + ".vdb")).string();
        isodel::save_adaptive(path, v);
        const auto w = isodel::load_adaptive(path);
        CHECK(w.k == v.k);
        CHECK(w.tolerance == v.tolerance);
        CHECK(w.source == v.source);
        CHECK(w.domain == v.domain);
        REQUIRE(w.levels.size() == std::size_t(g->max_level() + 1));
        CHECK(same_grid(*w.samples, *v.samples));
        for (int l = 1; l <= g->max_level(); ++l) CHECK(same_grid(*w.levels[l], *v.levels[l]));
        const auto info = isodel::adaptive_info(path);
        REQUIRE(info);
        CHECK(info->k == v.k);
        CHECK(info->levels == g->max_level() + 1);
        CHECK(info->histogram == g->level_histogram());
        CHECK(info->cells == g->cell_count());
        if (std::system("command -v vdb_print >/dev/null 2>&1") == 0)
            CHECK(std::system(("vdb_print " + path + " >/dev/null 2>&1").c_str()) == 0);
    }
    // A plain volume is not adaptive.
    auto s = testing::random_samples(4, 1);
    const std::string plain = (dir / "plain.vdb").string();
    openvdb::io::File(plain).write({s});
    CHECK_FALSE(isodel::adaptive_info(plain));
    CHECK_THROWS_AS(isodel::load_adaptive(plain), isodel::InvalidInput);
    // The uniform volume round-trips with no mask grids.
    const auto u = isodel::uniform_adaptive(s, 2);
    isodel::save_adaptive(plain, u);
    const auto info = isodel::adaptive_info(plain);
    REQUIRE(info);
    CHECK(info->levels == 1);
    CHECK(info->cells == 5u * 5u * 5u);
    std::filesystem::remove_all(dir);
}

TEST_CASE("load_adaptive and read_importance_grid read only grids the file check walked", "[octree][format]")
{
    openvdb::initialize();
    const auto dir = std::filesystem::temp_directory_path() / "isodel_adaptive_format_only_checked";
    std::filesystem::create_directories(dir);
    auto g = testing::random_adaptive(77, 1, 12, 3);
    REQUIRE(g->max_level() >= 1);
    const isodel::AdaptiveVolume v = volume_of(*g);
    const std::string path = (dir / "adaptive.vdb").string();
    isodel::save_adaptive(path, v);
    // The same grids and a point grid (a type the check does not walk): still loads, the point
    // grid unread.
    openvdb::GridPtrVec grids;
    {
        openvdb::io::File f(path);
        f.open(false);
        grids = *f.getGrids();
    }
    auto points = openvdb::points::PointDataGrid::create();
    points->setName("points");
    grids.push_back(points);
    const std::string with_points = (dir / "with_points.vdb").string();
    openvdb::io::File(with_points).write(grids);
    const auto w = isodel::load_adaptive(with_points);
    CHECK(same_grid(*w.samples, *v.samples));
    // A level grid of another type is refused with one line, not read.
    for (auto& grid : grids)
        if (grid->getName() == "level_1") {
            auto p = openvdb::points::PointDataGrid::create();
            p->setName("level_1");
            grid = p;
        }
    const std::string bad_level = (dir / "bad_level.vdb").string();
    openvdb::io::File(bad_level).write(grids);
    CHECK_THROWS_WITH(isodel::load_adaptive(bad_level), Catch::Contains("grid level_1 has type"));
    CHECK_FALSE(isodel::adaptive_info(bad_level));
    // fuzz_load_adaptive: an adaptive file whose sample grid has no active voxel was loaded, and
    // resampling it failed without the file's name.
    auto empty = openvdb::FloatGrid::create(0.0f);
    empty->setName("samples");
    empty->insertMeta("isodel_adaptive", openvdb::Int32Metadata(1));
    empty->insertMeta("isodel_levels", openvdb::Int32Metadata(1));
    empty->insertMeta("isodel_domain_min", openvdb::Vec3IMetadata(openvdb::Vec3i(0)));
    empty->insertMeta("isodel_domain_max", openvdb::Vec3IMetadata(openvdb::Vec3i(4)));
    const std::string empty_path = (dir / "empty.vdb").string();
    openvdb::io::File(empty_path).write({empty});
    CHECK_THROWS_WITH(isodel::load_adaptive(empty_path),
                      Catch::StartsWith(empty_path + ": adaptive sample grid") && Catch::Contains("is empty"));
    // The importance grid: the grid OpenVDB lists first, if its type is walked.
    auto mask = openvdb::MaskGrid::create();
    mask->setName("a_mask");
    mask->tree().setValueOn(openvdb::Coord(3, 4, 5));
    const std::string importance = (dir / "importance.vdb").string();
    openvdb::io::File(importance).write({points, mask});
    const auto im = isodel::read_importance_grid(importance);
    REQUIRE(im);
    CHECK(im->getName() == "a_mask");
    CHECK(im->activeVoxelCount() == 1);
    points->setName("0_points"); // now listed first
    openvdb::io::File(importance).write({points, mask});
    CHECK_THROWS_WITH(isodel::read_importance_grid(importance), Catch::Contains("importance grid '0_points' has type"));
    std::filesystem::remove_all(dir);
}

TEST_CASE("load_adaptive refuses a level difference bound below 1, naming the file", "[octree][format]")
{
    // fuzz_load_adaptive: isodel_k = 0 was loaded and handed on (the balance and the 3k+1 bound
    // need k >= 1). The fuzzer's input, and the same metadata written by hand.
    openvdb::initialize();
    const std::string found = std::string(ISODEL_TEST_DATA) + "/../fuzz/findings/load_adaptive_k_zero.vdb";
    CHECK_THROWS_WITH(isodel::load_adaptive(found), Catch::StartsWith(found + ": isodel_k") && Catch::Contains("at least 1"));
    const auto dir = std::filesystem::temp_directory_path() / "isodel_adaptive_format_k";
    std::filesystem::create_directories(dir);
    const isodel::AdaptiveVolume v = volume_of(*testing::random_adaptive(5, 1, 8, 2));
    const std::string ok = (dir / "ok.vdb").string();
    isodel::save_adaptive(ok, v);
    CHECK(isodel::load_adaptive(ok).k == 1);
    for (const int k : {0, -3}) {
        openvdb::GridPtrVec grids;
        {
            openvdb::io::File f(ok);
            f.open(false);
            grids = *f.getGrids();
        }
        for (auto& grid : grids)
            if (grid->getName() == v.samples->getName() || grid->getName() == "samples") {
                grid->removeMeta("isodel_k");
                grid->insertMeta("isodel_k", openvdb::Int32Metadata(k));
            }
        const std::string bad = (dir / ("k" + std::to_string(k) + ".vdb")).string();
        openvdb::io::File(bad).write(grids);
        CHECK_THROWS_WITH(isodel::load_adaptive(bad), Catch::StartsWith(bad + ": isodel_k") &&
                                                          Catch::Contains("is " + std::to_string(k)));
        CHECK_THROWS_AS(isodel::load_adaptive(bad), isodel::InvalidInput);
    }
}
