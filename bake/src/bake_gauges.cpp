#include "nearshore/bake/bake_gauges.hpp"

#include <cmath>
#include <cstdint>
#include <span>
#include <fstream>
#include <istream>
#include <ostream>
#include <sstream>

#include <fmt/core.h>

#include "nearshore/core/atomic_file.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::bake {

using namespace nearshore::ocean;       // spectra, sea states, the deep-water field
using namespace nearshore::boussinesq;  // the solver and its parameters
namespace {

template <class T>
void put(std::ostream& out, const T& value) {
  out.write(reinterpret_cast<const char*>(&value), sizeof(T));
}
template <class T>
T get(std::istream& in, const std::string& subject) {
  T value{};
  if (!in.read(reinterpret_cast<char*>(&value), sizeof(T)))
    throw Error(subject, "ends inside the gauge records (truncated checkpoint)", "bake again from the start with BakeOptions::overwrite instead of BakeOptions::resume");
  return value;
}

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, ',')) {
    if (!field.empty() && field.back() == '\r') field.pop_back();
    fields.push_back(field);
  }
  return fields;
}

}  // namespace

GaugeRecorder::GaugeRecorder(std::vector<GaugeSpec> gauges) : gauges_(std::move(gauges)) {
  for (const GaugeSpec& gauge : gauges_) table_.names.push_back(gauge.name);
  table_.elevation_m.resize(gauges_.size());
  table_.flux_x_m2_s.resize(gauges_.size());
  table_.flux_y_m2_s.resize(gauges_.size());
}

void GaugeRecorder::record(double time_s, const BoussinesqSolver& solver) {
  table_.time_s.push_back(time_s);
  for (std::size_t i = 0; i < gauges_.size(); ++i) {
    table_.elevation_m[i].push_back(solver.surface_elevation_at(gauges_[i].x_m, gauges_[i].y_m));
    const auto [flux_x, flux_y] = solver.flux_at(gauges_[i].x_m, gauges_[i].y_m);
    table_.flux_x_m2_s[i].push_back(flux_x);
    table_.flux_y_m2_s[i].push_back(flux_y);
  }
}

void GaugeRecorder::write_fluxes_csv(const std::filesystem::path& file) const {
  std::string text = "t";
  for (const std::string& name : table_.names) text += fmt::format(",{0}.flux_x_m2_s,{0}.flux_y_m2_s", name);
  text += "\n";
  for (std::size_t sample = 0; sample < table_.time_s.size(); ++sample) {
    text += fmt::format("{:.9g}", table_.time_s[sample]);
    for (std::size_t g = 0; g < table_.names.size(); ++g)
      text += fmt::format(",{:.9g},{:.9g}", table_.flux_x_m2_s[g][sample], table_.flux_y_m2_s[g][sample]);
    text += "\n";
  }
  write_text_atomically(file, text);
}

void GaugeRecorder::write_csv(const std::filesystem::path& file) const {
  std::string text = "t";
  for (const std::string& name : table_.names) text += "," + name;
  text += "\n";
  for (std::size_t sample = 0; sample < table_.time_s.size(); ++sample) {
    text += fmt::format("{:.9g}", table_.time_s[sample]);
    for (const auto& column : table_.elevation_m) text += fmt::format(",{:.9g}", column[sample]);
    text += "\n";
  }
  write_text_atomically(file, text);
}

void GaugeRecorder::save(std::ostream& out) const {
  put<std::uint64_t>(out, table_.names.size());
  for (const std::string& name : table_.names) {
    put<std::uint64_t>(out, name.size());
    out.write(name.data(), static_cast<std::streamsize>(name.size()));
  }
  put<std::uint64_t>(out, table_.time_s.size());
  out.write(reinterpret_cast<const char*>(table_.time_s.data()), static_cast<std::streamsize>(table_.time_s.size() * sizeof(double)));
  for (const auto* columns : {&table_.elevation_m, &table_.flux_x_m2_s, &table_.flux_y_m2_s})
    for (const auto& column : *columns)
      out.write(reinterpret_cast<const char*>(column.data()), static_cast<std::streamsize>(column.size() * sizeof(double)));
}

