#include "nearshore/bake/bake_gauges.hpp"

#include <cstdint>
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
}

void GaugeRecorder::record(double time_s, const BoussinesqSolver& solver) {
  table_.time_s.push_back(time_s);
  for (std::size_t i = 0; i < gauges_.size(); ++i)
    table_.elevation_m[i].push_back(solver.surface_elevation_at(gauges_[i].x_m, gauges_[i].y_m));
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
  for (const auto& column : table_.elevation_m)
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
  for (auto& column : table_.elevation_m) read_doubles(column);
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

const std::vector<double>& gauge_column(const GaugeTable& table, const std::string& name) {
  for (std::size_t i = 0; i < table.names.size(); ++i)
    if (table.names[i] == name) return table.elevation_m[i];
  std::string known;
  for (const auto& n : table.names) known += (known.empty() ? "" : ", ") + n;
  throw Error("gauge table", "has no gauge named \"" + name + "\"", "use one of: " + known);
}

}  // namespace nearshore::bake
