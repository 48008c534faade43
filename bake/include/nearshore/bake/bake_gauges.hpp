#pragma once
// Wave gauges: the surface elevation at named points, sampled during a bake and written as
// gauges.csv (docs/commands/bake.md): a header `t,<name1>,<name2>,...` then one row per sample,
// time in seconds and elevations in metres, numbers printed in full precision (%.9g) so a resumed
// bake writes byte-identical files. Beside it (docs/formats/sequence.md, "Gauges"):
//   gauge_fluxes.csv      the depth-integrated flux (P, Q) at each gauge with each sample: header
//                         `t,<name1>.flux_x_m2_s,<name1>.flux_y_m2_s,...`, m^2/s, %.9g;
//   gauge_statistics.csv  one row per gauge: Hm0, Tp, Tm01, Tm02 and the waves' peak and mean
//                         direction and spread (ocean/record_spectrum.hpp, the PUV method) over the
//                         records from the spin-up on.
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "nearshore/bake/bake_case.hpp"
#include "nearshore/ocean/record_spectrum.hpp"

namespace nearshore::bake {

/// A gauge table in memory: one column per gauge (elevation_m[gauge][sample]).
/// The fluxes are empty where they were not read (a gauges.csv without its gauge_fluxes.csv).
struct GaugeTable {
  std::vector<std::string> names;
  std::vector<double> time_s;
  std::vector<std::vector<double>> elevation_m;
  std::vector<std::vector<double>> flux_x_m2_s, flux_y_m2_s;  ///< [gauge][sample], east and north
};

/// The sea-state parameters and directions of one gauge's records (gauge_statistics.csv).
struct GaugeStatistics {
  std::string name;
  double x_m = 0.0, y_m = 0.0;  ///< the gauge's position as the case gives it (the grid's CRS, metres)
  double from_time_s = 0.0, to_time_s = 0.0;
  int samples = 0;
  ocean::DirectionalRecordSpectrum spectrum;
};

inline constexpr const char* kGaugeFluxesFile = "gauge_fluxes.csv";
inline constexpr const char* kGaugeStatisticsFile = "gauge_statistics.csv";

/// How many of the table's samples lie at or after `from_time_s`.
std::size_t gauge_sample_count_from(const GaugeTable& table, double from_time_s);

class GaugeRecorder {
 public:
  explicit GaugeRecorder(std::vector<GaugeSpec> gauges);
  /// Appends one row: the solver's surface elevation and flux at every gauge (bilinear) at `time_s`.
  void record(double time_s, const boussinesq::BoussinesqSolver& solver);
  const GaugeTable& table() const { return table_; }
  /// Writes gauges.csv atomically. Throws nearshore::Error naming the file on failure.
  void write_csv(const std::filesystem::path& file) const;
  /// Writes gauge_fluxes.csv atomically (same rows as gauges.csv).
  void write_fluxes_csv(const std::filesystem::path& file) const;
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

/// Reads gauge_fluxes.csv into `table` (read from the gauges.csv beside it): its gauges and times
/// must be the table's. Throws nearshore::Error naming the file otherwise.
void read_gauge_fluxes_csv(const std::filesystem::path& file, GaugeTable& table);

/// The statistics of every gauge over its samples from `from_time_s` on (the spin-up left out),
/// each from ocean::directional_record_spectrum with its default segments. Throws nearshore::Error
/// when fewer than 16 samples remain, the samples are not evenly spaced or the table has no fluxes.
std::vector<GaugeStatistics> gauge_statistics(const GaugeTable& table, const std::vector<GaugeSpec>& gauges,
                                              double from_time_s);

/// Writes gauge_statistics.csv atomically: a header, then one row per gauge (format in
/// docs/formats/sequence.md). Directions in two conventions: `*_direction_deg` the direction the
/// waves travel towards, counter-clockwise from east (the case files' direction_deg), and
/// `*_direction_from_deg` the compass direction they come from, clockwise from north (buoys, SWAN's
/// nautical convention); north and east are the grid's (its CRS's axes). NaN where undefined.
void write_gauge_statistics_csv(const std::filesystem::path& file, const std::vector<GaugeStatistics>& statistics);

/// The column of gauge `name`; throws nearshore::Error naming the file's gauges if absent.
const std::vector<double>& gauge_column(const GaugeTable& table, const std::string& name);

}  // namespace nearshore::bake
