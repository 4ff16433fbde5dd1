#pragma once
// Small helpers shared by the programs in tools/bench/ and tools/qa/ (compare_bench,
// corpus_runner, random_sweep): comma lists on the command line, lookups in
// ../shared/data/manifest.json, and one-line topology summaries of a triangle soup or of isodel's
// own statistics, printed the same way so tables can be compared column to column.
#include <isodel/mesh.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

namespace isodel::bench {

/// "a,b,,c" -> {"a", "b", "c"}.
inline std::vector<std::string> split(const std::string& s)
{
    std::vector<std::string> out;
    std::stringstream ss(s);
    std::string x;
    while (std::getline(ss, x, ','))
        if (!x.empty()) out.push_back(x);
    return out;
}

/// A manifest entry's string at \p key, or "" when absent or null (the manifest writes null for
/// "none", e.g. the grid name of a dense file).
inline std::string json_string(const nlohmann::json& entry, const char* key)
{
    const auto it = entry.find(key);
    return it != entry.end() && it->is_string() ? it->get<std::string>() : std::string();
}

/// A manifest entry's number at \p key, or 0 when absent or null.
inline double json_number(const nlohmann::json& entry, const char* key)
{
    const auto it = entry.find(key);
    return it != entry.end() && it->is_number() ? it->get<double>() : 0.0;
}

/// A manifest entry marked "expect_error": true (a file every reader must refuse).
inline bool expects_error(const nlohmann::json& entry)
{
    const auto it = entry.find("expect_error");
    return it != entry.end() && it->is_boolean() && it->get<bool>();
}

/// The manifest entry's "dims" as "NxNxN".
inline std::string dims_string(const nlohmann::json& entry)
{
    std::string dims;
    const auto it = entry.find("dims");
    if (it == entry.end() || !it->is_array()) return dims;
    for (std::size_t k = 0; k < it->size(); ++k) dims += (k ? "x" : "") + std::to_string((*it)[k].get<long long>());
    return dims;
}

/// "N comp, genus g1 g2 ..." (sorted), or a count of components with positive genus when long.
inline std::string genus_summary(std::vector<long long> genera)
{
    std::sort(genera.begin(), genera.end());
    std::string s = std::to_string(genera.size()) + " comp";
    if (genera.size() <= 8) {
        s += ", genus";
        for (auto g : genera) s += " " + std::to_string(g);
    } else {
        long long nz = 0, sum = 0;
        for (auto g : genera) nz += g != 0, sum += g;
        s += ", " + std::to_string(nz) + " with genus>0 (sum " + std::to_string(sum) + ")";
    }
    return s;
}

/// Components and genera of a triangle soup given by vertex ids: union-find over vertices,
/// chi = V - E + F per component, genus = (2 - chi) / 2; counts edges not shared by exactly two
/// triangles (then the genus is not meaningful: reported as such).
inline std::string soup_topology(const std::vector<std::array<std::int64_t, 3>>& tris)
{
    std::unordered_map<std::int64_t, std::int64_t> parent;
    std::function<std::int64_t(std::int64_t)> find = [&](std::int64_t x) {
        while (parent[x] != x) {
            parent[x] = parent[parent[x]];
            x = parent[x];
        }
        return x;
    };
    for (const auto& t : tris)
        for (auto v : t)
            if (!parent.count(v)) parent[v] = v;
    for (const auto& t : tris) {
        const auto a = find(t[0]);
        for (int j = 1; j < 3; ++j) {
            const auto b = find(t[j]);
            if (a != b) parent[b] = a;
        }
    }
    std::map<std::pair<std::int64_t, std::int64_t>, int> edges;
    for (const auto& t : tris)
        for (int j = 0; j < 3; ++j) {
            auto a = t[j], b = t[(j + 1) % 3];
            if (a > b) std::swap(a, b);
            ++edges[{a, b}];
        }
    std::map<std::int64_t, long long> chi; // root -> V - E + F
    for (auto& [v, p] : parent) chi[find(v)] += 1;
    long long nonmanifold = 0;
    for (const auto& [e, n] : edges) {
        chi[find(e.first)] -= 1;
        if (n != 2) ++nonmanifold;
    }
    for (const auto& t : tris) chi[find(t[0])] += 1;
    std::vector<long long> genera;
    for (const auto& [r, c] : chi) genera.push_back((2 - c) / 2);
    if (nonmanifold) { // the genus is meaningless: report chi = V - E + F of the whole soup
        long long total = 0;
        for (const auto& [r, c] : chi) total += c;
        return std::to_string(genera.size()) + " comp, not a manifold (" + std::to_string(nonmanifold) +
               " edges not in exactly 2 triangles), chi " + std::to_string(total);
    }
    return genus_summary(std::move(genera));
}

/// The same summary of isodel's own per-component statistics.
inline std::string isodel_topology(const MeshStats& st)
{
    std::vector<long long> g;
    for (const auto& c : st.components) g.push_back(c.genus);
    return genus_summary(std::move(g));
}

} // namespace isodel::bench
