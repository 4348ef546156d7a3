// Internal to the format library: the strict JSON reader of spec 18.2 (rules 2..7: RFC 8259 grammar,
// surrogate pairs, finite numbers, unique member names, nesting depth 32), shared by the material
// patches of format 1.3 (material_patch.cpp) and the extras texts of format 1.12 (extras.cpp).
//
// The reader parses a text once into a small tree of values (objects keep their members in text
// order with the offset of each value). Everything is bounded by the text's length and the nesting
// depth, so hostile text costs linear time and memory.
#pragma once

#include <cmath>
#include <cstdlib>
#include <memory>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace ellicast::detail {

inline constexpr size_t kMaxJsonDepth = 32;

struct JsonValue {
    enum Kind { Null, Bool, Number, String, Array, Object } kind = Null;
    size_t offset = 0;                 // where the value starts in the text
    size_t length = 0;                 // its length in the text (numbers: the token)
    std::string text;                  // String: the decoded string; Number: the token
    std::vector<std::pair<std::string, std::unique_ptr<JsonValue>>> members;  // Object, in text order
    std::vector<std::unique_ptr<JsonValue>> elements;                          // Array
    const JsonValue* member(std::string_view name) const {
        for (const auto& [n, v] : members)
            if (n == name) return v.get();
        return nullptr;
    }
};

