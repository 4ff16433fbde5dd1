// OpenVDB reader: grid choice, grid class -> inside side, double -> float, half-float files,
// sparse grids (lattice = active box), and the refusals.
#include "support/json.h"
#include "support/test_files.h"

#include <isodel/errors.h>
#include <isodel/volume.h>

#include <catch2/catch.hpp>
#include <openvdb/tools/LevelSetSphere.h>

using namespace isodel;
using namespace isodel::test;

namespace {
void write(const std::string& path, const openvdb::GridPtrVec& grids)
{
    openvdb::io::File f(path);
    f.write(grids);
    f.close();
}

template <typename GridT>
typename GridT::Ptr ramp(const std::string& name, double scale = 1.0)
{
    auto g = GridT::create(typename GridT::ValueType(0));
    g->setName(name);
    auto acc = g->getAccessor();
    for (int x = -2; x < 3; ++x)
        for (int y = 0; y < 4; ++y)
            for (int z = 1; z < 3; ++z)
                acc.setValue(openvdb::Coord(x, y, z), typename GridT::ValueType(scale * (x + 10 * y + 100 * z) + 0.1));
    g->setTransform(openvdb::math::Transform::createLinearTransform(0.25));
    return g;
}

std::string error_of(const std::string& path, const ReadOptions& opt = {})
{
    try {
        read_volume(path, opt);
    } catch (const isodel::Error& e) {
        return e.what();
    }
    return "(no error)";
}
} // namespace

TEST_CASE("VDB: default grid, grid class and transform", "[vdb]")
{
    TempDir dir;
    auto fog = ramp<openvdb::FloatGrid>("density");
    fog->setGridClass(openvdb::GRID_FOG_VOLUME);
    auto ls = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(1.0f, openvdb::Vec3f(0), 0.1f);
    ls->setName("surface");
    auto vec = openvdb::Vec3SGrid::create();
    vec->setName("velocity");
    vec->tree().setValue(openvdb::Coord(0), openvdb::Vec3s(1, 2, 3));
    write(dir / "a.vdb", {vec, fog, ls});

    const Volume first = read_volume(dir / "a.vdb"); // the vector grid is skipped
    CHECK(first.grid->getName() == "density");
    CHECK(first.default_inside == Inside::Above);
    CHECK(first.lattice == openvdb::CoordBBox(openvdb::Coord(-2, 0, 1), openvdb::Coord(2, 3, 2)));
    CHECK(first.grid->transform().voxelSize().x() == Approx(0.25));
    CHECK(first.value_min == Approx(-2 + 0 + 100 + 0.1));
    CHECK(first.value_max == Approx(2 + 30 + 200 + 0.1));

    ReadOptions opt;
    opt.grid_name = "surface";
    const Volume s = read_volume(dir / "a.vdb", opt);
    CHECK(s.grid->getName() == "surface");
    CHECK(s.default_inside == Inside::Below);
    // A narrow band: inactive voxels inside the active box read as +-background.
    CHECK(s.value_min == Approx(-ls->background()));
    CHECK(s.value_max == Approx(ls->background()));
}

TEST_CASE("VDB: double grids are converted to float", "[vdb]")
{
    TempDir dir;
    auto d = ramp<openvdb::DoubleGrid>("dbl", 1.0 / 3.0);
    write(dir / "d.vdb", {d});
    const Volume v = read_volume(dir / "d.vdb");
    auto a = v.grid->getConstAccessor();
    auto b = d->getConstAccessor();
    for (auto it = v.lattice.begin(); it; ++it) CHECK(a.getValue(*it) == float(b.getValue(*it)));
    CHECK(v.grid->activeVoxelCount() == d->activeVoxelCount());
}

TEST_CASE("VDB: half-float storage is decoded", "[vdb]")
{
    TempDir dir;
    auto g = ramp<openvdb::FloatGrid>("h", 0.001);
    g->setSaveFloatAsHalf(true);
    write(dir / "h.vdb", {g});
    const Volume v = read_volume(dir / "h.vdb");
    auto a = v.grid->getConstAccessor();
    auto b = g->getConstAccessor();
    for (auto it = v.lattice.begin(); it; ++it) {
        const float want = float(openvdb::math::half(b.getValue(*it)));
        CHECK(a.getValue(*it) == want);
    }
}

