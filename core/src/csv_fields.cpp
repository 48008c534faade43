#include "nearshore/core/csv_fields.hpp"

#include <cmath>
#include <exception>
#include <sstream>

namespace nearshore {

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
}

std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, ',')) fields.push_back(trimmed(field));
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

std::optional<double> finite_number(const std::string& field) {
  if (field.empty()) return std::nullopt;
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(field, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (used != field.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

}  // namespace nearshore
