#pragma once
// A small analytic sequence for the format tests: a progressive wave over a sloping harbour with a
// land strip, fields chosen so every channel differs and north/south or east/west swaps show.
#include <cmath>
#include <exception>
#include <filesystem>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "nearshore/core/error.hpp"
#include "nearshore/sequence/sequence_writer.hpp"

namespace nearshore::sequence::testing {

inline GridGeometry test_geometry(int columns = 37, int rows = 23) {
  GridGeometry geometry;
  geometry.columns = columns;
  geometry.rows = rows;
  geometry.spacing_m = 4.0;
  geometry.origin_x_m = 500000.0;
  geometry.origin_y_m = 4300000.0;
  geometry.projection = {{"kind", "utm"}, {"zone", 51}, {"north", true}};
  return geometry;
}

inline HarbourGrid test_harbour(const GridGeometry& geometry) {
  HarbourGrid harbour = HarbourGrid::open_water(geometry, 8.0f);
  for (int row = 0; row < geometry.rows; ++row)
    for (int column = 0; column < geometry.columns; ++column) {
      harbour.still_water_depth_m(column, row) = 2.0f + 0.25f * static_cast<float>(row);
      if (row >= geometry.rows - 3) {  // a quay along the northern edge
        harbour.land(column, row) = 1;
        harbour.still_water_depth_m(column, row) = -2.0f;
      }
    }
  return harbour;
}

/// Analytic fields of frame `index`: a wave travelling east plus a slow north-south tilt.
struct TestFields {
  Raster<float> eta, p, q, breaking;
  TestFields(const GridGeometry& g, int index) : eta(g.columns, g.rows), p(g.columns, g.rows), q(g.columns, g.rows),
                                                 breaking(g.columns, g.rows) {
    const double t = 0.25 * index;
    for (int row = 0; row < g.rows; ++row)
      for (int column = 0; column < g.columns; ++column) {
        const double phase = 0.21 * column - 1.3 * t;
        eta(column, row) = static_cast<float>(0.6 * std::cos(phase) + 0.01 * row);
        p(column, row) = static_cast<float>(2.5 * std::cos(phase) * (1.0 + 0.02 * row));
        q(column, row) = static_cast<float>(-0.3 * std::sin(phase) + 0.05 * column / g.columns);
        breaking(column, row) = static_cast<float>(row > g.rows / 2 ? 0.5 + 0.5 * std::sin(phase) : 0.0);
      }
  }
  FrameFields fields() const { return {&eta, &p, &q, &breaking}; }
};

inline SequenceDescription test_description(FrameEncoding encoding = {}) {
  SequenceDescription description;
  description.frame_interval_s = 0.25;
  description.first_frame_time_s = 30.0;
  description.seed = 0xfeedbeefcafe1234ULL;  // > 2^53: must survive JSON exactly
  description.loop_period_s = 0;
  description.wave_conditions = {{"kind", "regular"}, {"height_m", 1.2}, {"period_s", 8.0}};
  description.encoding = encoding;
  return description;
}

inline void write_test_sequence(const std::filesystem::path& folder, int frames, FrameEncoding encoding = {},
                                const GridGeometry& geometry = test_geometry()) {
  SequenceWriter writer(folder, test_harbour(geometry), test_description(encoding));
  for (int index = 0; index < frames; ++index) writer.write_frame(index, TestFields(geometry, index).fields());
  writer.finish(frames);
}

/// A fresh, empty folder under the test's working directory.
inline std::filesystem::path fresh_folder(const std::string& name) {
  const std::filesystem::path folder = std::filesystem::current_path() / ("sequence_test_" + name);
  std::filesystem::remove_all(folder);
  return folder;
}

/// The message of the nearshore::Error `action` throws. No error, or an exception of another type,
/// fails the test, and the text returned says which (so a caller's find() fails with it).
inline std::string error_message_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not a nearshore::Error: " << e.what();
    return std::string("not a nearshore::Error: ") + e.what();
  }
  ADD_FAILURE() << "no error";
  return "(no error)";
}

}  // namespace nearshore::sequence::testing
