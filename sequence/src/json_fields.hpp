#pragma once
// Typed access to the fields of the sequence folder's JSON files with a message naming the key:
// malformed files must never escape as nlohmann exceptions or crash (the readers are fuzzed).
#include <cmath>
#include <string>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "nearshore/core/error.hpp"

namespace nearshore::sequence {

inline const nlohmann::json& require(const nlohmann::json& object, const char* key, nlohmann::json::value_t type,
                              const std::string& source) {
  const auto it = object.find(key);
  if (it == object.end())
    throw Error(source, fmt::format("has no \"{}\"", key), "the manifest is incomplete; rewrite the sequence");
  const bool number_wanted = type == nlohmann::json::value_t::number_float;
  const bool ok = number_wanted ? it->is_number()
                  : type == nlohmann::json::value_t::number_unsigned ? it->is_number_unsigned() ||
                                                                           (it->is_number_integer() && *it >= 0)
                                                                     : it->type() == type;
  if (!ok)
    throw Error(source, fmt::format("\"{}\" has the wrong type ({})", key, it->type_name()),
                "the manifest is corrupt; rewrite the sequence");
  return *it;
}

inline double require_number(const nlohmann::json& object, const char* key, const std::string& source) {
  const double value = require(object, key, nlohmann::json::value_t::number_float, source).get<double>();
  if (!std::isfinite(value))
    throw Error(source, fmt::format("\"{}\" is not a finite number", key), "rewrite the sequence");
  return value;
}

inline std::string require_string(const nlohmann::json& object, const char* key, const std::string& source) {
  return require(object, key, nlohmann::json::value_t::string, source).get<std::string>();
}

}  // namespace nearshore::sequence
