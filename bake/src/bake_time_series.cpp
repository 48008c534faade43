#include "nearshore/bake/bake_time_series.hpp"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <numeric>
#include <string>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"

namespace nearshore::bake {
namespace {

// Splits on blanks, tabs and commas; parses each field as a double. Returns false on a non-number.
bool parse_row(const std::string& line, std::vector<double>& fields) {
  fields.clear();
  std::size_t position = 0;
  while (position < line.size()) {
    while (position < line.size() && (line[position] == ' ' || line[position] == '\t' || line[position] == ',' ||
                                      line[position] == '\r'))
      ++position;
    if (position >= line.size()) break;
    std::size_t end = position;
    while (end < line.size() && line[end] != ' ' && line[end] != '\t' && line[end] != ',' && line[end] != '\r') ++end;
    double value = 0.0;
    const char* first = line.data() + position;
    if (*first == '+') ++first;
    const auto [pointer, error] = std::from_chars(first, line.data() + end, value);
    if (error != std::errc() || pointer != line.data() + end) return false;
    fields.push_back(value);
    position = end;
  }
  return true;
}

}  // namespace

TimeSeries read_time_series(const std::filesystem::path& file, const TimeSeriesLayout& layout) {
  require_readable_file(file, "a time series table (columns of numbers)");
  const std::string subject = file.string();
  if (layout.elevation_column < 1 || layout.time_column < 0)
    throw Error(subject, "column numbers start at 1", "set elevation_column >= 1 and time_column >= 0 (0 = none)");
  if (layout.time_column == 0 && !(layout.sample_interval_s > 0.0))
    throw Error(subject, "there is no time column and no sample interval",
                "give time_column (1-based) or sample_interval_s > 0");
  std::ifstream in(file);
  TimeSeries series;
  std::string line;
  std::vector<double> fields;
  int line_number = 0;
  bool seen_data = false;
  const int needed = std::max(layout.elevation_column, layout.time_column);
  while (std::getline(in, line)) {
    ++line_number;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    if (!parse_row(line, fields)) {
      if (!seen_data) {  // a header line
        seen_data = true;
        continue;
      }
      throw Error(subject, fmt::format("line {} is not a row of numbers: \"{}\"", line_number, line.substr(0, 60)),
                  "remove or comment out (#) that line");
    }
    seen_data = true;
    if (static_cast<int>(fields.size()) < needed)
      throw Error(subject, fmt::format("line {} has {} columns, column {} is needed", line_number, fields.size(), needed),
                  "check elevation_column and time_column against the file");
    const double t = layout.time_column > 0 ? fields[layout.time_column - 1]
                                            : static_cast<double>(series.time_s.size()) * layout.sample_interval_s;
    if (!series.time_s.empty() && !(t > series.time_s.back()))
      throw Error(subject, fmt::format("line {}: time {} s does not increase (previous {} s)", line_number, t,
                                       series.time_s.back()),
                  "sort the table by time and remove repeated rows");
    series.time_s.push_back(t);
    series.elevation_m.push_back(fields[layout.elevation_column - 1] * layout.elevation_scale_to_m);
  }
  if (series.time_s.size() < 2)
    throw Error(subject, fmt::format("holds {} samples", series.time_s.size()), "give at least two rows of numbers");
  if (layout.remove_mean) {
    const double mean = std::accumulate(series.elevation_m.begin(), series.elevation_m.end(), 0.0) /
                        static_cast<double>(series.elevation_m.size());
    for (double& value : series.elevation_m) value -= mean;
  }
  return series;
}

double interpolated_elevation_m(const TimeSeries& series, double time_s) {
  const std::vector<double>& t = series.time_s;
  const std::vector<double>& z = series.elevation_m;
  if (time_s <= t.front()) return z.front();
  if (time_s >= t.back()) return z.back();
  const std::size_t after = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), time_s) - t.begin());
  const double weight = (time_s - t[after - 1]) / (t[after] - t[after - 1]);
  return z[after - 1] + weight * (z[after] - z[after - 1]);
}

}  // namespace nearshore::bake