void GaugeRecorder::load(std::istream& in, const std::string& subject) {
  const auto count = get<std::uint64_t>(in, subject);
  std::vector<std::string> names;
  for (std::uint64_t i = 0; i < count && i < 1000000; ++i) {
    const auto length = get<std::uint64_t>(in, subject);
    if (length > 4096) throw Error(subject, "holds a corrupt gauge name", "bake again from the start with BakeOptions::overwrite instead of BakeOptions::resume");
    std::string name(length, '\0');
    if (!in.read(name.data(), static_cast<std::streamsize>(length)))
      throw Error(subject, "ends inside the gauge names (truncated checkpoint)", "bake again from the start with BakeOptions::overwrite instead of BakeOptions::resume");
    names.push_back(std::move(name));
  }
  if (names != table_.names)
    throw Error(subject, "was written for other gauges than the case now lists",
                "bake again from the start with BakeOptions::overwrite instead of BakeOptions::resume (the case file changed since the checkpoint)");
  const auto samples = get<std::uint64_t>(in, subject);
  if (samples > (1ull << 32)) throw Error(subject, "holds a corrupt sample count", "bake again from the start with BakeOptions::overwrite instead of BakeOptions::resume");
  table_.time_s.resize(samples);
  const auto read_doubles = [&](std::vector<double>& values) {
    values.resize(samples);
    if (!in.read(reinterpret_cast<char*>(values.data()), static_cast<std::streamsize>(samples * sizeof(double))))
      throw Error(subject, "ends inside the gauge samples (truncated checkpoint)", "bake again from the start with BakeOptions::overwrite instead of BakeOptions::resume");
  };
  read_doubles(table_.time_s);
  for (auto* columns : {&table_.elevation_m, &table_.flux_x_m2_s, &table_.flux_y_m2_s})
    for (auto& column : *columns) read_doubles(column);
}

GaugeTable read_gauges_csv(const std::filesystem::path& file) {
  require_readable_file(file, "a gauges.csv written by nearshore bake");
  std::ifstream in(file);
  std::string line;
  GaugeTable table;
  if (!std::getline(in, line)) throw Error(file.string(), "is empty", "bake again: gauges.csv starts with a `t,<gauge>...` header");
  const auto header = split_csv(line);
  if (header.empty() || header[0] != "t")
    throw Error(file.string(), "line 1 does not start with the column `t`", "give a gauges.csv written by nearshore bake");
  table.names.assign(header.begin() + 1, header.end());
  table.elevation_m.resize(table.names.size());
  int line_number = 1;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty()) continue;
    const auto fields = split_csv(line);
    if (fields.size() != header.size())
      throw Error(file.string(), fmt::format("line {} has {} fields, the header {}", line_number, fields.size(), header.size()),
                  "the file is damaged; bake again");
    try {
      table.time_s.push_back(std::stod(fields[0]));
      for (std::size_t i = 1; i < fields.size(); ++i) table.elevation_m[i - 1].push_back(std::stod(fields[i]));
    } catch (const std::exception&) {
      throw Error(file.string(), fmt::format("line {} holds a field that is not a number", line_number), "the file is damaged; bake again");
    }
  }
  return table;
}

void read_gauge_fluxes_csv(const std::filesystem::path& file, GaugeTable& table) {
  GaugeTable read = read_gauges_csv(file);
  std::vector<std::string> expected;
  for (const std::string& name : table.names) {
    expected.push_back(name + ".flux_x_m2_s");
    expected.push_back(name + ".flux_y_m2_s");
  }
  if (read.names != expected)
    throw Error(file.string(), "does not hold the flux_x_m2_s and flux_y_m2_s columns of the gauges of the gauges.csv beside it",
                "give the gauge_fluxes.csv the same bake wrote with that gauges.csv");
  if (read.time_s != table.time_s)
    throw Error(file.string(), "holds other sample times than the gauges.csv beside it",
                "give the gauge_fluxes.csv the same bake wrote with that gauges.csv");
  table.flux_x_m2_s.clear();
  table.flux_y_m2_s.clear();
  for (std::size_t g = 0; g < table.names.size(); ++g) {
    table.flux_x_m2_s.push_back(std::move(read.elevation_m[2 * g]));
    table.flux_y_m2_s.push_back(std::move(read.elevation_m[2 * g + 1]));
  }
}

std::size_t gauge_sample_count_from(const GaugeTable& table, double from_time_s) {
  std::size_t first = 0;
  while (first < table.time_s.size() && table.time_s[first] < from_time_s - 1e-9) ++first;
  return table.time_s.size() - first;
}

