#include "nearshore/runtime/harbour_site.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "nearshore/core/elevation_moments.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/statistics.hpp"

namespace nearshore::runtime {

namespace {
// The widest sponge of the bake (manifest solver.sponges) on a side other than `source_side`.
double widest_sponge_m(const nlohmann::json& solver, const std::string& source_side) {
  double widest = 0.0;
  if (!solver.is_object() || !solver.contains("sponges") || !solver["sponges"].is_array()) return widest;
  for (const nlohmann::json& sponge : solver["sponges"]) {
    if (!sponge.is_object() || !sponge.contains("width_m") || !sponge["width_m"].is_number()) continue;
    const std::string side = sponge.contains("side") && sponge["side"].is_string() ? sponge["side"].get<std::string>() : "";
    if (side == source_side) continue;
    widest = std::max(widest, sponge["width_m"].get<double>());
  }
  return widest;
}
}  // namespace

HarbourSite read_harbour_site(const sequence::SequenceReader& reader, double edge_fade_m, sequence::Verify verify) {
  HarbourSite site;
  site.harbour = reader.read_harbour_grid(verify);
  const GridGeometry& geometry = reader.geometry();
  site.width_m = geometry.width_m();  // columns dx, rows dy (rectangular cells alike)
  site.height_m = geometry.height_m();
  site.frame_interval_s = reader.frame_interval_s();
  const sequence::SequenceManifest& manifest = reader.manifest();
  std::string source_side;
  if (manifest.deep_water) {
    site.choppiness = manifest.deep_water->choppiness;
    if (manifest.deep_water->coupling && manifest.deep_water->coupling->blending) {
      const sequence::DeepWaterBlendingRecord& blending = *manifest.deep_water->coupling->blending;
      source_side = blending.side;
      site.source_axis = blending.axis == "x" ? 0 : 1;
      site.inward_sign = blending.side == "east" || blending.side == "north" ? -1.0 : 1.0;
      site.source_line_m = blending.source_line_m;
      site.blend_start_m = blending.start_m;
      site.blend_width_m = blending.width_m;
    }
  }
  if (const std::optional<double> dry_depth_m = manifest.recorded_dry_depth_m()) site.dry_depth_m = *dry_depth_m;
  const double smaller_side_m = std::min(site.width_m, site.height_m);
  if (edge_fade_m >= 0.0) {
    site.edge_fade_m = edge_fade_m;
  } else {
    double fade = widest_sponge_m(manifest.solver, source_side);
    if (!(fade > 0.0)) fade = site.blend_width_m;
    if (!(fade > 0.0)) fade = 0.05 * smaller_side_m;
    site.edge_fade_m = std::min(fade, 0.25 * smaller_side_m);
  }
  if (source_side.empty()) {
    // No maker record: the south edge fades like the others.
    site.source_axis = 1;
    site.inward_sign = 1.0;
    site.source_line_m = 0.0;
    site.blend_start_m = 0.0;
    site.blend_width_m = site.edge_fade_m;
  }
  site.relative_wave_height = relative_wave_height(reader, site);
  return site;
}

Raster<float> relative_wave_height(const sequence::SequenceReader& reader, const HarbourSite& site) {
  const HarbourGrid& grid = site.harbour;
  const int columns = grid.geometry.columns, rows = grid.geometry.rows;
  const int frames = reader.frame_count();
  if (columns < 1 || rows < 1 || frames < 8) return {};
  const auto is_water = [&](int i, int j) {
    return grid.land(i, j) == 0 && grid.porosity(i, j) >= 0.99f && grid.still_water_depth_m(i, j) > 0.f;
  };
  // 1. Hs per cell over frames spread evenly (the first and the last included).
  const int count = std::min(frames, kRelativeWaveHeightFrames);
  ElevationMoments moments(std::size_t(columns) * rows);
  sequence::Frame frame;
  const sequence::ChannelSelection elevation_only{true, false, false, false};
  for (int k = 0; k < count; ++k) {
    const int index = count > 1 ? int(std::lround(double(k) * (frames - 1) / (count - 1))) : 0;
    try {
      reader.read_frame_into(index, frame, elevation_only);
    } catch (const Error&) {
      continue;  // a damaged frame: the streaming engine says so when it reaches it
    }
    const Raster<float>& eta = frame.surface_elevation_m;
    if (eta.columns() != columns || eta.rows() != rows) continue;
    for (std::size_t cell = 0; cell < moments.cell_count(); ++cell)
      moments.add(cell, std::isfinite(eta.data()[cell]) ? double(eta.data()[cell]) : 0.0);
    moments.end_sample();
  }
  if (moments.sample_count() < 8) return {};
  // 2. [1 2 1] x [1 2 1] over the water cells only (a quay's other side is another sea).
  const float nan = std::numeric_limits<float>::quiet_NaN();
  Raster<float> hs(columns, rows);
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) {
      if (!is_water(i, j)) {
        hs(i, j) = nan;
        continue;
      }
      double sum = 0.0, weights = 0.0;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int ii = i + di, jj = j + dj;
          if (ii < 0 || jj < 0 || ii >= columns || jj >= rows || !is_water(ii, jj)) continue;
          const double w = (2 - std::abs(di)) * (2 - std::abs(dj));
          sum += w * moments.significant_wave_height_m(std::size_t(jj) * columns + ii);
          weights += w;
        }
      hs(i, j) = float(sum / weights);
    }
  // 3. The incident sea: the median Hs on the line where the baked weight reaches 1.
  const double along_m = site.source_line_m + site.inward_sign * (site.blend_start_m + site.blend_width_m);
  const bool along_y = site.source_axis == 1;
  const double spacing_m = along_y ? grid.geometry.spacing_y_m() : grid.geometry.spacing_x_m();
  const int lines = along_y ? rows : columns, across = along_y ? columns : rows;
  const int line = std::clamp(int(std::floor(along_m / spacing_m)), 0, lines - 1);
  std::vector<double> on_line;
  for (int k = 0; k < across; ++k) {
    const float value = along_y ? hs(k, line) : hs(line, k);
    if (std::isfinite(value)) on_line.push_back(value);
  }
  const double incident_m = median_of(std::move(on_line));
  if (!(incident_m > 1e-3)) return {};
  for (float& value : hs.values()) value = std::isfinite(value) ? float(value / incident_m) : nan;
  return hs;
}

}  // namespace nearshore::runtime
