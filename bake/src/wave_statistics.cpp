#include "nearshore/bake/wave_statistics.hpp"

#include <cassert>
#include <cmath>
#include <cstring>
#include <istream>
#include <limits>
#include <ostream>

#include <fmt/core.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "nearshore/core/error.hpp"

namespace nearshore::bake {
namespace {

constexpr float kNeverWet = -std::numeric_limits<float>::infinity();
constexpr float kNoValue = std::numeric_limits<float>::quiet_NaN();
constexpr char kStateMagic[8] = {'w', 'a', 'v', 'e', 's', 't', 'a', '1'};

template <class T>
void write_values(std::ostream& out, const std::vector<T>& values) {
  out.write(reinterpret_cast<const char*>(values.data()), static_cast<std::streamsize>(values.size() * sizeof(T)));
}
template <class T>
bool read_values(std::istream& in, std::vector<T>& values) {
  return static_cast<bool>(
      in.read(reinterpret_cast<char*>(values.data()), static_cast<std::streamsize>(values.size() * sizeof(T))));
}

}  // namespace

WaveStatistics::WaveStatistics(const HarbourGrid& harbour, double dry_depth_m)
    : geometry_(harbour.geometry),
      still_water_depth_m_(harbour.still_water_depth_m.values().begin(), harbour.still_water_depth_m.values().end()),
      dry_depth_m_(dry_depth_m),
      moments_(geometry_.cell_count()),
      maximum_m_(geometry_.cell_count(), kNeverWet) {}

void WaveStatistics::add_step(const Raster<float>& surface_elevation_m) {
  assert(surface_elevation_m.columns() == geometry_.columns && surface_elevation_m.rows() == geometry_.rows);
  const float* eta = surface_elevation_m.data();
  const std::size_t columns = static_cast<std::size_t>(geometry_.columns);
  // Rows in parallel: one pass over the grid per solver step, a few per cent of the step itself.
  tbb::parallel_for(tbb::blocked_range<int>(0, geometry_.rows, 16), [&](const tbb::blocked_range<int>& rows) {
    for (std::size_t cell = rows.begin() * columns; cell < rows.end() * columns; ++cell) {
      moments_.add(cell, eta[cell]);
      // Wet as the solver's moving shoreline counts it (docs/solver.md, "Wet and dry"): total
      // depth above the dry threshold.
      if (still_water_depth_m_[cell] + eta[cell] > dry_depth_m_ && eta[cell] > maximum_m_[cell]) maximum_m_[cell] = eta[cell];
    }
  });
  moments_.end_sample();
}

Raster<float> WaveStatistics::maximum_surface_elevation_m() const {
  Raster<float> map(geometry_.columns, geometry_.rows);
  for (std::size_t cell = 0; cell < maximum_m_.size(); ++cell)
    map.values()[cell] = maximum_m_[cell] == kNeverWet ? kNoValue : maximum_m_[cell];
  return map;
}

Raster<float> WaveStatistics::significant_wave_height_m() const {
  Raster<float> map(geometry_.columns, geometry_.rows, kNoValue);
  if (moments_.sample_count() == 0) return map;
  for (std::size_t cell = 0; cell < moments_.cell_count(); ++cell)
    if (still_water_depth_m_[cell] > 0) map.values()[cell] = static_cast<float>(moments_.significant_wave_height_m(cell));
  return map;
}

Raster<float> WaveStatistics::mean_surface_elevation_m() const {
  Raster<float> map(geometry_.columns, geometry_.rows, kNoValue);
  if (moments_.sample_count() == 0) return map;
  for (std::size_t cell = 0; cell < moments_.cell_count(); ++cell)
    if (still_water_depth_m_[cell] > 0) map.values()[cell] = static_cast<float>(moments_.mean_m(cell));
  return map;
}

Raster<float> WaveStatistics::runup_line_water_level_m() const {
  Raster<float> map(geometry_.columns, geometry_.rows, kNoValue);
  const int columns = geometry_.columns, rows = geometry_.rows;
  const auto ever_wet = [&](int column, int row) {
    return maximum_m_[static_cast<std::size_t>(row) * columns + column] != kNeverWet;
  };
  for (int row = 0; row < rows; ++row)
    for (int column = 0; column < columns; ++column) {
      if (!ever_wet(column, row)) continue;
      // The grid's edge is no front: the water goes on beyond it.
      const bool touches_dry = (column > 0 && !ever_wet(column - 1, row)) || (column + 1 < columns && !ever_wet(column + 1, row)) ||
                               (row > 0 && !ever_wet(column, row - 1)) || (row + 1 < rows && !ever_wet(column, row + 1));
      if (touches_dry) map(column, row) = maximum_m_[static_cast<std::size_t>(row) * columns + column];
    }
  return map;
}

std::optional<RunupPoint> WaveStatistics::highest_runup() const {
  std::optional<RunupPoint> highest;
  for (int row = 0; row < geometry_.rows; ++row)
    for (int column = 0; column < geometry_.columns; ++column) {
      const std::size_t cell = static_cast<std::size_t>(row) * geometry_.columns + column;
      if (still_water_depth_m_[cell] > 0 || maximum_m_[cell] == kNeverWet) continue;
      if (highest && maximum_m_[cell] <= highest->water_level_m) continue;
      highest = RunupPoint{geometry_.cell_centre_x_m(column), geometry_.cell_centre_y_m(row), column, row, maximum_m_[cell],
                           -static_cast<double>(still_water_depth_m_[cell])};
    }
  return highest;
}

void WaveStatistics::save(std::ostream& out) const {
  const std::int32_t size[2] = {geometry_.columns, geometry_.rows};
  const std::int64_t steps = moments_.sample_count();
  out.write(kStateMagic, sizeof kStateMagic);
  out.write(reinterpret_cast<const char*>(size), sizeof size);
  out.write(reinterpret_cast<const char*>(&steps), sizeof steps);
  write_values(out, moments_.sums_m());
  write_values(out, moments_.sums_of_squares_m2());
  write_values(out, maximum_m_);
}

void WaveStatistics::load(std::istream& in, const std::string& source) {
  char magic[sizeof kStateMagic] = {};
  std::int32_t size[2] = {};
  std::int64_t steps = 0;
  const auto broken = [&](const std::string& problem) {
    return Error(source, "holds no usable wave statistics: " + problem,
                 "bake again from the start with BakeOptions::overwrite instead of BakeOptions::resume");
  };
  if (!in.read(magic, sizeof magic) || std::memcmp(magic, kStateMagic, sizeof magic) != 0)
    throw broken("their header is missing");
  if (!in.read(reinterpret_cast<char*>(size), sizeof size) || !in.read(reinterpret_cast<char*>(&steps), sizeof steps))
    throw broken("the file ends inside their header");
  if (size[0] != geometry_.columns || size[1] != geometry_.rows || steps < 0)
    throw broken(fmt::format("they cover {} x {} cells over {} steps but the grid is {} x {}", size[0], size[1], steps,
                             geometry_.columns, geometry_.rows));
  if (!read_values(in, moments_.sums_m()) || !read_values(in, moments_.sums_of_squares_m2()) || !read_values(in, maximum_m_))
    throw broken("the file ends inside their maps");
  moments_.set_sample_count(static_cast<long>(steps));
}

}  // namespace nearshore::bake
