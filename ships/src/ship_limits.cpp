#include "nearshore/ships/ship_limits.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "nearshore/core/error.hpp"

namespace nearshore::ships {

double max_speed_m_s(double length_m, double gravity_m_s2) {
  const double froude_limit = limits::kMaxLengthFroudeNumber * std::sqrt(gravity_m_s2 * std::max(length_m, 0.0));
  return std::min(limits::kSpeed.max, froude_limit);
}

std::string format_value(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return fmt::format("{:.6g}", value);
}

void require_in_range(const std::string& subject, const std::string& field, double value, const ParameterRange& range) {
  if (value >= range.min && value <= range.max) return;  // false for NaN
  throw Error(subject,
              fmt::format("{} = {} is outside [{}, {}] {}: {}", field, format_value(value), format_value(range.min),
                          format_value(range.max), range.unit, range.reason),
              fmt::format("give {} within [{}, {}] {}", field, format_value(range.min), format_value(range.max), range.unit));
}

}  // namespace nearshore::ships