inline void append_utf8(std::string& out, uint32_t cp) {
    if (cp < 0x80) {
        out += char(cp);
    } else if (cp < 0x800) {
        out += char(0xC0 | (cp >> 6));
        out += char(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
        out += char(0xE0 | (cp >> 12));
        out += char(0x80 | ((cp >> 6) & 0x3F));
        out += char(0x80 | (cp & 0x3F));
    } else {
        out += char(0xF0 | (cp >> 18));
        out += char(0x80 | ((cp >> 12) & 0x3F));
        out += char(0x80 | ((cp >> 6) & 0x3F));
        out += char(0x80 | (cp & 0x3F));
    }
}

class Parser {
public:
    explicit Parser(std::string_view text) : s_(text) {}

    std::unique_ptr<JsonValue> document() {
        skip_ws();
        auto v = value(1);
        if (!v) return nullptr;
        skip_ws();
        if (i_ != s_.size()) return nullptr;  // a second value, or anything after the first
        return v;
    }

private:
    std::string_view s_;
    size_t i_ = 0;

    void skip_ws() {
        while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\n' || s_[i_] == '\r')) ++i_;
    }
    bool literal(std::string_view word) {
        if (s_.substr(i_, word.size()) != word) return false;
        i_ += word.size();
        return true;
    }

    std::unique_ptr<JsonValue> value(size_t depth) {
        if (i_ >= s_.size()) return nullptr;
        auto v = std::make_unique<JsonValue>();
        v->offset = i_;
        const char c = s_[i_];
        bool ok;
        if (c == '{') v->kind = JsonValue::Object, ok = object(*v, depth);
        else if (c == '[') v->kind = JsonValue::Array, ok = array(*v, depth);
        else if (c == '"') v->kind = JsonValue::String, ok = string(v->text);
        else if (c == 't') v->kind = JsonValue::Bool, ok = literal("true");
        else if (c == 'f') v->kind = JsonValue::Bool, ok = literal("false");
        else if (c == 'n') v->kind = JsonValue::Null, ok = literal("null");
        else v->kind = JsonValue::Number, ok = number(v->text);
        if (!ok) return nullptr;
        v->length = i_ - v->offset;
        return v;
    }

    bool object(JsonValue& v, size_t depth) {
        if (depth > kMaxJsonDepth) return false;
        ++i_;  // '{'
        skip_ws();
        if (i_ < s_.size() && s_[i_] == '}') return ++i_, true;
        std::set<std::string> names;
        for (;;) {
            skip_ws();
            std::string name;
            if (i_ >= s_.size() || s_[i_] != '"' || !string(name)) return false;
            if (!names.insert(name).second) return false;  // rule 6: a name twice
            skip_ws();
            if (i_ >= s_.size() || s_[i_] != ':') return false;
            ++i_;
            skip_ws();
            auto member = value(depth + 1);
            if (!member) return false;
            v.members.emplace_back(std::move(name), std::move(member));
            skip_ws();
            if (i_ < s_.size() && s_[i_] == ',') {
                ++i_;
                continue;
            }
            if (i_ < s_.size() && s_[i_] == '}') return ++i_, true;
            return false;
        }
    }

    bool array(JsonValue& v, size_t depth) {
        if (depth > kMaxJsonDepth) return false;
        ++i_;  // '['
        skip_ws();
        if (i_ < s_.size() && s_[i_] == ']') return ++i_, true;
        for (;;) {
            skip_ws();
            auto element = value(depth + 1);
            if (!element) return false;
            v.elements.push_back(std::move(element));
            skip_ws();
            if (i_ < s_.size() && s_[i_] == ',') {
                ++i_;
                continue;
            }
            if (i_ < s_.size() && s_[i_] == ']') return ++i_, true;
            return false;
        }
    }

    bool hex4(uint32_t& out) {
        if (s_.size() - i_ < 4) return false;
        out = 0;
        for (int k = 0; k < 4; ++k) {
            const char h = s_[i_ + k];
            int d;
            if (h >= '0' && h <= '9') d = h - '0';
            else if (h >= 'a' && h <= 'f') d = h - 'a' + 10;
            else if (h >= 'A' && h <= 'F') d = h - 'A' + 10;
            else return false;
            out = out * 16 + uint32_t(d);
        }
        i_ += 4;
        return true;
    }

    // A string token (the text is well-formed UTF-8 already); `out` gets it decoded.
    bool string(std::string& out) {
        ++i_;  // '"'
        while (i_ < s_.size()) {
            const auto c = uint8_t(s_[i_]);
            if (c == '"') return ++i_, true;
            if (c < 0x20) return false;  // rule 4: an unescaped control character
            if (c != '\\') {
                out += char(c);
                ++i_;
                continue;
            }
            if (++i_ >= s_.size()) return false;
            const char e = s_[i_++];
            switch (e) {
            case '"': out += '"'; break;
            case '\\': out += '\\'; break;
            case '/': out += '/'; break;
            case 'b': out += '\b'; break;
            case 'f': out += '\f'; break;
            case 'n': out += '\n'; break;
            case 'r': out += '\r'; break;
            case 't': out += '\t'; break;
            case 'u': {
                uint32_t cp;
                if (!hex4(cp)) return false;
                if (cp >= 0xDC00 && cp <= 0xDFFF) return false;  // a low surrogate with no high one before it
                if (cp >= 0xD800 && cp <= 0xDBFF) {
                    uint32_t low;
                    if (s_.substr(i_, 2) != "\\u") return false;
                    i_ += 2;
                    if (!hex4(low) || low < 0xDC00 || low > 0xDFFF) return false;
                    cp = 0x10000 + ((cp - 0xD800) << 10) + (low - 0xDC00);
                }
                append_utf8(out, cp);
                break;
            }
            default: return false;
            }
        }
        return false;  // the text ended inside the string
    }

    // A number token: -? (0 | [1-9][0-9]*) (. [0-9]+)? ([eE] [+-]? [0-9]+)?, finite as a binary64.
    bool number(std::string& token) {
        const size_t start = i_;
        auto digits = [&]() {
            const size_t from = i_;
            while (i_ < s_.size() && s_[i_] >= '0' && s_[i_] <= '9') ++i_;
            return i_ > from;
        };
        if (i_ < s_.size() && s_[i_] == '-') ++i_;
        if (i_ < s_.size() && s_[i_] == '0') ++i_;
        else if (!digits()) return false;
        if (i_ < s_.size() && s_[i_] == '.') {
            ++i_;
            if (!digits()) return false;
        }
        if (i_ < s_.size() && (s_[i_] == 'e' || s_[i_] == 'E')) {
            ++i_;
            if (i_ < s_.size() && (s_[i_] == '+' || s_[i_] == '-')) ++i_;
            if (!digits()) return false;
        }
        token.assign(s_.substr(start, i_ - start));
        // Rule 5: finite once rounded to binary64 (strtod rounds to nearest; an overflow gives HUGE_VAL).
        const double value = std::strtod(token.c_str(), nullptr);
        return std::isfinite(value);
    }
};

}  // namespace ellicast::detail
