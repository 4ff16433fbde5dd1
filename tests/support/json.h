#pragma once
// JSON in the tests (../shared/data/manifest.json, `isodel info --json`, --stats, verify --json):
// nlohmann::json, plus lookups that treat an absent key and a null alike, as the manifest writes
// null for "none" (grid_name of a dense file, isovalue of a file that must be refused).
#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace isodel::testing {

using Json = nlohmann::json;

/// \p j has \p key with a value other than null.
inline bool json_has(const Json& j, const std::string& key)
{
    const auto it = j.find(key); // end() when j is not an object
    return it != j.end() && !it->is_null();
}

/// The string at \p key, or \p dflt when it is absent, null or not a string.
inline std::string json_string(const Json& j, const std::string& key, const std::string& dflt = "")
{
    const auto it = j.find(key);
    return it != j.end() && it->is_string() ? it->get<std::string>() : dflt;
}

/// The number at \p key, or \p dflt when it is absent, null or not a number.
inline double json_number(const Json& j, const std::string& key, double dflt = 0.0)
{
    const auto it = j.find(key);
    return it != j.end() && it->is_number() ? it->get<double>() : dflt;
}

/// The file \p path parsed. \throw std::runtime_error unreadable; nlohmann::json::parse_error.
inline Json read_json_file(const std::string& path)
{
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot read " + path);
    std::stringstream ss;
    ss << in.rdbuf();
    return Json::parse(ss.str());
}

} // namespace isodel::testing
