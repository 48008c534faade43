// The operability's files (operability.hpp, write_operability): two CSV tables and a bar chart of
// the berths' downtime drawn with nearshore_plot's primitives (axes, ticks, labels).
#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "nearshore/core/atomic_file.hpp"
#include "nearshore/library/operability.hpp"
#include "nearshore/plot/plot.hpp"

namespace nearshore::library {

std::string operability_berths_csv(const OperabilityResult& result);       // operability.cpp
std::string operability_conditions_csv(const OperabilityResult& result);   // operability.cpp

namespace {

// The percent axis's top: the largest bar rounded up to 1, 2, 5 x 10^k, at most 100.
double percent_axis_top(const OperabilityResult& result) {
  double largest = 0.0;
  for (const OperabilityBerth& berth : result.berths) largest = std::max(largest, berth.exceedance_percent);
  if (largest <= 0.0) return 10.0;
  const double magnitude = std::pow(10.0, std::floor(std::log10(largest)));
  for (double nice : {1.0, 2.0, 5.0, 10.0})
    if (nice * magnitude >= largest * (1.0 - 1e-9)) return std::min(100.0, nice * magnitude);
  return 100.0;
}

Image operability_chart(const OperabilityResult& result) {
  const int width = std::max(640, 140 + 110 * static_cast<int>(result.berths.size())), height = 480;
  Image image(width, height);
  const Rgb ink{0.1f, 0.1f, 0.1f}, grid{0.85f, 0.85f, 0.85f}, bar{0.12f, 0.47f, 0.71f};
  const int left = 80, right = width - 30, top = 60, bottom = height - 90;
  draw_text(image, left, 28,
            fmt::format("time Hs exceeds {:.2f} m at each berth (downtime)", result.limit_significant_wave_height_m), ink, 17);
  draw_text(image, left, 48, fmt::format("{} offshore conditions, library {}", result.conditions.size(),
                                         result.library_folder.filename().string()),
            ink, 13);
  const double top_percent = percent_axis_top(result);
  const auto y_of = [&](double percent) { return bottom - (bottom - top) * percent / top_percent; };
  // The y axis: five ticks with grid lines, its label along the side.
  for (int tick = 0; tick <= 5; ++tick) {
    const double percent = top_percent * tick / 5.0;
    const int y = static_cast<int>(y_of(percent));
    draw_line(image, left, y, right, y, grid, 1);
    draw_line(image, left - 5, y, left, y, ink, 1);
    const std::string label = fmt::format("{:g}", percent);
    draw_text(image, left - 9 - text_width_px(label, 13), y + 5, label, ink, 13);
  }
  draw_text(image, 8, top - 12, "exceedance (% of time)", ink, 13);
  draw_line(image, left, top, left, bottom, ink, 1);
  draw_line(image, left, bottom, right, bottom, ink, 1);
  // One bar per berth, its value on top and its name below.
  const int count = std::max<int>(1, static_cast<int>(result.berths.size()));
  const double slot = static_cast<double>(right - left) / count;
  for (int b = 0; b < static_cast<int>(result.berths.size()); ++b) {
    const OperabilityBerth& berth = result.berths[static_cast<std::size_t>(b)];
    const int x0 = static_cast<int>(left + slot * (b + 0.2)), x1 = static_cast<int>(left + slot * (b + 0.8));
    const int y = static_cast<int>(y_of(std::min(berth.exceedance_percent, top_percent)));
    image.fill_rectangle(x0, y, x1, bottom - 1, bar);
    const std::string value = fmt::format("{:.1f} %", berth.exceedance_percent);
    draw_text(image, (x0 + x1 - text_width_px(value, 13)) / 2, y - 6, value, ink, 13);
    draw_text(image, (x0 + x1 - text_width_px(berth.berth.name, 13)) / 2, bottom + 20, berth.berth.name, ink, 13);
  }
  draw_text(image, (left + right - text_width_px("berth", 14)) / 2, bottom + 48, "berth", ink, 14);
  draw_text(image, left, bottom + 72, "Hs at a berth = its agitation coefficient in the nearest state x the condition's Hs",
            ink, 12);
  return image;
}

}  // namespace

std::vector<std::filesystem::path> write_operability(const OperabilityResult& result, const std::filesystem::path& folder) {
  create_output_folder(folder);
  const std::filesystem::path berths = folder / "operability.csv", conditions = folder / "operability_conditions.csv",
                              chart = folder / "operability.png";
  write_text_atomically(berths, operability_berths_csv(result));
  write_text_atomically(conditions, operability_conditions_csv(result));
  write_png(operability_chart(result), chart);
  return {berths, conditions, chart};
}

}  // namespace nearshore::library
