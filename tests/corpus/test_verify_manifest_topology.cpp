// Reference topology of isodel verify (check 1) against the manifest's expected_topology for every
// .vdb volume of ../shared/data that has one, except the single-cell and random volumes, which
// tests/verify/test_verify_reference.cpp covers. Slow-ish (the 136^3 bunny): label "corpus".
#include <catch2/catch.hpp>

#include "support/verify_test_support.h"

#include <isodel/verify.h>

#include <algorithm>

using namespace isodel;

TEST_CASE("verify reference topology equals the manifest's expected topology", "[corpus][verify]")
{
    const auto manifest = testing::read_manifest();
    if (manifest.type != minijson::Value::Array) {
        WARN("../shared/data not found at " << testing::shared_data() << ": test skipped");
        SUCCEED();
        return;
    }
    int checked = 0;
    for (const auto& e : manifest.arr) {
        const std::string cat = e["category"].as_string();
        if (e["format"].as_string() != "vdb" || cat == "mc-ambiguity-cell" || cat == "random") continue;
        if (!e.has("expected_topology") || !e["expected_topology"].has("genus")) continue;
        const std::string file = e["file"].as_string();
        auto grid = testing::read_vdb(testing::shared_data() + "/" + file, e["grid_name"].as_string());
        const Inside inside = e["inside"].as_string() == "below" ? Inside::Below : Inside::Above;
        const auto r = reference_topology(*grid, e["isovalue"].as_number(), inside);
        std::vector<int> expected, got;
        for (const auto& v : e["expected_topology"]["genus"].arr) expected.push_back(int(v.num));
        for (const auto& c : r.components) got.push_back(c.genus);
        std::sort(expected.begin(), expected.end());
        INFO(file << ": refinements " << r.refinements.front() << ".." << r.refinements.back() << ", " << r.seconds << " s");
        CHECK(r.determined);
        CHECK(got == expected);
        ++checked;
    }
    CHECK(checked >= 12);
}
