#pragma once
// A tiny JSON reader for the tests (manifest.json, `isodel info --json`): enough of RFC 8259 for
// objects, arrays, strings with simple escapes, numbers, true/false/null. Throws on bad input.
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace isodel::test {

struct Json {
    enum Kind { Null, Bool, Number, String, Array, Object } kind = Null;
    bool b = false;
    double num = 0;
    std::string str;
    std::vector<Json> arr;
    std::map<std::string, Json> obj;

    bool has(const std::string& k) const { return kind == Object && obj.count(k) && obj.at(k).kind != Null; }
    const Json& operator[](const std::string& k) const
    {
        auto it = obj.find(k);
        if (kind != Object || it == obj.end()) throw std::runtime_error("json: no key '" + k + "'");
        return it->second;
    }
    const Json& operator[](std::size_t i) const { return arr.at(i); }
    std::size_t size() const { return kind == Array ? arr.size() : obj.size(); }
};

class JsonParser {
public:
    explicit JsonParser(const std::string& text) : s_(text) {}
    Json parse()
    {
        Json v = value();
        ws();
        if (p_ != s_.size()) fail("trailing characters");
        return v;
    }

private:
    const std::string& s_;
    std::size_t p_ = 0;

    [[noreturn]] void fail(const std::string& what) const
    {
        throw std::runtime_error("json: " + what + " at offset " + std::to_string(p_));
    }
    void ws()
    {
        while (p_ < s_.size() && (s_[p_] == ' ' || s_[p_] == '\n' || s_[p_] == '\r' || s_[p_] == '\t')) ++p_;
    }
    bool eat(const char* word)
    {
        const std::string w(word);
        if (s_.compare(p_, w.size(), w) == 0) { p_ += w.size(); return true; }
        return false;
    }
    std::string string()
    {
        if (s_[p_] != '"') fail("string expected");
        ++p_;
        std::string out;
        while (p_ < s_.size() && s_[p_] != '"') {
            char c = s_[p_++];
            if (c == '\\') {
                if (p_ >= s_.size()) fail("bad escape");
                char e = s_[p_++];
                switch (e) {
                case 'n': out += '\n'; break;
                case 't': out += '\t'; break;
                case 'r': out += '\r'; break;
                case 'b': out += '\b'; break;
                case 'f': out += '\f'; break;
                case 'u': {
                    const unsigned code = unsigned(std::stoul(s_.substr(p_, 4), nullptr, 16));
                    p_ += 4;
                    if (code < 0x80) out += char(code);
                    else if (code < 0x800) { out += char(0xC0 | (code >> 6)); out += char(0x80 | (code & 0x3F)); }
                    else { out += char(0xE0 | (code >> 12)); out += char(0x80 | ((code >> 6) & 0x3F)); out += char(0x80 | (code & 0x3F)); }
                    break;
                }
                default: out += e;
                }
            } else {
                out += c;
            }
        }
        if (p_ >= s_.size()) fail("unterminated string");
        ++p_;
        return out;
    }
    Json value()
    {
        ws();
        if (p_ >= s_.size()) fail("value expected");
        Json v;
        const char c = s_[p_];
        if (c == '{') {
            v.kind = Json::Object;
            ++p_;
            ws();
            if (s_[p_] == '}') { ++p_; return v; }
            for (;;) {
                ws();
                std::string k = string();
                ws();
                if (s_[p_++] != ':') fail("':' expected");
                v.obj[k] = value();
                ws();
                if (s_[p_] == ',') { ++p_; continue; }
                if (s_[p_] == '}') { ++p_; return v; }
                fail("',' or '}' expected");
            }
        }
        if (c == '[') {
            v.kind = Json::Array;
            ++p_;
            ws();
            if (s_[p_] == ']') { ++p_; return v; }
            for (;;) {
                v.arr.push_back(value());
                ws();
                if (s_[p_] == ',') { ++p_; continue; }
                if (s_[p_] == ']') { ++p_; return v; }
                fail("',' or ']' expected");
            }
        }
        if (c == '"') { v.kind = Json::String; v.str = string(); return v; }
        if (eat("true")) { v.kind = Json::Bool; v.b = true; return v; }
        if (eat("false")) { v.kind = Json::Bool; return v; }
        if (eat("null")) return v;
        if (eat("NaN")) { v.kind = Json::Number; v.num = std::numeric_limits<double>::quiet_NaN(); return v; }
        std::size_t used = 0;
        try {
            v.num = std::stod(s_.substr(p_, 64), &used);
        } catch (const std::exception&) {
            fail("number expected");
        }
        v.kind = Json::Number;
        p_ += used;
        return v;
    }
};

inline Json parse_json(const std::string& text) { return JsonParser(text).parse(); }

} // namespace isodel::test
