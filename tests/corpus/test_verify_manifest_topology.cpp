// Reference topology of isodel verify (check 1) against the manifest's expected_topology for every
// .vdb volume of ../shared/data that has one, except the single-cell and random volumes, which
// tests/verify/test_verify_reference.cpp covers. Slow-ish (the 136^3 bunny): label "corpus".
#include <catch2/catch.hpp>

#include "support/skip.h"

#include "support/verify_test_support.h"

#include <isodel/verify.h>

#include <algorithm>

using namespace isodel;

TEST_CASE("verify reference topology equals the manifest's expected topology", "[corpus][verify]")
{
    const auto manifest = testing::read_manifest();
    if (!manifest.is_array()) {
        ISODEL_SKIP("../shared/data not found at " << testing::shared_data());
    }
    int checked = 0;
    for (const auto& e : manifest) {
        const std::string cat = testing::json_string(e, "category");
        if (testing::json_string(e, "format") != "vdb" || cat == "mc-ambiguity-cell" || cat == "random") continue;
        if (!testing::json_has(e, "expected_topology") || !testing::json_has(e.at("expected_topology"), "genus"))
            continue;
        const std::string file = testing::json_string(e, "file");
        auto grid = testing::read_vdb(testing::shared_data() + "/" + file, testing::json_string(e, "grid_name"));
        const Inside inside = testing::json_string(e, "inside") == "below" ? Inside::Below : Inside::Above;
        const auto r = reference_topology(*grid, testing::json_number(e, "isovalue"), inside);
        std::vector<int> expected, got;
        for (const auto& v : e.at("expected_topology").at("genus")) expected.push_back(v.get<int>());
        for (const auto& c : r.components) got.push_back(c.genus);
        std::sort(expected.begin(), expected.end());
        INFO(file << ": refinements " << r.refinements.front() << ".." << r.refinements.back() << ", " << r.seconds << " s");
        CHECK(r.determined);
        CHECK(got == expected);
        ++checked;
    }
    CHECK(checked >= 12);
}