TEST_CASE("VDB refusals", "[vdb][errors]")
{
    TempDir dir;
    const std::string p = dir / "x.vdb";
    SECTION("non-scalar grid only")
    {
        auto vec = openvdb::Vec3SGrid::create();
        vec->setName("velocity");
        vec->tree().setValue(openvdb::Coord(0), openvdb::Vec3s(1, 2, 3));
        write(p, {vec});
        const std::string msg = error_of(p);
        CHECK(msg.rfind(p + ": no float or double scalar grid", 0) == 0);
        CHECK(msg.find("'velocity'") != std::string::npos);
        ReadOptions opt;
        opt.grid_name = "velocity";
        CHECK(error_of(p, opt).find("not a scalar grid") != std::string::npos);
    }
    SECTION("missing grid name lists the grids")
    {
        write(p, {ramp<openvdb::FloatGrid>("alpha"), ramp<openvdb::FloatGrid>("beta")});
        ReadOptions opt;
        opt.grid_name = "gamma";
        const std::string msg = error_of(p, opt);
        CHECK(msg.rfind(p + ": no grid named 'gamma'", 0) == 0);
        CHECK(msg.find("'alpha'") != std::string::npos);
        CHECK(msg.find("'beta'") != std::string::npos);
    }
    SECTION("empty grid")
    {
        auto g = openvdb::FloatGrid::create(0.f);
        g->setName("empty");
        write(p, {g});
        CHECK(error_of(p).rfind(p + ": empty grid 'empty'", 0) == 0);
    }
    SECTION("NaN voxel names its index")
    {
        auto g = ramp<openvdb::FloatGrid>("n");
        g->tree().setValue(openvdb::Coord(1, 2, 1), std::numeric_limits<float>::quiet_NaN());
        write(p, {g});
        CHECK(error_of(p) == p + ": NaN sample at index (i,j,k) = (1, 2, 1); non-finite samples are not accepted");
    }
    SECTION("wrong magic number")
    {
        write_bytes(p, std::string(64, 'x'));
        CHECK(error_of(p).rfind(p + ": not a readable OpenVDB file", 0) == 0);
    }
    SECTION("truncated file")
    {
        write(p, {ramp<openvdb::FloatGrid>("t")});
        const std::string bytes = read_text(p);
        write_bytes(p, bytes.substr(0, bytes.size() / 2));
        CHECK(error_of(p).rfind(p + ": ", 0) == 0);
    }
}

TEST_CASE("VDB: bundled test files read", "[vdb]")
{
    const std::string p = std::string(ISODEL_TEST_DATA) + "/torus.vdb";
    REQUIRE(file_exists(p));
    const Volume v = read_volume(p);
    CHECK(v.default_inside == Inside::Below);
    CHECK(v.value_min < 0);
    CHECK(v.value_max > 0);
    CHECK(v.grid->activeVoxelCount() > 0);
}

namespace read_vdb_corpus_test {
/// Every value and active state of \p expected (OpenVDB's own read) in \p got, at float
/// precision, the same active voxel count, background and transform.
template <class GridT>
void check_same_grid(const GridT& expected, const openvdb::FloatGrid& got)
{
    CHECK(got.activeVoxelCount() == expected.activeVoxelCount());
    CHECK(got.background() == float(expected.background()));
    CHECK(got.transform() == expected.transform());
    auto acc = got.getConstAccessor();
    std::size_t differ = 0;
    for (auto it = expected.cbeginValueOn(); it; ++it)
        differ += acc.getValue(it.getCoord()) != float(*it) || !acc.isValueOn(it.getCoord());
    for (auto leaf = expected.tree().cbeginLeaf(); leaf; ++leaf)
        for (auto v = leaf->cbeginValueOff(); v; ++v) differ += acc.getValue(v.getCoord()) != float(*v);
    CHECK(differ == 0);
}
} // namespace read_vdb_corpus_test

TEST_CASE("VDB: every corpus file reads as the grid OpenVDB reads without isodel's checks", "[vdb][corpus]")
{
    // The file check (octree/vdb_file_layout.h) only refuses: an accepted file reads exactly as
    // OpenVDB alone reads it, so the meshes of the corpus do not depend on it.
    if (!shared_data_present()) {
        WARN("skipped: the corpus (../shared/data) is absent");
        return;
    }
    openvdb::initialize();
    int files = 0;
    for (const auto& e : isodel::testing::read_json_file(std::string(ISODEL_SHARED_DATA) + "/manifest.json")) {
        if (isodel::testing::json_string(e, "format") != "vdb" || e.value("expect_error", false)) continue;
        const std::string path = std::string(ISODEL_SHARED_DATA) + "/" + isodel::testing::json_string(e, "file");
        CAPTURE(path);
        ReadOptions opt;
        opt.grid_name = e.value("grid_name", std::string());
        const Volume v = read_volume(path, opt);
        openvdb::io::File f(path);
        f.open(false);
        const auto base = f.readGrid(v.grid->getName());
        if (const auto fg = openvdb::gridPtrCast<openvdb::FloatGrid>(base))
            read_vdb_corpus_test::check_same_grid(*fg, *v.grid);
        else if (const auto dg = openvdb::gridPtrCast<openvdb::DoubleGrid>(base))
            read_vdb_corpus_test::check_same_grid(*dg, *v.grid);
        else
            FAIL("grid '" << v.grid->getName() << "' is neither float nor double");
        ++files;
    }
    CHECK(files > 10);
}
