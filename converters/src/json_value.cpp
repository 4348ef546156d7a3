// tinygltf's JSON values to and from nlohmann::json. See json_value.h.
#include "json_value.h"

#include <climits>

namespace ellicast::json_value {

using json = nlohmann::json;

json to_json(const tinygltf::Value& v) {
    if (v.IsBool()) return v.Get<bool>();
    if (v.IsInt()) return v.Get<int>();
    if (v.IsReal()) return v.Get<double>();
    if (v.IsString()) return v.Get<std::string>();
    if (v.IsArray()) {
        json a = json::array();
        for (size_t i = 0; i < v.ArrayLen(); ++i) a.push_back(to_json(v.Get(int(i))));
        return a;
    }
    if (v.IsObject()) {
        json o = json::object();
        for (const std::string& key : v.Keys()) o[key] = to_json(v.Get(key));
        return o;
    }
    return nullptr;  // null (and binary, which JSON text never holds)
}

tinygltf::Value to_value(const json& j) {
    switch (j.type()) {
    case json::value_t::boolean: return tinygltf::Value(j.get<bool>());
    case json::value_t::number_integer: {
        const int64_t n = j.get<int64_t>();
        return n >= INT_MIN && n <= INT_MAX ? tinygltf::Value(int(n)) : tinygltf::Value(double(n));
    }
    case json::value_t::number_unsigned: {
        const uint64_t n = j.get<uint64_t>();
        return n <= uint64_t(INT_MAX) ? tinygltf::Value(int(n)) : tinygltf::Value(double(n));
    }
    case json::value_t::number_float: return tinygltf::Value(j.get<double>());
    case json::value_t::string: return tinygltf::Value(j.get<std::string>());
    case json::value_t::array: {
        tinygltf::Value::Array a;
        for (const json& e : j) a.push_back(to_value(e));
        return tinygltf::Value(std::move(a));
    }
    case json::value_t::object: {
        tinygltf::Value::Object o;
        for (const auto& [key, e] : j.items()) o[key] = to_value(e);
        return tinygltf::Value(std::move(o));
    }
    default: return tinygltf::Value();
    }
}

}  // namespace ellicast::json_value
