// `isodel info --json` on every volume of ../shared/data/manifest.json: dims, voxel size, origin
// and value range must agree with the manifest and with an independent reader (mrcfile, vdb_print,
// numpy). Entries marked expect_error must be refused with exit code 2.
//
// OpenVDB files store only active voxels: padding equal to the background is not in the file, so
// the active box of a sparse .vdb (proteins, narrow bands, cells) can be smaller than the
// manifest's lattice. For those the reported box must lie inside the manifest's and agree with
// vdb_print exactly; for dense .vdb files (active box == manifest box) everything must be equal.
#include "support/json.h"
#include "support/test_files.h"

#include <catch2/catch.hpp>

#include "support/skip.h"

#include <algorithm>
#include <cmath>

using namespace isodel::test;
using isodel::testing::Json;
using isodel::testing::json_has;
using isodel::testing::read_json_file;

namespace {

const std::string kData = ISODEL_SHARED_DATA;

bool close(double a, double b, double rel, double abs_tol = 1e-12)
{
    return std::abs(a - b) <= abs_tol + rel * std::max(std::abs(a), std::abs(b));
}

std::string independent_script() { return std::string(ISODEL_TEST_DATA) + "/../cli/independent_reader.py"; }

} // namespace

TEST_CASE("isodel info agrees with manifest.json and independent readers", "[cli][manifest]")
{
    if (!shared_data_present()) {
        ISODEL_SKIP("../shared/data (manifest.json) is absent: manifest test skipped, nothing was checked");
    }
    TempDir tmp;
    const Json manifest = read_json_file(kData + "/manifest.json");
    REQUIRE(manifest.is_array());
    REQUIRE(manifest.size() > 0);
    bool warned_independent = false;
    std::size_t checked = 0, sparse_vdb = 0;
    for (const Json& e : manifest) {
        const std::string file = e.at("file").get<std::string>();
        const std::string path = kData + "/" + file;
        INFO("manifest entry " << file);
        const RunResult r = run_isodel("info --json " + shell_quote(path), tmp.path());
        if (e.value("expect_error", false)) {
            CHECK(r.status == 2);
            CHECK(r.err.rfind("isodel: " + path + ": ", 0) == 0);
            CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
            continue;
        }
        INFO("stderr: " << r.err);
        REQUIRE(r.status == 0);
        const Json info = Json::parse(r.out);
        const std::string fmt = e.at("format").get<std::string>();
        CHECK(info.at("format").get<std::string>() == fmt);
        if (json_has(e, "grid_name"))
            CHECK(info.at("grid_name").get<std::string>() == e.at("grid_name").get<std::string>());
        if (json_has(e, "grid_class"))
            CHECK(info.at("grid_class").get<std::string>() == e.at("grid_class").get<std::string>());

        // Lattice.
        std::array<int, 3> mdims{}, idims{};
        for (int a = 0; a < 3; ++a) {
            mdims[a] = e.at("dims")[a].get<int>();
            idims[a] = info.at("dims")[a].get<int>();
        }
        bool dense = true;
        if (fmt == "vdb") {
            for (int a = 0; a < 3; ++a) {
                CHECK(info.at("index_bbox")[0][a].get<double>() >= e.at("index_bbox")[0][a].get<double>());
                CHECK(info.at("index_bbox")[1][a].get<double>() <= e.at("index_bbox")[1][a].get<double>());
                if (info.at("index_bbox")[0][a].get<double>() != e.at("index_bbox")[0][a].get<double>() ||
                    info.at("index_bbox")[1][a].get<double>() != e.at("index_bbox")[1][a].get<double>())
                    dense = false;
            }
            sparse_vdb += !dense;
        }
        if (dense) CHECK(idims == mdims);

        // Voxel size and origin (world position of the manifest lattice's first sample).
        for (int a = 0; a < 3; ++a)
            CHECK(close(info.at("voxel_size")[a].get<double>(), e.at("voxel_size")[a].get<double>(), 1e-6));
        std::array<double, 3> first{0, 0, 0};
        if (json_has(e, "index_bbox"))
            for (int a = 0; a < 3; ++a) first[a] = e.at("index_bbox")[0][a].get<double>();
        const Json& M = info.at("index_to_world");
        for (int c = 0; c < 3; ++c) {
            double w = M[3][c].get<double>();
            for (int r = 0; r < 3; ++r) w += first[r] * M[r][c].get<double>();
            CHECK(close(w, e.at("origin")[c].get<double>(), 1e-6, 1e-6));
        }
        if (json_has(e, "index_to_world"))
            for (int r = 0; r < 4; ++r)
                for (int c = 0; c < 4; ++c)
                    CHECK(close(M[r][c].get<double>(), e.at("index_to_world")[r][c].get<double>(), 1e-6, 1e-9));

        // Value range: equal for dense lattices; inside the manifest's range otherwise.
        const double mlo = e.at("value_range")[0].get<double>(), mhi = e.at("value_range")[1].get<double>();
        const double ilo = info.at("value_range")[0].get<double>(), ihi = info.at("value_range")[1].get<double>();
        const double tol = 1e-6 * std::max({std::abs(mlo), std::abs(mhi), 1e-30});
        if (dense) {
            CHECK(std::abs(ilo - mlo) <= tol);
            CHECK(std::abs(ihi - mhi) <= tol);
        } else {
            CHECK(ilo >= mlo - tol);
            CHECK(ihi <= mhi + tol);
        }

        // Independent reader.
        const RunResult ind = run("/usr/bin/python3 " + shell_quote(independent_script()) + " " + shell_quote(path),
                                  tmp.path());
        if (ind.status == 3 || ind.status == 127) {
            if (!warned_independent) WARN("independent reader unavailable (" << ind.out << ind.err << "): cross-check skipped");
            warned_independent = true;
        } else {
            INFO("independent reader: " << ind.out << ind.err);
            REQUIRE(ind.status == 0);
            const Json ref = Json::parse(ind.out);
            for (int a = 0; a < 3; ++a) CHECK(idims[a] == ref.at("dims")[a].get<int>());
            if (fmt == "vdb") {
                // vdb_print prints about 3 (voxel size) to 5 (values) significant digits.
                CHECK(info.at("active_voxels").get<double>() == ref.at("active_voxels").get<double>());
                for (int a = 0; a < 3; ++a)
                    CHECK(close(info.at("voxel_size")[a].get<double>(), ref.at("voxel_size_printed")[a].get<double>(), 1e-2));
                const double ptol = 1e-4 * std::max({std::abs(ihi), std::abs(ilo), 1e-30});
                CHECK(ilo <= ref.at("active_range")[0].get<double>() + ptol);
                CHECK(ihi >= ref.at("active_range")[1].get<double>() - ptol);
                if (info.at("active_voxels").get<double>() == double(idims[0]) * idims[1] * idims[2]) {
                    CHECK(std::abs(ilo - ref.at("active_range")[0].get<double>()) <= ptol);
                    CHECK(std::abs(ihi - ref.at("active_range")[1].get<double>()) <= ptol);
                }
            } else {
                for (int a = 0; a < 3; ++a)
                    CHECK(close(info.at("voxel_size")[a].get<double>(), ref.at("voxel_size")[a].get<double>(), 1e-6));
                CHECK(close(ilo, ref.at("value_range")[0].get<double>(), 1e-6, tol));
                CHECK(close(ihi, ref.at("value_range")[1].get<double>(), 1e-6, tol));
            }
        }
        ++checked;
    }
    CHECK(checked + 1 >= manifest.size()); // all but the expect_error entry were read
    if (sparse_vdb) WARN(sparse_vdb << " sparse .vdb files: active box inside the manifest lattice (see file comment)");
}
