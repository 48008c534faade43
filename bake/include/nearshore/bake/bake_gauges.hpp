#pragma once
// Wave gauges: the surface elevation at named points, sampled during a bake and written as
// gauges.csv (docs/commands/bake.md): a header `t,<name1>,<name2>,...` then one row per sample,
// time in seconds and elevations in metres, numbers printed in full precision (%.9g) so a resumed
// bake writes byte-identical files.
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "nearshore/bake/bake_case.hpp"

namespace nearshore::bake {

/// A gauge table in memory: one column per gauge (elevation_m[gauge][sample]).
struct GaugeTable {
  std::vector<std::string> names;
  std::vector<double> time_s;
  std::vector<std::vector<double>> elevation_m;
};

class GaugeRecorder {
 public:
  explicit GaugeRecorder(std::vector<GaugeSpec> gauges);
  /// Appends one row: the solver's surface elevation at every gauge (bilinear) at `time_s`.
  void record(double time_s, const boussinesq::BoussinesqSolver& solver);
  const GaugeTable& table() const { return table_; }
  /// Writes gauges.csv atomically. Throws nearshore::Error naming the file on failure.
  void write_csv(const std::filesystem::path& file) const;
  /// Binary state for checkpoints (names are checked on load).
  void save(std::ostream& out) const;
  /// Throws nearshore::Error(subject, ...) if the stored gauges differ from this recorder's.
  void load(std::istream& in, const std::string& subject);

 private:
  std::vector<GaugeSpec> gauges_;
  GaugeTable table_;
};

/// Reads a gauges.csv written by GaugeRecorder (or any CSV with a `t` first column and a header).
/// Throws nearshore::Error naming the file and the line for anything else.
GaugeTable read_gauges_csv(const std::filesystem::path& file);

/// The column of gauge `name`; throws nearshore::Error naming the file's gauges if absent.
const std::vector<double>& gauge_column(const GaugeTable& table, const std::string& name);

}  // namespace nearshore::bake
