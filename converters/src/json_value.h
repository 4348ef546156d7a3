// Internal to converters: tinygltf's JSON values to and from nlohmann::json, for what travels as JSON
// text (a material's patch, format 1.3, spec 18; an element's extras, format 1.12, spec 28).
#pragma once

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

namespace ellicast::json_value {

// A null (or binary) value becomes JSON null.
nlohmann::json to_json(const tinygltf::Value& v);
// Integers that fit an int stay integers, the others become doubles.
tinygltf::Value to_value(const nlohmann::json& j);

}  // namespace ellicast::json_value
