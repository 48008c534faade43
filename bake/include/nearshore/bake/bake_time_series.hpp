#pragma once
// Surface-elevation time series from plain text tables: the wave maker's `time_series` input, and
// the laboratory gauge records the validation compares against (e.g. Mase & Kirby's r2dNNN.dat,
// one column in centimetres at 20 Hz). Columns are separated by blanks, tabs or commas; lines
// starting with '#' and blank lines are skipped; a first line that is not numeric is a header.
#include <filesystem>
#include <vector>

namespace nearshore::bake {

struct TimeSeriesLayout {
  int elevation_column = 1;        ///< 1-based column of the surface elevation
  int time_column = 0;             ///< 1-based column of the time in seconds; 0 = none (use sample_interval_s)
  double sample_interval_s = 0.0;  ///< spacing of the samples when there is no time column
  double elevation_scale_to_m = 1.0;  ///< e.g. 0.01 for centimetres
  bool remove_mean = false;        ///< subtract the mean of the record (a wave maker must not add mass)
};

struct TimeSeries {
  std::vector<double> time_s, elevation_m;
};

/// The series at `time_s`, linear between samples and held at the first and last beyond them: the
/// still-water level of a tide ([tide] level_m). The series must not be empty.
double interpolated_elevation_m(const TimeSeries& series, double time_s);

/// Reads the table. Throws nearshore::Error(file, "line N: ...", fix) for a short row, a
/// non-numeric value, time not increasing, or fewer than two samples.
TimeSeries read_time_series(const std::filesystem::path& file, const TimeSeriesLayout& layout);

}  // namespace nearshore::bake
