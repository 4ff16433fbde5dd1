#pragma once
// Header-only minimal JSON reader, enough for ../shared/data/manifest.json in the verify tests and
// the corpus runner (no JSON library is among the project's Debian dependencies). Strict enough
// to reject garbage, not a validator: \u escapes outside ASCII become '?'.
#include <cstdlib>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace isodel::minijson {

struct Value {
    enum Type { Null, Bool, Number, String, Array, Object } type = Null;
    bool b = false;
    double num = 0.0;
    std::string str;
    std::vector<Value> arr;
    std::map<std::string, Value> obj;

    bool has(const std::string& k) const { return type == Object && obj.count(k) && obj.at(k).type != Null; }
    const Value& operator[](const std::string& k) const
    {
        static const Value null;
        if (type != Object) return null;
        auto it = obj.find(k);
        return it == obj.end() ? null : it->second;
    }
    const Value& operator[](std::size_t i) const { return arr.at(i); }
    std::size_t size() const { return type == Array ? arr.size() : obj.size(); }
    std::string as_string(const std::string& dflt = "") const { return type == String ? str : dflt; }
    double as_number(double dflt = 0.0) const { return type == Number ? num : dflt; }
};

class Parser {
public:
    explicit Parser(const std::string& text) : s_(text) {}
    Value parse()
    {
        Value v = value();
        ws();
        if (i_ != s_.size()) fail("trailing characters");
        return v;
    }

private:
    [[noreturn]] void fail(const char* what) { throw std::runtime_error(std::string("json: ") + what + " at " + std::to_string(i_)); }
    void ws()
    {
        while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\n' || s_[i_] == '\r' || s_[i_] == '\t')) ++i_;
    }
    bool lit(const char* w)
    {
        std::size_t n = std::char_traits<char>::length(w);
        if (s_.compare(i_, n, w) != 0) return false;
        i_ += n;
        return true;
    }
    std::string string()
    {
        if (s_[i_] != '"') fail("expected string");
        ++i_;
        std::string out;
        while (i_ < s_.size() && s_[i_] != '"') {
            char c = s_[i_++];
            if (c == '\\') {
                if (i_ >= s_.size()) fail("bad escape");
                char e = s_[i_++];
                switch (e) {
                case 'n': out += '\n'; break;
                case 't': out += '\t'; break;
                case 'r': out += '\r'; break;
                case 'b': out += '\b'; break;
                case 'f': out += '\f'; break;
                case 'u': {
                    const long cp = std::strtol(s_.substr(i_, 4).c_str(), nullptr, 16);
                    out += cp < 128 ? char(cp) : '?';
                    i_ += 4;
                    break;
                }
                default: out += e;
                }
            } else {
                out += c;
            }
        }
        if (i_ >= s_.size()) fail("unterminated string");
        ++i_;
        return out;
    }
    Value value()
    {
        ws();
        if (i_ >= s_.size()) fail("unexpected end");
        Value v;
        const char c = s_[i_];
        if (c == '{') {
            v.type = Value::Object;
            ++i_;
            ws();
            if (s_[i_] == '}') { ++i_; return v; }
            for (;;) {
                ws();
                std::string k = string();
                ws();
                if (s_[i_++] != ':') fail("expected ':'");
                v.obj[k] = value();
                ws();
                if (s_[i_] == ',') { ++i_; continue; }
                if (s_[i_] == '}') { ++i_; return v; }
                fail("expected ',' or '}'");
            }
        }
        if (c == '[') {
            v.type = Value::Array;
            ++i_;
            ws();
            if (s_[i_] == ']') { ++i_; return v; }
            for (;;) {
                v.arr.push_back(value());
                ws();
                if (s_[i_] == ',') { ++i_; continue; }
                if (s_[i_] == ']') { ++i_; return v; }
                fail("expected ',' or ']'");
            }
        }
        if (c == '"') {
            v.type = Value::String;
            v.str = string();
            return v;
        }
        if (lit("true")) { v.type = Value::Bool; v.b = true; return v; }
        if (lit("false")) { v.type = Value::Bool; return v; }
        if (lit("null")) return v;
        if (lit("NaN")) { v.type = Value::Number; v.num = 0.0 / 0.0; return v; }
        char* end = nullptr;
        v.num = std::strtod(s_.c_str() + i_, &end);
        if (end == s_.c_str() + i_) fail("unexpected character");
        v.type = Value::Number;
        i_ = std::size_t(end - s_.c_str());
        return v;
    }
    const std::string& s_;
    std::size_t i_ = 0;
};

inline Value parse(const std::string& text) { return Parser(text).parse(); }

} // namespace isodel::minijson