std::vector<GaugeStatistics> gauge_statistics(const GaugeTable& table, const std::vector<GaugeSpec>& gauges,
                                              double from_time_s) {
  const char* const subject = "gauge statistics";
  const std::size_t samples = gauge_sample_count_from(table, from_time_s);
  const std::size_t first = table.time_s.size() - samples;
  if (samples < 16)
    throw Error(subject, fmt::format("the gauges hold {} samples from t = {} s on (from_time_s)", samples, from_time_s),
                "record at least 16 samples after the spin-up (time.gauge_interval_s, time.duration_s)");
  const double interval_s = (table.time_s.back() - table.time_s[first]) / static_cast<double>(samples - 1);
  for (std::size_t k = first + 1; k < table.time_s.size(); ++k)
    if (std::abs(table.time_s[k] - table.time_s[k - 1] - interval_s) > 1e-6 * interval_s)
      throw Error(subject, fmt::format("the samples at {} s and {} s are not {} s apart", table.time_s[k - 1], table.time_s[k], interval_s),
                  "give evenly spaced records (a spectrum needs them)");
  if (table.flux_x_m2_s.size() != table.names.size() || table.flux_y_m2_s.size() != table.names.size())
    throw Error(subject, "the gauge table holds no fluxes", "read gauge_fluxes.csv with the gauges (read_gauge_fluxes_csv)");
  std::vector<GaugeStatistics> out;
  for (std::size_t g = 0; g < table.names.size(); ++g) {
    GaugeStatistics row;
    row.name = table.names[g];
    for (const GaugeSpec& spec : gauges)
      if (spec.name == row.name) row.x_m = spec.x_m, row.y_m = spec.y_m;
    row.from_time_s = table.time_s[first];
    row.to_time_s = table.time_s.back();
    row.samples = static_cast<int>(samples);
    const auto tail = [&](const std::vector<double>& column) { return std::span<const double>(column).subspan(first); };
    row.spectrum = ocean::directional_record_spectrum(tail(table.elevation_m[g]), tail(table.flux_x_m2_s[g]),
                                                      tail(table.flux_y_m2_s[g]), interval_s);
    out.push_back(std::move(row));
  }
  return out;
}

void write_gauge_statistics_csv(const std::filesystem::path& file, const std::vector<GaugeStatistics>& statistics) {
  // Compass "from" = 270 - "towards" (counter-clockwise from east), in [0, 360).
  const auto from_deg = [](double towards_deg) {
    const double from = std::fmod(270.0 - towards_deg, 360.0);
    return from < 0.0 ? from + 360.0 : from;
  };
  std::string text =
      "gauge,x_m,y_m,from_time_s,to_time_s,samples,segment_samples,significant_height_hm0_m,peak_period_s,"
      "mean_period_tm01_s,zero_crossing_period_tm02_s,peak_direction_deg,mean_direction_deg,directional_spread_deg,"
      "peak_direction_from_deg,mean_direction_from_deg\n";
  for (const GaugeStatistics& row : statistics) {
    const ocean::DirectionalRecordSpectrum& s = row.spectrum;
    text += fmt::format("{},{:.9g},{:.9g},{:.9g},{:.9g},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}\n",
                        row.name, row.x_m, row.y_m, row.from_time_s, row.to_time_s, row.samples, s.elevation.segment_samples,
                        s.elevation.significant_height_hm0_m, s.elevation.peak_period_s, s.elevation.mean_period_tm01_s,
                        s.elevation.zero_crossing_period_tm02_s, s.peak_direction_deg, s.mean_direction_deg,
                        s.directional_spread_deg, from_deg(s.peak_direction_deg), from_deg(s.mean_direction_deg));
  }
  write_text_atomically(file, text);
}

const std::vector<double>& gauge_column(const GaugeTable& table, const std::string& name) {
  for (std::size_t i = 0; i < table.names.size(); ++i)
    if (table.names[i] == name) return table.elevation_m[i];
  std::string known;
  for (const auto& n : table.names) known += (known.empty() ? "" : ", ") + n;
  throw Error("gauge table", "has no gauge named \"" + name + "\"", "use one of: " + known);
}

}  // namespace nearshore::bake
