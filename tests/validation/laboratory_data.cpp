#include "laboratory_data.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/core.h>

#include "nearshore/bake/bake_time_series.hpp"
#include "nearshore/core/error.hpp"

namespace nearshore::validation {
namespace fs = std::filesystem;
namespace {

// Rows of numbers of a whitespace-separated table; '#' lines and blank lines skipped.
std::vector<std::vector<double>> read_rows(const fs::path& file) {
  require_readable_file(file, "a laboratory data table from ../shared/validation");
  std::ifstream in(file);
  std::vector<std::vector<double>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::vector<double> row;
    double value = 0;
    while (fields >> value) row.push_back(value);
    if (!row.empty() && line.find('#') == std::string::npos) rows.push_back(row);
  }
  return rows;
}

}  // namespace

fs::path shared_validation_folder() { return fs::path(NEARSHORE_SHARED_DIR) / "validation"; }

std::vector<BerkhoffPoint> read_berkhoff_transects() {
  const fs::path folder = shared_validation_folder() / "berkhoff_1982";
  std::vector<BerkhoffPoint> points;
  for (int transect = 1; transect <= 5; ++transect)
    for (const auto& row : read_rows(folder / fmt::format("section{}.dat", transect)))
      points.push_back({transect, 1.0 + 2.0 * (transect - 1), row.at(0), row.at(1) / (1000.0 * kBerkhoffIncidentAmplitude_m)});
  for (const auto& row : read_rows(folder / "section678.dat"))
    for (int k = 0; k < 3; ++k)
      points.push_back({6 + k, -row.at(0), -2.0 + 2.0 * k, row.at(1 + k) / (1000.0 * kBerkhoffIncidentAmplitude_m)});
  return points;
}

std::vector<MaseKirbyGauge> read_mase_kirby_gauges() {
  const fs::path folder = shared_validation_folder() / "mase_kirby_1992";
  std::vector<MaseKirbyGauge> gauges;
  for (int depth_mm : {470, 350, 300, 250, 200, 175, 150, 125, 100, 75, 50, 25}) {
    bake::TimeSeriesLayout layout;  // one column, centimetres, 20 Hz (README)
    layout.sample_interval_s = kMaseKirbySampleInterval_s;
    layout.elevation_scale_to_m = 0.01;
    const auto series = bake::read_time_series(folder / fmt::format("r2d{:03d}.dat", depth_mm), layout);
    MaseKirbyGauge gauge;
    gauge.name = fmt::format("h{:03d}", depth_mm);
    gauge.still_water_depth_m = depth_mm / 1000.0;
    gauge.x_m = 10.0 + 20.0 * (0.47 - gauge.still_water_depth_m);
    gauge.elevation_m = series.elevation_m;
    gauges.push_back(std::move(gauge));
  }
  return gauges;
}

std::vector<RunupMeasurement> read_synolakis_runup() {
  std::vector<RunupMeasurement> runs;
  for (const auto& row : read_rows(shared_validation_folder() / "synolakis_1987" / "Lab_runup.txt"))
    if (row.size() >= 3) runs.push_back({row[0], row[1], row[2]});
  return runs;
}

double measured_runup_ratio(const std::vector<RunupMeasurement>& runs, double height_ratio) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& run : runs)
    if (run.height_ratio >= height_ratio / 1.2 && run.height_ratio <= height_ratio * 1.2) {
      const double x = std::log(run.height_ratio), y = std::log(run.runup_ratio);
      n += 1, sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
  if (n < 3) throw Error("Lab_runup.txt", fmt::format("has {} runs near H/d = {}", n, height_ratio), "choose a height ratio the table covers");
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  const double intercept = (sy - slope * sx) / n;
  return std::exp(intercept + slope * std::log(height_ratio));
}

double synolakis_runup_law(double height_ratio, double cot_beta) {
  return 2.831 * std::sqrt(cot_beta) * std::pow(height_ratio, 1.25);
}

std::vector<ProfileSnapshot> read_synolakis_profiles(const std::string& case_name) {
  std::vector<ProfileSnapshot> snapshots;
  const fs::path folder = shared_validation_folder() / "synolakis_1987" / "profiles";
  for (int t : {15, 20, 25, 30, 40, 50, 60, 70}) {
    const fs::path file = folder / fmt::format("{}_t{}.txt", case_name, t);
    if (!fs::exists(file)) continue;
    ProfileSnapshot snapshot;
    snapshot.dimensionless_time = t;
    for (const auto& row : read_rows(file)) {
      snapshot.offshore_distance_ratio.push_back(row.at(0));
      snapshot.elevation_ratio.push_back(row.at(1));
    }
    snapshots.push_back(std::move(snapshot));
  }
  return snapshots;
}

double mean_wave_height_m(const std::vector<double>& time_s, const std::vector<double>& elevation_m, double period_s,
                          double start_s, double end_s) {
  const int periods = static_cast<int>(std::floor((end_s - start_s) / period_s + 1e-9));
  double sum = 0;
  int counted = 0;
  for (int k = 0; k < periods; ++k) {
    const double t0 = end_s - (k + 1) * period_s, t1 = end_s - k * period_s;  // whole periods back from the end
    double high = -1e300, low = 1e300;
    for (std::size_t i = 0; i < time_s.size(); ++i)
      if (time_s[i] >= t0 && time_s[i] < t1) high = std::max(high, elevation_m[i]), low = std::min(low, elevation_m[i]);
    if (high >= low) sum += high - low, ++counted;
  }
  return counted ? sum / counted : 0.0;
}

double mean_level_m(const std::vector<double>& elevation_m, std::size_t first, std::size_t last) {
  double sum = 0;
  for (std::size_t i = first; i < last; ++i) sum += elevation_m[i];
  return sum / static_cast<double>(last - first);
}

double significant_wave_height_m(const std::vector<double>& elevation_m, std::size_t first, std::size_t last) {
  const double mean = mean_level_m(elevation_m, first, last);
  double variance = 0;
  for (std::size_t i = first; i < last; ++i) variance += (elevation_m[i] - mean) * (elevation_m[i] - mean);
  return 4.0 * std::sqrt(variance / static_cast<double>(last - first));
}

double root_mean_square_error(const std::vector<double>& model, const std::vector<double>& data) {
  double sum = 0;
  for (std::size_t i = 0; i < model.size(); ++i) sum += (model[i] - data[i]) * (model[i] - data[i]);
  return std::sqrt(sum / static_cast<double>(model.size()));
}

double sample_at(const std::vector<double>& time_s, const std::vector<double>& values, double t) {
  if (time_s.empty() || !(t >= time_s.front()) || t > time_s.back()) return NAN;
  const auto upper = std::upper_bound(time_s.begin(), time_s.end(), t);
  if (upper == time_s.end()) return values.back();
  const std::size_t i = static_cast<std::size_t>(upper - time_s.begin());
  return values[i - 1] + (t - time_s[i - 1]) / (time_s[i] - time_s[i - 1]) * (values[i] - values[i - 1]);
}

}  // namespace nearshore::validation
