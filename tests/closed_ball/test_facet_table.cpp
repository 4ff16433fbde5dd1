// FacetTable (src/closed_ball/facet_table.h), the open-addressing map behind FacetCache: it must
// agree with std::map under the insert/erase traffic of a refinement (long probe runs, erasures
// in the middle of runs, growth), and a value must stay where it is until its key is erased.
#include "closed_ball/facet_table.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <random>

using isodel::mesher::FacetKey;
using isodel::mesher::FacetTable;

namespace {

FacetKey key_of(std::uint32_t a, std::uint32_t b, std::uint32_t c)
{
    FacetKey k{{a, b, c}};
    std::sort(k.v.begin(), k.v.end());
    return k;
}

} // namespace

TEST_CASE("facet table: agrees with std::map under random inserts and erasures", "[facet-table]")
{
    std::mt19937 rng(12345);
    // Few distinct ids: many collisions in the probe runs, many erasures of present keys.
    std::uniform_int_distribution<std::uint32_t> id(0, 60);
    FacetTable<int> table;
    std::map<FacetKey, int> reference;
    std::map<FacetKey, const int*> where; // a value's address while its key is present
    for (int step = 0; step < 200000; ++step) {
        const FacetKey k = key_of(id(rng), id(rng), id(rng));
        if (rng() % 3 != 0) {
            const auto [value, fresh] = table.try_emplace(k, step);
            const auto [it, ref_fresh] = reference.try_emplace(k, step);
            REQUIRE(fresh == ref_fresh);
            REQUIRE(*value == it->second);
            if (fresh) where[k] = value;
            else REQUIRE(where[k] == value);
        } else {
            REQUIRE(table.erase(k) == (reference.erase(k) == 1));
            where.erase(k);
        }
        REQUIRE(table.size() == reference.size());
        const FacetKey probe = key_of(id(rng), id(rng), id(rng));
        REQUIRE(table.contains(probe) == (reference.count(probe) == 1));
    }
    // Every key still present is found, with its value at the same address.
    for (const auto& [k, v] : reference) {
        const auto [value, fresh] = table.try_emplace(k, -1);
        REQUIRE_FALSE(fresh);
        REQUIRE(*value == v);
        REQUIRE(where[k] == value);
    }
}

TEST_CASE("facet table: grows past many thousands of keys and empties again", "[facet-table]")
{
    FacetTable<std::uint32_t> table;
    const std::uint32_t n = 50000;
    for (std::uint32_t i = 0; i < n; ++i) REQUIRE(table.try_emplace(key_of(i, i + 1, i + 2), i).second);
    REQUIRE(table.size() == n);
    for (std::uint32_t i = 0; i < n; i += 2) REQUIRE(table.erase(key_of(i, i + 1, i + 2)));
    REQUIRE_FALSE(table.erase(key_of(0, 1, 2)));
    for (std::uint32_t i = 1; i < n; i += 2) {
        const auto [value, fresh] = table.try_emplace(key_of(i, i + 1, i + 2), 0);
        REQUIRE_FALSE(fresh);
        REQUIRE(*value == i);
    }
    REQUIRE(table.size() == n / 2);
    table.clear();
    REQUIRE(table.size() == 0);
    REQUIRE_FALSE(table.erase(key_of(1, 2, 3)));
    REQUIRE(table.try_emplace(key_of(1, 2, 3), 7).second);
}
