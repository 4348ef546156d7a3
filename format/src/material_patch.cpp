// MATERIAL_EXTENSIONS (format 1.3, spec section 18): the payload, and the strict check of its JSON
// patch (RFC 8259 grammar, the limits of spec 18.2, the patch's fixed shape, texture references).
//
// The checker parses the patch once into a small tree of values (objects keep their members in
// text order with the offset of each value), then walks the tree for the shape and the texture
// references. Everything is bounded by the patch's length (at most one packet) and a nesting depth
// of 32, so hostile text costs linear time and memory.
#include "bytes.h"
#include "ellicast/format.h"

#include <functional>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <set>

namespace ellicast {

using namespace detail;

namespace {

constexpr size_t kMaxPatchDepth = 32;

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

void append_utf8(std::string& out, uint32_t cp) {
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
        if (depth > kMaxPatchDepth) return false;
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
        if (depth > kMaxPatchDepth) return false;
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

bool ends_with_texture(std::string_view name) {
    constexpr std::string_view kSuffix = "Texture";
    return name.size() >= kSuffix.size() && name.substr(name.size() - kSuffix.size()) == kSuffix;
}

// Rule 8, the shape: only the named members, each (and every extension object) an object.
bool extensions_ok(const JsonValue& v) {
    if (v.kind != JsonValue::Object) return false;
    for (const auto& [name, ext] : v.members)
        if (ext->kind != JsonValue::Object) return false;
    return true;
}

bool core_texture_info_ok(const JsonValue& v) {
    if (v.kind != JsonValue::Object) return false;
    for (const auto& [name, member] : v.members)
        if (name != "extensions" || !extensions_ok(*member)) return false;
    return true;
}

bool shape_ok(const JsonValue& patch) {
    if (patch.kind != JsonValue::Object) return false;
    for (const auto& [name, member] : patch.members) {
        if (name == "extensions") {
            if (!extensions_ok(*member)) return false;
        } else if (name == "normalTexture" || name == "occlusionTexture" || name == "emissiveTexture") {
            if (!core_texture_info_ok(*member)) return false;
        } else if (name == "pbrMetallicRoughness") {
            if (member->kind != JsonValue::Object) return false;
            for (const auto& [inner, value] : member->members) {
                if (inner == "extensions") {
                    if (!extensions_ok(*value)) return false;
                } else if (inner == "baseColorTexture" || inner == "metallicRoughnessTexture") {
                    if (!core_texture_info_ok(*value)) return false;
                } else {
                    return false;
                }
            }
        } else {
            return false;
        }
    }
    return true;
}

// The texture rules of spec 18.2 and the references in document order (spec 18.3). `name` is the
// member whose value `v` is (empty for an array element or the patch itself).
bool walk_references(const JsonValue& v, std::string_view name, const std::string& path,
                     std::vector<PatchTextureReference>* out) {
    if (v.kind == JsonValue::Object) {
        const JsonValue* index = v.member("index");
        const bool reference = index && ends_with_texture(name);
        const bool transform = name == "KHR_texture_transform";
        if (reference || transform) {
            if (const JsonValue* tc = v.member("texCoord"); tc && !(tc->kind == JsonValue::Number && tc->text == "0"))
                return false;
        }
        if (reference) {
            const std::string& digits = index->text;
            if (index->kind != JsonValue::Number || digits.empty() || digits.size() > 5 ||
                digits.find_first_not_of("0123456789") != std::string::npos || (digits.size() > 1 && digits[0] == '0'))
                return false;
            const unsigned long value = std::strtoul(digits.c_str(), nullptr, 10);
            if (value > 65534) return false;
            if (out) out->push_back({path, uint16_t(value), index->offset, index->length});
        }
        for (const auto& [member_name, member] : v.members)
            if (!walk_references(*member, member_name, path.empty() ? member_name : path + "/" + member_name, out))
                return false;
    } else if (v.kind == JsonValue::Array) {
        for (size_t k = 0; k < v.elements.size(); ++k)
            if (!walk_references(*v.elements[k], {}, path + "/" + std::to_string(k), out)) return false;
    }
    return true;
}

}  // namespace

Error check_material_patch(std::string_view patch, std::vector<PatchTextureReference>* references) {
    if (!is_valid_utf8(patch)) return Error::MalformedPayload;  // rule 2
    Parser parser(patch);
    std::unique_ptr<JsonValue> root = parser.document();  // rules 3..7
    if (!root || root->kind != JsonValue::Object || !shape_ok(*root)) return Error::MalformedPayload;
    std::vector<PatchTextureReference> found;
    if (!walk_references(*root, {}, {}, &found)) return Error::MalformedPayload;
    // Members are walked in text order, so the references come in the order of their '{'.
    if (references) *references = std::move(found);
    return Error::Ok;
}

std::string remap_patch_textures(std::string_view patch, const std::vector<PatchTextureReference>& references,
                                 const std::function<uint16_t(uint16_t)>& map) {
    std::string out;
    size_t at = 0;
    for (const auto& r : references) {  // document order is text order of the index digits too
        out.append(patch.substr(at, r.index_offset - at));
        out += std::to_string(map(r.texture));
        at = r.index_offset + r.index_length;
    }
    out.append(patch.substr(at));
    return out;
}

std::vector<uint8_t> encode_material_extensions_payload(const MaterialExtensions& m) {
    std::vector<uint8_t> out(4 + m.patch.size());
    out[0] = uint8_t(m.index), out[1] = uint8_t(m.index >> 8);
    out[2] = uint8_t(m.material_count), out[3] = uint8_t(m.material_count >> 8);
    std::copy(m.patch.begin(), m.patch.end(), out.begin() + 4);
    return out;
}

Error decode_material_extensions_payload(std::span<const uint8_t> payload, MaterialExtensions& out) {
    if (payload.size() < kMaterialExtensionsMinSize) return Error::MalformedPayload;
    MaterialExtensions m;
    m.index = uint16_t(payload[0] | (payload[1] << 8));
    m.material_count = uint16_t(payload[2] | (payload[3] << 8));
    if (m.index >= m.material_count) return Error::MalformedPayload;
    m.patch.assign(reinterpret_cast<const char*>(payload.data()) + 4, payload.size() - 4);
    if (check_material_patch(m.patch) != Error::Ok) return Error::MalformedPayload;
    out = std::move(m);
    return Error::Ok;
}

}  // namespace ellicast
